// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The `packing` method of the amrsp tool: vtkSinglePassAMRVolumeMapper in an offscreen
/// vtkRenderWindow with the tool's camera, transfer-function and background conventions
/// (README, "Rendering conventions"; the set-up is GpuRenderer's).

#include "AmrspGpuRenderer.h"

class vtkSinglePassAMRVolumeMapper;

namespace amrsp
{
namespace tool
{

class PackingRenderer : public GpuRenderer
{
public:
  /// `h` holds the scalars as they are displayed (after --scale); `s` gives the image size, the
  /// transfer function, its unit distance, the sample factor and the LOD threshold. Nothing is
  /// rendered yet.
  PackingRenderer(const Hierarchy& h, const RenderSettings& s, const ViewAngles& view);

  vtkSinglePassAMRVolumeMapper* GetMapper() const;

  double BuildSeconds() const override;
  double UploadSeconds() const override;
  int NumberOfBuilds() const override;
  long long TextureBytes() const override;

protected:
  std::string LastError() const override;
  void GetAtlasDimensions(int dims[3]) const override;

private:
  PackingRenderer(vtkSinglePassAMRVolumeMapper* mapper, const Hierarchy& h, const RenderSettings& s,
    const ViewAngles& view);
  vtkSinglePassAMRVolumeMapper* Mapper; // held by the base (its volume's mapper)
};

} // namespace tool
} // namespace amrsp
