// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspPacking.h"

#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkSmartPointer.h"

namespace amrsp
{
namespace tool
{

namespace
{
vtkSmartPointer<vtkSinglePassAMRVolumeMapper> NewMapper()
{
  return vtkSmartPointer<vtkSinglePassAMRVolumeMapper>::New();
}
} // namespace

PackingRenderer::PackingRenderer(
  const Hierarchy& h, const RenderSettings& s, const ViewAngles& view)
  : PackingRenderer(NewMapper(), h, s, view)
{
}

PackingRenderer::PackingRenderer(vtkSinglePassAMRVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view)
  : GpuRenderer("packing", mapper, h, s, view)
  , Mapper(mapper)
{
  this->Mapper->SetSampleDistanceFactor(s.SampleDistanceFactor);
  this->Mapper->SetLODThreshold(s.LodThresholdPixels);
  this->Mapper->SetOpacityThreshold(s.OpacityThreshold);
  this->Mapper->SetEmptySpaceSkipping(s.SkipEmptySpace);
  this->Mapper->SetCellInterpolation(s.SmoothCellData ? vtkSinglePassAMRVolumeMapper::SMOOTH_CELL
                                                      : vtkSinglePassAMRVolumeMapper::NEAREST_CELL);
}

vtkSinglePassAMRVolumeMapper* PackingRenderer::GetMapper() const
{
  return this->Mapper;
}

double PackingRenderer::BuildSeconds() const
{
  return this->Mapper->GetLastBuildSeconds();
}

double PackingRenderer::UploadSeconds() const
{
  return this->Mapper->GetLastUploadSeconds();
}

int PackingRenderer::NumberOfBuilds() const
{
  return this->Mapper->GetNumberOfBuilds();
}

long long PackingRenderer::TextureBytes() const
{
  return this->Mapper->GetTextureBytes();
}

std::string PackingRenderer::LastError() const
{
  return this->Mapper->GetLastError();
}

void PackingRenderer::GetAtlasDimensions(int dims[3]) const
{
  this->Mapper->GetAtlasDimensions(dims);
}

} // namespace tool
} // namespace amrsp
