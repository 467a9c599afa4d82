// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRCosmoSource.h"

#include "vtkAMRMapperConversion.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include "amrsp/SyntheticCosmo.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

vtkStandardNewMacro(vtkSinglePassAMRCosmoSource);

vtkSinglePassAMRCosmoSource::vtkSinglePassAMRCosmoSource()
{
  this->SetNumberOfInputPorts(0);
}

int vtkSinglePassAMRCosmoSource::FillOutputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkOverlappingAMR");
  return 1;
}

int vtkSinglePassAMRCosmoSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* info = outputVector->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (this->NumberOfTimeSteps > 1)
  {
    std::vector<double> times(static_cast<std::size_t>(this->NumberOfTimeSteps));
    for (std::size_t s = 0; s < times.size(); ++s)
    {
      times[s] = static_cast<double>(s);
    }
    info->Set(SDDP::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { 0.0, times.back() };
    info->Set(SDDP::TIME_RANGE(), range, 2);
  }
  else
  {
    info->Remove(SDDP::TIME_STEPS());
    info->Remove(SDDP::TIME_RANGE());
  }
  return 1;
}

int vtkSinglePassAMRCosmoSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkOverlappingAMR* output = vtkOverlappingAMR::GetData(outputVector, 0);
  if (!output)
  {
    vtkErrorMacro("The output is not a vtkOverlappingAMR.");
    return 0;
  }
  amrsp::CosmoParameters p;
  p.Grids = this->NumberOfGrids;
  p.Levels = this->NumberOfLevels;
  p.Cells = this->NumberOfCells;
  p.Seed = static_cast<uint64_t>(this->Seed);
  p.Steps = this->NumberOfTimeSteps;
  p.RegridEvery = this->RegridEvery;
  vtkInformation* info = outputVector->GetInformationObject(0);
  using SDDP = vtkStreamingDemandDrivenPipeline;
  if (p.Steps > 1 && info->Has(SDDP::UPDATE_TIME_STEP()))
  {
    const double t = info->Get(SDDP::UPDATE_TIME_STEP());
    p.Step = std::min(p.Steps - 1, std::max(0, static_cast<int>(std::lround(t))));
  }
  try
  {
    const amrsp::Hierarchy h = amrsp::GenerateCosmo(p);
    vtkAMRMapperConversion::ToOverlappingAMR(h, output);
    if (p.Steps > 1)
    {
      output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), static_cast<double>(p.Step));
    }
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("Cannot generate the synthetic hierarchy: " << e.what());
    return 0;
  }
  return 1;
}

void vtkSinglePassAMRCosmoSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfGrids: " << this->NumberOfGrids << "\n";
  os << indent << "NumberOfLevels: " << this->NumberOfLevels << "\n";
  os << indent << "NumberOfCells: " << this->NumberOfCells << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "NumberOfTimeSteps: " << this->NumberOfTimeSteps << "\n";
  os << indent << "RegridEvery: " << this->RegridEvery << "\n";
}
