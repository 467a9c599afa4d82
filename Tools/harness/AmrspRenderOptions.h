// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The render options (`amrsp render --size --tf --scale ...`, docs/command-line.md) as the
/// RenderSettings of a hierarchy, following the rendering conventions of docs/design.md: what the
/// tool, the tests and the benchmark share, so that a test's "--size 96x96" means what the
/// tool's does.

#include "AmrspArguments.h"
#include "AmrspGpuRenderer.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

/// The names of the options MakeSettings reads (all take a value).
extern const std::vector<std::string> RenderOptionNames;

/// The render settings of the view and transfer-function options. Maps the scalars of `h` as
/// --scale asks (log10 in place) and returns their display range in `range`. Throws UsageError
/// for bad options and DatasetError for data the scale cannot map.
RenderSettings MakeSettings(Hierarchy& h, const Arguments& a, glm::dvec2* range = nullptr);

/// MakeSettings for a list of option words, e.g. { "--size", "96x96", "--scale", "linear" }.
RenderSettings MakeSettings(Hierarchy& h, const std::vector<std::string>& optionWords);

/// Maps the scalars for display (--scale `scale`: log10 when "log", or with "auto" for
/// non-negative data whose positive values span more than 3 decades; zeros map to the smallest
/// positive value) and returns their range. MakeSettings does this for its hierarchy.
void PrepareScalars(Hierarchy& h, const std::string& scale, double& lo, double& hi);

/// The VTK camera operations the view options ask for (--azimuth, --elevation, --zoom).
ViewAngles ViewOf(const Arguments& a);

/// Largest difference between two cameras relative to the camera distance (positions, focal
/// points), of the unit view-up vectors, and of the view angles in degrees / 180.
double CameraDifference(const Camera& a, const Camera& b);

/// World bounds of the hierarchy's root box.
void Bounds(const Hierarchy& h, glm::dvec3& lo, glm::dvec3& hi);

} // namespace harness
} // namespace amrsp
