// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `uniform-gpu` method of the amrsp tool: what a VTK user does without an AMR renderer —
/// resample the hierarchy onto one uniform grid at a level's cell size and render it with
/// vtkGPUVolumeRayCastMapper, with the tool's camera and transfer-function conventions (the
/// scene is GpuRenderer's: composite, unshaded, uncropped, the conventions' camera).

#include "AmrspGpuRenderer.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/RenderSettings.h"

#include <glm/glm.hpp>

#include <string>

class vtkGPUVolumeRayCastMapper;

namespace amrsp
{
namespace harness
{

class UniformGpuRenderer : public GpuRenderer
{
public:
  /// Resamples `h` at the cell size of `level` (ResampleToLevel) and sets up the scene. Throws
  /// GpuError when no OpenGL context can be had and ResampleError when the grid does not fit
  /// (GL_MAX_3D_TEXTURE_SIZE per axis, 2^29 voxels).
  UniformGpuRenderer(
    const Hierarchy& h, const RenderSettings& s, const ViewAngles& view, int level);

  /// The level resampled at, the seconds of the resampling and the grid's dimensions "XxYxZ"
  /// (voxels).
  int Level() const;
  double ResampleSeconds() const;
  std::string Dimensions() const;

  /// The resampling (once per renderer); the upload is part of the first frame (-1).
  double BuildSeconds() const override;
  double UploadSeconds() const override;
  int NumberOfBuilds() const override;
  /// Bytes of the resampled grid's float voxels.
  long long TextureBytes() const override;

protected:
  std::string LastError() const override;
  void GetAtlasDimensions(int dims[3]) const override;

private:
  UniformGpuRenderer(vtkGPUVolumeRayCastMapper* mapper, const Hierarchy& h, const RenderSettings& s,
    const ViewAngles& view, int level);
  vtkGPUVolumeRayCastMapper* Mapper; // held by the base (its volume's mapper)
  int ResampledLevel;
  double Seconds = 0.0;
  glm::ivec3 Dims{ 0 };
};

} // namespace harness
} // namespace amrsp
