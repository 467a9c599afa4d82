// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The subcommands of the amrsp tool. Each returns the process exit code; errors are printed as
/// one line "amrsp: error: ..." on stderr.

#include "AmrspSinglePass.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

/// Parsed command line: positional arguments and --options (flags map to "1").
struct Arguments
{
  std::vector<std::string> Positional;
  std::map<std::string, std::string> Options;

  bool Has(const std::string& key) const { return Options.count(key) != 0; }
  std::string Get(const std::string& key, const std::string& fallback) const;
  double GetNumber(const std::string& key, double fallback) const;
  /// Comma-separated numbers (`fallback` when the option is absent). Throws UsageError.
  std::vector<double> GetNumbers(const std::string& key, const std::string& fallback) const;
};

/// Thrown for bad command-line usage; what() is one line.
struct UsageError
{
  std::string Message;
};

/// Parses `argv[first..]`. `valueOptions` lists the options that take a value; any other
/// --option is a flag. Throws UsageError for an unknown option.
Arguments ParseArguments(int argc, char** argv, int first,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags);

int RunInspect(int argc, char** argv);
int RunReference(int argc, char** argv);
int RunRender(int argc, char** argv);
int RunBench(int argc, char** argv);

/// The render settings of the view and transfer-function options (docs/design.md, "Rendering
/// conventions"). Maps the scalars of `h` as --scale asks (log10 in place) and returns their
/// display range in `range`. Throws UsageError for bad options.
RenderSettings MakeSettings(Hierarchy& h, const Arguments& a, glm::dvec2* range = nullptr);

/// Maps the scalars for display (--scale `scale`: log10 when "log", or with "auto" for
/// non-negative data whose positive values span more than 3 decades; zeros map to the smallest
/// positive value) and returns their range. MakeSettings does this for its hierarchy.
void PrepareScalars(Hierarchy& h, const std::string& scale, double& lo, double& hi);

/// The VTK camera operations the view options ask for (--azimuth, --elevation, --zoom).
ViewAngles ViewOf(const Arguments& a);

/// Largest difference between two cameras relative to the camera distance (positions, focal
/// points), of the unit view-up vectors, and of the view angles in degrees / 180.
double CameraDifference(const Camera& a, const Camera& b);

/// The dataset used when none is given: small enough to render in a second on two CPU cores.
extern const char* const DefaultDataset;

} // namespace tool
} // namespace amrsp
