// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspArguments.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace amrsp
{
namespace harness
{

std::string Arguments::Get(const std::string& key, const std::string& fallback) const
{
  const auto it = Options.find(key);
  return it == Options.end() ? fallback : it->second;
}

double Arguments::GetNumber(const std::string& key, double fallback) const
{
  const auto it = Options.find(key);
  if (it == Options.end())
  {
    return fallback;
  }
  try
  {
    std::size_t used = 0;
    const double v = std::stod(it->second, &used);
    if (used == it->second.size() && std::isfinite(v))
    {
      return v;
    }
  }
  catch (const std::exception&)
  {
  }
  throw UsageError{ "--" + key + " expects a number, got '" + it->second + "'" };
}

std::vector<double> Arguments::GetNumbers(const std::string& key, const std::string& fallback) const
{
  const std::string text = Get(key, fallback);
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
  {
    try
    {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(out.back()))
      {
        throw std::invalid_argument(item);
      }
    }
    catch (const std::exception&)
    {
      throw UsageError{ "--" + key + " expects comma-separated numbers, got '" + text + "'" };
    }
  }
  return out;
}

Arguments ParseArguments(int argc, char** argv, int first,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags)
{
  Arguments a;
  for (int i = first; i < argc; ++i)
  {
    std::string s = argv[i];
    if (s == "-o")
    {
      s = "--output";
    }
    if (s.size() > 2 && s.compare(0, 2, "--") == 0)
    {
      std::string key = s.substr(2), value;
      const std::size_t eq = key.find('=');
      if (eq != std::string::npos)
      {
        value = key.substr(eq + 1);
        key = key.substr(0, eq);
      }
      const bool takesValue =
        std::find(valueOptions.begin(), valueOptions.end(), key) != valueOptions.end();
      const bool isFlag =
        std::find(flags.begin(), flags.end(), key) != flags.end() || key == "help";
      if (!takesValue && !isFlag)
      {
        throw UsageError{ "unknown option --" + key };
      }
      if (takesValue && eq == std::string::npos)
      {
        if (i + 1 >= argc)
        {
          throw UsageError{ "--" + key + " needs a value" };
        }
        value = argv[++i];
      }
      a.Options[key] = takesValue ? value : "1";
    }
    else
    {
      a.Positional.push_back(s);
    }
  }
  return a;
}

Arguments ParseArguments(const std::vector<std::string>& words,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags)
{
  std::vector<std::string> copy = words;
  std::vector<char*> argv;
  for (std::string& w : copy)
  {
    argv.push_back(&w[0]);
  }
  return ParseArguments(static_cast<int>(argv.size()), argv.data(), 0, valueOptions, flags);
}

} // namespace harness
} // namespace amrsp
