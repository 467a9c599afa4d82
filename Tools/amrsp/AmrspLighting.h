// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The shading, iso-surface and shadow options of the amrsp tool (docs/design.md, "Shading,
/// iso-surfaces and shadows"), and their translation into VTK objects for the GPU methods.

#include "amrsp/Render.h"

#include <string>
#include <vector>

class vtkRenderer;
class vtkVolumeMapper;
class vtkVolumeProperty;

namespace amrsp
{
namespace tool
{

struct Arguments;

/// Option names (values): shade, iso, shadows, light.
extern const std::vector<std::string> LightingOptions;

/// Reads --shade on|off, --iso F[,F...] (fractions of the transfer function's range [lo, hi];
/// --blend iso), --shadows STEP (world units; 0 = off) and --light X,Y,Z (a point light at this
/// world position; default: the headlight) into `s`. Throws UsageError.
void ApplyLightingOptions(RenderSettings& s, const Arguments& a, double lo, double hi);

/// Sets the vtkVolumeProperty (shading, iso-values), the mapper's shadow options (when it is a
/// vtkSinglePassAMRVolumeMapper) and the renderer's light from `s`.
void ApplyLighting(const RenderSettings& s, vtkVolumeProperty* property, vtkVolumeMapper* mapper,
  vtkRenderer* renderer);

} // namespace tool
} // namespace amrsp
