// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The shading, iso-surface and shadow options of a render (docs/design.md, "Shading,
/// iso-surfaces and shadows"); AmrspSceneLighting.h turns them into VTK objects.

#include "amrsp/Render.h"

#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

struct Arguments;

/// Option names (values): shade, iso, shadows, light.
extern const std::vector<std::string> LightingOptions;

/// Reads --shade on|off, --iso F[,F...] (fractions of the transfer function's range [lo, hi];
/// --blend iso), --shadows STEP (world units; 0 = off) and --light X,Y,Z (a point light at this
/// world position; default: the headlight) into `s`. Throws UsageError.
void ApplyLightingOptions(RenderSettings& s, const Arguments& a, double lo, double hi);

} // namespace harness
} // namespace amrsp
