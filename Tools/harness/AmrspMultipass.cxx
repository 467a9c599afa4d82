// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspMultipass.h"

#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkSmartPointer.h"

namespace amrsp
{
namespace harness
{

namespace
{
vtkSmartPointer<vtkMultiPassAMRVolumeMapper> NewMultipassMapper(const RenderSettings& s)
{
  if (s.LodThresholdPixels > 0.0f)
  {
    throw GpuError("the multipass method renders the finest level only (no --lod)");
  }
  return vtkSmartPointer<vtkMultiPassAMRVolumeMapper>::New();
}
} // namespace

MultipassRenderer::MultipassRenderer(
  const Hierarchy& h, const RenderSettings& s, const ViewAngles& view)
  : MultipassRenderer(NewMultipassMapper(s), h, s, view)
{
}

MultipassRenderer::MultipassRenderer(vtkMultiPassAMRVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view)
  : GpuRenderer("multipass", mapper, h, s, view)
  , Mapper(mapper)
{
  this->Mapper->SetSampleDistanceFactor(s.SampleDistanceFactor);
  if (s.AtlasPageBytes > 0)
  {
    this->Mapper->SetMaximumAtlasPageBytes(s.AtlasPageBytes);
  }
}

vtkMultiPassAMRVolumeMapper* MultipassRenderer::GetMapper() const
{
  return this->Mapper;
}

long long MultipassRenderer::AccumulationBytes() const
{
  return this->Mapper->GetAccumulationBytes();
}

long long MultipassRenderer::Passes() const
{
  return this->Mapper->GetLastNumberOfPasses();
}

double MultipassRenderer::OrderSeconds() const
{
  return this->Mapper->GetLastOrderSeconds();
}

} // namespace harness
} // namespace amrsp
