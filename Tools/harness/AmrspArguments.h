// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Named options as `amrsp` spells them ("--size 96x96", "--shade=on", "--quiet"): the words the
/// tool's commands, the tests and the benchmark use to describe a render (AmrspRenderOptions.h
/// turns them into RenderSettings; docs/command-line.md lists them).

#include <map>
#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

/// Parsed words: positional arguments and --options without their dashes (a flag maps to "1").
struct Arguments
{
  std::vector<std::string> Positional;
  std::map<std::string, std::string> Options;

  bool Has(const std::string& key) const { return Options.count(key) != 0; }
  std::string Get(const std::string& key, const std::string& fallback) const;
  /// The option as a finite number (`fallback` when absent). Throws UsageError.
  double GetNumber(const std::string& key, double fallback) const;
  /// Comma-separated numbers (`fallback` when the option is absent). Throws UsageError.
  std::vector<double> GetNumbers(const std::string& key, const std::string& fallback) const;
};

/// Thrown for a bad option or option value; Message is one line naming the option.
struct UsageError
{
  std::string Message;
};

/// Parses `argv[first..]`. `valueOptions` lists the options that take a value; any other
/// --option is a flag; "-o" means "--output". Throws UsageError for an unknown option.
Arguments ParseArguments(int argc, char** argv, int first,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags);

/// The same for a list of words, e.g. { "--size", "96x96", "--scale", "linear" }.
Arguments ParseArguments(const std::vector<std::string>& words,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags = {});

} // namespace harness
} // namespace amrsp
