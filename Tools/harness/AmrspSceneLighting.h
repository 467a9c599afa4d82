// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A RenderSettings' shading, iso-surfaces, shadows and light as VTK objects, for the GPU
/// renderers of the harness (docs/design.md, "Shading, iso-surfaces and shadows").

#include "amrsp/Render.h"

class vtkRenderer;
class vtkVolumeMapper;
class vtkVolumeProperty;

namespace amrsp
{
namespace harness
{

/// Sets the vtkVolumeProperty (shading, iso-values), the mapper's shadow options (when it is a
/// vtkSinglePassAMRVolumeMapper) and the renderer's light from `s`.
void ApplyLighting(const RenderSettings& s, vtkVolumeProperty* property, vtkVolumeMapper* mapper,
  vtkRenderer* renderer);

} // namespace harness
} // namespace amrsp
