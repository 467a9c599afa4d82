// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `uniform-gpu` method of the amrsp tool: what a VTK user does without an AMR renderer —
/// resample the hierarchy onto one uniform grid at a level's cell size and render it with
/// vtkGPUVolumeRayCastMapper, with the tool's camera and transfer-function conventions.

#include "AmrspPacking.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"

#include <memory>
#include <string>

namespace amrsp
{
namespace tool
{

class UniformGpuRenderer
{
public:
  /// Resamples `h` at the cell size of `level` (ResampleToLevel) and sets up the scene. Throws
  /// ResampleError when the grid does not fit (GL_MAX_3D_TEXTURE_SIZE per axis, 2^29 voxels) and
  /// GpuError when no OpenGL context can be had.
  UniformGpuRenderer(const Hierarchy& h, const RenderSettings& s, const ViewAngles& view,
    int level);
  ~UniformGpuRenderer();
  UniformGpuRenderer(const UniformGpuRenderer&) = delete;
  UniformGpuRenderer& operator=(const UniformGpuRenderer&) = delete;

  /// As PackingRenderer::Render.
  Image Render(double orbitDegrees, double& milliseconds);
  double ResampleSeconds() const;
  long long TextureBytes() const;
  std::string Dimensions() const;

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};

} // namespace tool
} // namespace amrsp
