// SPDX-License-Identifier: BSD-3-Clause
// What vtkSinglePassAMRVolumeMapper reports about its data and its last frame: the read-only
// getters (texture bytes, atlas pages, tree sizes, the storage and access the last frame used,
// kept time steps, the interactive frame's quality). They read the mapper's internals and change
// nothing.
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkSinglePassAMRVolumeMapperInternals.h"

#include "vtkSinglePassAMRGridStorage.h"

#include "amrsp/DataStorage.h"
#include "amrsp/RayCaster.h"
#include "amrsp/RayLoop.h"

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::GetAtlasDimensions(int dims[3])
{
  const glm::ivec3 d = this->Internals->Data.AtlasDims;
  dims[0] = d.x;
  dims[1] = d.y;
  dims[2] = d.z;
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfKeptStepHits()
{
  return this->Internals->KeptStepHits;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeMapper::GetNumberOfKeptSteps()
{
  return static_cast<int>(this->Internals->KeptSteps.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkSinglePassAMRVolumeMapper::GetKeptStepBytes()
{
  vtkIdType bytes = 0;
  for (const auto& kept : this->Internals->KeptSteps)
  {
    bytes += static_cast<vtkIdType>(kept.Storage->GetTextureBytes());
  }
  return bytes;
}

//------------------------------------------------------------------------------
long long vtkSinglePassAMRVolumeMapper::GetTextureBytes()
{
  return this->Internals->Storage->GetTextureBytes();
}

long long vtkSinglePassAMRVolumeMapper::GetPackedTextureBytes()
{
  return this->Internals->Data.PackedBytes;
}

long long vtkSinglePassAMRVolumeMapper::GetBindlessTextureBytes()
{
  return this->Internals->Data.BindlessBytes;
}

bool vtkSinglePassAMRVolumeMapper::GetLastFrameInteractive()
{
  return this->Internals->Budget.LastInteractive;
}

double vtkSinglePassAMRVolumeMapper::GetLastImageSampleDistance()
{
  return this->Internals->Budget.LastQuality.ImageSampleDistance;
}

double vtkSinglePassAMRVolumeMapper::GetLastSampleDistanceScale()
{
  return this->Internals->Budget.LastQuality.SampleDistanceScale;
}

double vtkSinglePassAMRVolumeMapper::GetLastFrameSeconds()
{
  return this->Internals->Budget.LastSeconds;
}

double vtkSinglePassAMRVolumeMapper::GetLastFrameBudget()
{
  return this->Internals->Budget.LastBudget;
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfAtlasPages()
{
  return static_cast<int>(this->Internals->Data.PageDims.size());
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfLinearPages()
{
  return this->Internals->Storage->GetNumberOfLinearPages();
}

double vtkSinglePassAMRVolumeMapper::GetAtlasWaste()
{
  return this->Internals->Data.AtlasWaste;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfKdNodes()
{
  return this->Internals->Data.KdNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfDataNodes()
{
  return this->Internals->Data.DataNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfTransparentDataNodes()
{
  return this->Internals->TransparentDataNodes;
}

int vtkSinglePassAMRVolumeMapper::GetLastDataStorage()
{
  return static_cast<int>(this->Internals->LastStorage);
}

bool vtkSinglePassAMRVolumeMapper::GetLastRopes()
{
  return this->Internals->LastRopes;
}

const char* vtkSinglePassAMRVolumeMapper::GetBindlessFallbackReason()
{
  return this->Internals->StorageNote.c_str();
}

int vtkSinglePassAMRVolumeMapper::GetLastRayLoop()
{
  return this->Internals->LastFlatLoop ? FLAT_LOOP : NESTED_LOOPS;
}

const char* vtkSinglePassAMRVolumeMapper::GetRayLoopName(int loop)
{
  return amrsp::RayLoopName(static_cast<amrsp::RayLoop>(loop));
}

int vtkSinglePassAMRVolumeMapper::GetLastBindlessAccess()
{
  return static_cast<int>(this->Internals->LastAccess);
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeMapper::GetDataStorageName(int storage)
{
  return amrsp::DataStorageName(static_cast<amrsp::DataStorage>(storage));
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeMapper::GetBindlessAccessName(int access)
{
  return amrsp::BindlessAccessName(static_cast<amrsp::BindlessAccess>(access));
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeMapper::GetLastRayCaster()
{
  const amrsp::RayCaster last = this->Internals->LastCaster;
  return last == amrsp::RayCaster::Auto ? -1 : static_cast<int>(last);
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeMapper::GetRayCasterFallbackReason()
{
  return this->Internals->CasterNote.c_str();
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeMapper::GetRayCasterName(int caster)
{
  return caster >= FRAGMENT_CASTER && caster <= AUTO_CASTER
    ? amrsp::RayCasterName(static_cast<amrsp::RayCaster>(caster))
    : "none";
}
