// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRCosmoSource.h"

#include "vtkSinglePassAMRConversion.h"
#include "vtkDataObject.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"

#include "amrsp/SyntheticCosmo.h"

#include <stdexcept>

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
  try
  {
    const amrsp::Hierarchy h = amrsp::GenerateCosmo(p);
    vtkSinglePassAMRConversion::ToOverlappingAMR(h, output);
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
}
