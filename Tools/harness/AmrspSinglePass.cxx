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

namespace
{
vtkSmartPointer<vtkSinglePassAMRVolumeMapper> NewMapper()
{
  return vtkSmartPointer<vtkSinglePassAMRVolumeMapper>::New();
}
} // namespace

SinglePassRenderer::SinglePassRenderer(const Hierarchy& h, const RenderSettings& s,
  const ViewAngles& view, const std::string& storage, const std::string& bindlessAccess)
  : SinglePassRenderer(NewMapper(), h, s, view, storage, bindlessAccess)
{
}

SinglePassRenderer::SinglePassRenderer(vtkSinglePassAMRVolumeMapper* mapper, const Hierarchy& h,
  const RenderSettings& s, const ViewAngles& view, const std::string& storage,
  const std::string& bindlessAccess)
  : GpuRenderer(storage, mapper, h, s, view)
  , Mapper(mapper)
{
  using M = vtkSinglePassAMRVolumeMapper;
  if (storage != "packing" && storage != "bindless" && storage != "linear" && storage != "auto")
  {
    throw std::invalid_argument(
      "unknown data storage '" + storage + "' (packing, bindless, linear or auto)");
  }
  if (bindlessAccess != "auto" && bindlessAccess != "direct" && bindlessAccess != "waterfall")
  {
    throw std::invalid_argument(
      "unknown bindless access '" + bindlessAccess + "' (auto, direct or waterfall)");
  }
  this->Mapper->SetDataStorage(storage == "packing" ? M::PACKED_ATLAS
      : storage == "bindless"                       ? M::BINDLESS_TEXTURES
      : storage == "linear"                         ? M::LINEAR_BRICKS
                                                    : M::AUTO_STORAGE);
  this->Mapper->SetBindlessAccess(bindlessAccess == "direct" ? M::DIRECT_ACCESS
      : bindlessAccess == "waterfall"                        ? M::WATERFALL_ACCESS
                                                             : M::AUTO_ACCESS);
  this->Mapper->SetSampleDistanceFactor(s.SampleDistanceFactor);
  if (s.AtlasPageBytes > 0)
  {
    this->Mapper->SetMaximumAtlasPageBytes(s.AtlasPageBytes);
  }
  this->Mapper->SetLODThreshold(s.LodThresholdPixels);
  this->Mapper->SetOpacityThreshold(s.OpacityThreshold);
  this->Mapper->SetEmptySpaceSkipping(s.SkipEmptySpace);
  this->Mapper->SetRopes(s.Ropes);
  this->Mapper->SetRayLoop(s.GpuRayLoop == RenderSettings::RayLoop::Flat
      ? vtkSinglePassAMRVolumeMapper::FLAT_LOOP
      : s.GpuRayLoop == RenderSettings::RayLoop::Nested ? vtkSinglePassAMRVolumeMapper::NESTED_LOOPS
                                                        : vtkSinglePassAMRVolumeMapper::AUTO_LOOP);
  this->Mapper->SetRayCaster(static_cast<int>(s.GpuRayCaster));
  this->Mapper->SetDiagnosticAblation(s.GpuAblation);
  this->Mapper->SetDiagnosticAblationSamples(s.GpuAblationSamples);
  this->Mapper->SetCellInterpolation(s.SmoothCellData ? vtkSinglePassAMRVolumeMapper::SMOOTH_CELL
                                                      : vtkSinglePassAMRVolumeMapper::NEAREST_CELL);
}

std::string SinglePassRenderer::StorageUsed() const
{
  const int storage = this->Mapper->GetLastDataStorage();
  std::string name = vtkSinglePassAMRVolumeMapper::GetDataStorageName(storage);
  if (storage == vtkSinglePassAMRVolumeMapper::BINDLESS_TEXTURES)
  {
    name += std::string(" (") +
      vtkSinglePassAMRVolumeMapper::GetBindlessAccessName(this->Mapper->GetLastBindlessAccess()) +
      ")";
  }
  return name;
}

std::string SinglePassRenderer::CasterUsed() const
{
  return vtkSinglePassAMRVolumeMapper::GetRayCasterName(this->Mapper->GetLastRayCaster());
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
  this->Mapper->SetWorkCountOutput(count);
  double ms = 0.0;
  Image counts;
  try
  {
    counts = this->RenderAsIs(ms);
  }
  catch (...)
  {
    this->Mapper->SetWorkCountOutput(vtkSinglePassAMRVolumeMapper::NO_WORK_COUNT);
    throw;
  }
  this->Mapper->SetWorkCountOutput(vtkSinglePassAMRVolumeMapper::NO_WORK_COUNT);
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
