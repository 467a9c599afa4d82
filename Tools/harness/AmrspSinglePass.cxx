// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspSinglePass.h"

#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>

namespace amrsp
{
namespace harness
{

SinglePassRenderer::SinglePassRenderer(const Hierarchy& h, const RenderSettings& s,
  const ViewAngles& view, DataStorage storage, BindlessAccess access)
  : SinglePassRenderer(
      vtkSmartPointer<vtkSinglePassAMRVolumeMapper>::New(), h, s, view, storage, access)
{
}

SinglePassRenderer::SinglePassRenderer(vtkSinglePassAMRVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view, DataStorage storage, BindlessAccess access)
  : GpuRenderer(DataStorageName(storage), mapper, h, s, view)
  , Mapper(mapper)
{
  if (storage == DataStorage::None || access == BindlessAccess::None)
  {
    throw std::invalid_argument("a single-pass renderer needs a data storage and an access");
  }
  // the mapper's public modes have the values of amrsp::DataStorage and amrsp::BindlessAccess
  this->Mapper->SetDataStorage(static_cast<int>(storage));
  this->Mapper->SetBindlessAccess(static_cast<int>(access));
  this->Mapper->SetSampleDistanceFactor(s.SampleDistanceFactor);
  if (s.AtlasPageBytes > 0)
  {
    this->Mapper->SetMaximumAtlasPageBytes(s.AtlasPageBytes);
  }
  this->Mapper->SetLODThreshold(s.LodThresholdPixels);
  this->Mapper->SetOpacityThreshold(s.OpacityThreshold);
  this->Mapper->SetEmptySpaceSkipping(s.SkipEmptySpace);
  this->Mapper->SetRopes(s.Ropes);
  this->Mapper->SetRayLoop(static_cast<int>(s.GpuRayLoop));
  this->Mapper->SetRayCaster(static_cast<int>(s.GpuRayCaster));
  this->Mapper->SetDiagnosticAblation(s.GpuAblation);
  this->Mapper->SetDiagnosticAblationSamples(s.GpuAblationSamples);
  this->Mapper->SetCellInterpolation(s.SmoothCellData ? vtkSinglePassAMRVolumeMapper::SMOOTH_CELL
                                                      : vtkSinglePassAMRVolumeMapper::NEAREST_CELL);
}

DataStorage SinglePassRenderer::StorageUsed() const
{
  return static_cast<DataStorage>(this->Mapper->GetLastDataStorage());
}

BindlessAccess SinglePassRenderer::AccessUsed() const
{
  return static_cast<BindlessAccess>(this->Mapper->GetLastBindlessAccess());
}

RayLoop SinglePassRenderer::LoopUsed() const
{
  return static_cast<RayLoop>(this->Mapper->GetLastRayLoop());
}

RayCaster SinglePassRenderer::CasterUsed() const
{
  return static_cast<RayCaster>(this->Mapper->GetLastRayCaster());
}

std::string SinglePassRenderer::StorageUsedInWords() const
{
  return StorageInWords(this->StorageUsed(), this->AccessUsed());
}

std::string SinglePassRenderer::BindlessFallbackReason() const
{
  return this->Mapper->GetBindlessFallbackReason();
}

long long SinglePassRenderer::PackedBytes() const
{
  return this->Mapper->GetPackedTextureBytes();
}

long long SinglePassRenderer::BindlessBytes() const
{
  return this->Mapper->GetBindlessTextureBytes();
}

long long SinglePassRenderer::RenderWorkCount(int count)
{
  this->Mapper->SetLoopCountOutput(count);
  double ms = 0.0;
  Image counts;
  try
  {
    counts = this->RenderAsIs(ms);
  }
  catch (...)
  {
    this->Mapper->SetLoopCountOutput(vtkSinglePassAMRVolumeMapper::NO_LOOP_COUNT);
    throw;
  }
  this->Mapper->SetLoopCountOutput(vtkSinglePassAMRVolumeMapper::NO_LOOP_COUNT);
  long long sum = 0;
  for (const glm::vec4& p : counts.Pixels)
  {
    // 24-bit integer: red the low byte (8-bit channels read back exactly as k / 255)
    sum += std::lround(p.r * 255.0f) + 256 * std::lround(p.g * 255.0f) +
      65536 * std::lround(p.b * 255.0f);
  }
  return sum;
}

SinglePassRenderer::Occupancy SinglePassRenderer::RenderOccupancy()
{
  Occupancy o;
  this->Mapper->OccupancyProbeOn();
  double ms = 0.0;
  Image probe;
  try
  {
    probe = this->RenderAsIs(ms);
  }
  catch (const GpuError& e)
  {
    this->Mapper->OccupancyProbeOff();
    o.Why = e.what();
    return o;
  }
  this->Mapper->OccupancyProbeOff();
  o.Available = true;
  o.Caster = this->CasterUsed();
  // 8-bit exact channels: red the SM, green the warp slot, blue the SM count; alpha 1 marks a ray
  std::set<long> sms;
  std::map<long, std::set<long>> warps;
  for (const glm::vec4& p : probe.Pixels)
  {
    if (p.a < 0.5f)
    {
      continue;
    }
    const long sm = std::lround(p.r * 255.0f), warp = std::lround(p.g * 255.0f);
    ++o.Rays;
    sms.insert(sm);
    warps[sm].insert(warp);
    o.ChipMultiprocessors =
      std::max(o.ChipMultiprocessors, static_cast<int>(std::lround(p.b * 255.0f)));
  }
  o.Multiprocessors = static_cast<int>(sms.size());
  for (const auto& w : warps)
  {
    o.Warps += static_cast<int>(w.second.size());
    o.MostWarpsOnOne = std::max(o.MostWarpsOnOne, static_cast<int>(w.second.size()));
  }
  return o;
}

vtkSinglePassAMRVolumeMapper* SinglePassRenderer::GetMapper() const
{
  return this->Mapper;
}

} // namespace harness
} // namespace amrsp
