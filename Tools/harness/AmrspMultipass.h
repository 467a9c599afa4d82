// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `multipass` method of the amrsp tool: vtkMultiPassAMRVolumeMapper (the paper's multi-pass
/// baseline: the kD-tree ordered on the CPU, one draw per data node, blended front to back) in an
/// offscreen vtkRenderWindow with the tool's conventions (the set-up is GpuRenderer's).

#include "AmrspGpuRenderer.h"

class vtkMultiPassAMRVolumeMapper;

namespace amrsp
{
namespace harness
{

class MultipassRenderer : public GpuRenderer
{
public:
  /// As SinglePassRenderer. The multi-pass method renders the finest level only: a level-of-detail
  /// threshold in `s` (--lod) is a GpuError.
  MultipassRenderer(const Hierarchy& h, const RenderSettings& s, const ViewAngles& view);

  vtkMultiPassAMRVolumeMapper* GetMapper() const;

  /// Bytes of the RGBA32F accumulation target of the last frame (TextureBytes() counts the
  /// atlas only: the method has no tree textures).
  long long AccumulationBytes() const;
  /// Draws (data nodes) of the last frame, and the CPU seconds of their front-to-back ordering.
  long long Passes() const;
  double OrderSeconds() const;

private:
  MultipassRenderer(vtkMultiPassAMRVolumeMapper* mapper, const Hierarchy& h,
    const RenderSettings& s, const ViewAngles& view);
  vtkMultiPassAMRVolumeMapper* Mapper; // held by the base (its volume's mapper)
};

} // namespace harness
} // namespace amrsp
