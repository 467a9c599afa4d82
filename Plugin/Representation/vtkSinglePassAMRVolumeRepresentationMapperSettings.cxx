// SPDX-License-Identifier: BSD-3-Clause
// The representation's properties that go to its two mappers (the single-pass mapper and the
// multi-pass baseline get the same values where both have them) and the counts read back from
// them. The pipeline, delivery, the animation cache and the diagnostics of copied data are in
// vtkSinglePassAMRVolumeRepresentation.cxx.
#include "vtkSinglePassAMRVolumeRepresentation.h"

#include "vtkContourValues.h"
#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <cmath>

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetSampleDistanceFactor(double factor)
{
  this->VolumeMapper->SetSampleDistanceFactor(factor);
  this->MultiPassMapper->SetSampleDistanceFactor(factor);
}

//------------------------------------------------------------------------------
double vtkSinglePassAMRVolumeRepresentation::GetSampleDistanceFactor()
{
  return this->VolumeMapper->GetSampleDistanceFactor();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetOpacityThreshold(double threshold)
{
  this->VolumeMapper->SetOpacityThreshold(threshold);
}

//------------------------------------------------------------------------------
double vtkSinglePassAMRVolumeRepresentation::GetOpacityThreshold()
{
  return this->VolumeMapper->GetOpacityThreshold();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetEmptySpaceSkipping(bool on)
{
  this->VolumeMapper->SetEmptySpaceSkipping(on);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeRepresentation::GetEmptySpaceSkipping()
{
  return this->VolumeMapper->GetEmptySpaceSkipping();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetCellInterpolation(int mode)
{
  this->VolumeMapper->SetCellInterpolation(mode);
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetCellInterpolation()
{
  return this->VolumeMapper->GetCellInterpolation();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetRayCaster(int caster)
{
  this->VolumeMapper->SetRayCaster(caster);
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetRayCaster()
{
  return this->VolumeMapper->GetRayCaster();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetRayLoop(int loop)
{
  this->VolumeMapper->SetRayLoop(loop);
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetRayLoop()
{
  return this->VolumeMapper->GetRayLoop();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetShade(bool on)
{
  this->Property->SetShade(on ? 1 : 0);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetAmbient(double value)
{
  this->Property->SetAmbient(value);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetDiffuse(double value)
{
  this->Property->SetDiffuse(value);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetSpecular(double value)
{
  this->Property->SetSpecular(value);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetSpecularPower(double value)
{
  this->Property->SetSpecularPower(value);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetShadows(bool on)
{
  this->VolumeMapper->SetShadows(on);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetShadowSampleDistance(double distance)
{
  this->VolumeMapper->SetShadowSampleDistance(distance);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetNumberOfIsosurfaces(int count)
{
  this->Property->GetIsoSurfaceValues()->SetNumberOfContours(count);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetIsosurfaceValue(int index, double value)
{
  this->Property->GetIsoSurfaceValues()->SetValue(index, value);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetLODThreshold(double pixels)
{
  this->VolumeMapper->SetLODThreshold(pixels);
}

//------------------------------------------------------------------------------
double vtkSinglePassAMRVolumeRepresentation::GetLODThreshold()
{
  return this->VolumeMapper->GetLODThreshold();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetAutoAdjustSampleDistances(int on)
{
  this->VolumeMapper->SetAutoAdjustSampleDistances(on);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetImageSampleDistance(double pixels)
{
  this->VolumeMapper->SetImageSampleDistance(static_cast<float>(pixels));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetMinimumImageSampleDistance(double pixels)
{
  this->VolumeMapper->SetMinimumImageSampleDistance(static_cast<float>(pixels));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetMaximumImageSampleDistance(double pixels)
{
  this->VolumeMapper->SetMaximumImageSampleDistance(static_cast<float>(pixels));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetInteractiveAdjustSampleDistances(int on)
{
  this->VolumeMapper->SetInteractiveAdjustSampleDistances(on);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetBlendMode(int mode)
{
  this->VolumeMapper->SetBlendMode(mode);
  this->MultiPassMapper->SetBlendMode(mode); // composite only: it reports an error for others
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetBlendMode()
{
  return this->VolumeMapper->GetBlendMode();
}

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeMapper* vtkSinglePassAMRVolumeRepresentation::GetVolumeMapper()
{
  return this->VolumeMapper;
}

//------------------------------------------------------------------------------
vtkMultiPassAMRVolumeMapper* vtkSinglePassAMRVolumeRepresentation::GetMultiPassMapper()
{
  return this->MultiPassMapper;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetNumberOfTextureBuilds()
{
  return this->Method == METHOD_MULTI_PASS ? this->MultiPassMapper->GetNumberOfBuilds()
                                           : this->VolumeMapper->GetNumberOfBuilds();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetKeptStepsMiB(double mib)
{
  this->VolumeMapper->SetMaximumKeptStepBytes(
    static_cast<vtkIdType>(std::max(0.0, mib) * 1024.0 * 1024.0));
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetNumberOfKeptStepHits()
{
  return this->VolumeMapper->GetNumberOfKeptStepHits();
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetNumberOfValueRefreshes()
{
  return this->Method == METHOD_MULTI_PASS ? this->MultiPassMapper->GetNumberOfValueRefreshes()
                                           : this->VolumeMapper->GetNumberOfValueRefreshes();
}
