// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The render options (`amrsp render --size --tf --scale ...`, docs/command-line.md) as the
/// RenderSettings of a hierarchy, following the rendering conventions of docs/design.md: what the
/// tool, the tests and the benchmark share, so that a test's "--size 96x96" means what the
/// tool's does.

#include "AmrspArguments.h"
#include "AmrspGpuRenderer.h"
#include "AmrspRenderRequest.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <limits>
#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

/// The names of the options MakeSettings reads (all take a value).
extern const std::vector<std::string> RenderOptionNames;

/// The span of an array's finite values, in the data's own units (before any log10).
struct ScalarSpan
{
  double Lo = 0.0;
  double Hi = 0.0;
  /// the smallest value > 0; +max when there is none
  double MinPositive = std::numeric_limits<double>::max();
};

/// The span of the finite values of `h`'s array. Throws DatasetError when it has none.
ScalarSpan MeasureScalars(const Hierarchy& h);

/// The span covering both.
ScalarSpan Union(const ScalarSpan& a, const ScalarSpan& b);

/// A given span, "LO:HI" with LO < HI finite (--range). Throws UsageError otherwise.
ScalarSpan ParseScalarSpan(const std::string& text);

/// The render settings of a request (the view, transfer-function and rendering options). Maps the
/// scalars of `h` as --scale asks (log10 in place) and returns their display range in `range`. The
/// scale rule and the transfer function's range follow `over` where it is given (a series' span
/// over all its steps), else --range LO:HI where it is given, else `h`'s own values. Throws
/// UsageError for bad options and DatasetError for data the scale cannot map.
RenderSettings MakeSettings(Hierarchy& h, const RenderRequest& r, glm::dvec2* range = nullptr,
  const ScalarSpan* over = nullptr);
/// MakeSettings of the request the option words of `a` make (ParseRenderRequest).
RenderSettings MakeSettings(
  Hierarchy& h, const Arguments& a, glm::dvec2* range = nullptr, const ScalarSpan* over = nullptr);

/// MakeSettings for a list of option words, e.g. { "--size", "96x96", "--scale", "linear" }.
RenderSettings MakeSettings(Hierarchy& h, const std::vector<std::string>& optionWords);

/// Maps the scalars for display (--scale `scale`: log10 when "log", or with "auto" when the
/// span is non-negative and its positive values cover more than 3 decades; values below the
/// span's smallest positive value map to it) and returns the span's display range. The span is
/// `over` where given, else `h`'s own. MakeSettings does this for its hierarchy.
void PrepareScalars(
  Hierarchy& h, const std::string& scale, double& lo, double& hi, const ScalarSpan* over = nullptr);

/// The VTK camera operations the view options ask for (--azimuth, --elevation, --zoom).
ViewAngles ViewOf(const Arguments& a);

/// Largest difference between two cameras relative to the camera distance (positions, focal
/// points), of the unit view-up vectors, and of the view angles in degrees / 180.
double CameraDifference(const Camera& a, const Camera& b);

/// World bounds of the hierarchy's root box.
void Bounds(const Hierarchy& h, glm::dvec3& lo, glm::dvec3& hi);

} // namespace harness
} // namespace amrsp
