// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRPositiveRangeInformation.h"

#include "vtkAlgorithm.h"
#include "vtkCellData.h"
#include "vtkClientServerStream.h"
#include "vtkCompositeDataIterator.h"
#include "vtkCompositeDataSet.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSet.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessStream.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>

namespace
{
// Tags the parameter stream, so that a stream of another class is recognised.
constexpr int ParametersTag = 0x5a4d5052;

}

vtkStandardNewMacro(vtkSinglePassAMRPositiveRangeInformation);

//------------------------------------------------------------------------------
vtkSinglePassAMRPositiveRangeInformation::vtkSinglePassAMRPositiveRangeInformation()
{
  // every rank scans its own blocks; AddInformation merges them
  this->RootOnly = 0;
}

//------------------------------------------------------------------------------
vtkSinglePassAMRPositiveRangeInformation::~vtkSinglePassAMRPositiveRangeInformation() = default;

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::SetArrayName(const char* name)
{
  const std::string value = name ? name : "";
  if (value != this->ArrayName)
  {
    this->ArrayName = value;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::ResetResult()
{
  this->NumberOfValues = 0;
  this->Minimum = this->Maximum = this->MinimumPositive = 0.0;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRPositiveRangeInformation::IsDensityLike(double decades) const
{
  return this->NumberOfValues > 0 && this->Minimum >= 0.0 && this->MinimumPositive > 0.0 &&
    this->Maximum / this->MinimumPositive > std::pow(10.0, decades);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::CopyFromObject(vtkObject* object)
{
  this->ResetResult();
  vtkDataObject* data = vtkDataObject::SafeDownCast(object);
  if (auto* algorithm = vtkAlgorithm::SafeDownCast(object))
  {
    if (this->PortNumber >= 0 && this->PortNumber < algorithm->GetNumberOfOutputPorts())
    {
      data = algorithm->GetOutputDataObject(this->PortNumber);
    }
  }
  if (!data || this->ArrayName.empty())
  {
    return;
  }
  if (auto* composite = vtkCompositeDataSet::SafeDownCast(data))
  {
    vtkSmartPointer<vtkCompositeDataIterator> iter;
    iter.TakeReference(composite->NewIterator());
    for (iter->InitTraversal(); !iter->IsDoneWithTraversal(); iter->GoToNextItem())
    {
      this->ScanDataObject(iter->GetCurrentDataObject());
    }
  }
  else
  {
    this->ScanDataObject(data);
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::ScanDataObject(vtkDataObject* data)
{
  auto* dataset = vtkDataSet::SafeDownCast(data);
  if (!dataset)
  {
    return;
  }
  const bool points = this->FieldAssociation == vtkDataObject::POINT;
  vtkDataSetAttributes* attributes = points
    ? static_cast<vtkDataSetAttributes*>(dataset->GetPointData())
    : static_cast<vtkDataSetAttributes*>(dataset->GetCellData());
  vtkDataArray* array = attributes ? attributes->GetArray(this->ArrayName.c_str()) : nullptr;
  if (!array || array->GetNumberOfComponents() < 1)
  {
    return;
  }
  // elements the mapper does not sample: duplicates, hidden ones, cells under a finer level
  const unsigned char skipped = points
    ? static_cast<unsigned char>(
        vtkDataSetAttributes::DUPLICATEPOINT | vtkDataSetAttributes::HIDDENPOINT)
    : static_cast<unsigned char>(vtkDataSetAttributes::DUPLICATECELL |
        vtkDataSetAttributes::HIDDENCELL | vtkDataSetAttributes::REFINEDCELL);
  auto* ghosts = vtkUnsignedCharArray::SafeDownCast(
    attributes->GetArray(vtkDataSetAttributes::GhostArrayName()));
  if (ghosts && ghosts->GetNumberOfTuples() != array->GetNumberOfTuples())
  {
    ghosts = nullptr;
  }

  for (vtkIdType i = 0, n = array->GetNumberOfTuples(); i < n; ++i)
  {
    if (!ghosts || (ghosts->GetValue(i) & skipped) == 0)
    {
      this->AddValue(array->GetComponent(i, 0));
    }
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::AddValue(double value)
{
  if (!std::isfinite(value))
  {
    return;
  }
  if (this->NumberOfValues == 0)
  {
    this->Minimum = this->Maximum = value;
  }
  else
  {
    this->Minimum = std::min(this->Minimum, value);
    this->Maximum = std::max(this->Maximum, value);
  }
  ++this->NumberOfValues;
  if (value > 0.0 && (this->MinimumPositive == 0.0 || value < this->MinimumPositive))
  {
    this->MinimumPositive = value;
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::AddInformation(vtkPVInformation* other)
{
  auto* that = vtkSinglePassAMRPositiveRangeInformation::SafeDownCast(other);
  if (!that || that->NumberOfValues == 0)
  {
    return;
  }
  if (this->NumberOfValues == 0)
  {
    this->NumberOfValues = that->NumberOfValues;
    this->Minimum = that->Minimum;
    this->Maximum = that->Maximum;
    this->MinimumPositive = that->MinimumPositive;
    return;
  }
  this->NumberOfValues += that->NumberOfValues;
  this->Minimum = std::min(this->Minimum, that->Minimum);
  this->Maximum = std::max(this->Maximum, that->Maximum);
  if (that->MinimumPositive > 0.0 &&
    (this->MinimumPositive == 0.0 || that->MinimumPositive < this->MinimumPositive))
  {
    this->MinimumPositive = that->MinimumPositive;
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << static_cast<vtkTypeInt64>(this->NumberOfValues)
          << this->Minimum << this->Maximum << this->MinimumPositive << vtkClientServerStream::End;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  this->ResetResult();
  vtkTypeInt64 count = 0;
  if (!stream->GetArgument(0, 0, &count) || !stream->GetArgument(0, 1, &this->Minimum) ||
    !stream->GetArgument(0, 2, &this->Maximum) ||
    !stream->GetArgument(0, 3, &this->MinimumPositive))
  {
    vtkErrorMacro("Cannot read the array range from the stream.");
    this->ResetResult();
    return;
  }
  this->NumberOfValues = static_cast<vtkIdType>(count);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::CopyParametersToStream(vtkMultiProcessStream& stream)
{
  stream << ParametersTag << this->PortNumber << this->FieldAssociation << this->ArrayName;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::CopyParametersFromStream(
  vtkMultiProcessStream& stream)
{
  int tag = 0;
  stream >> tag;
  if (tag != ParametersTag)
  {
    vtkErrorMacro("Unexpected parameter stream.");
    return;
  }
  stream >> this->PortNumber >> this->FieldAssociation >> this->ArrayName;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRPositiveRangeInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PortNumber: " << this->PortNumber << "\n";
  os << indent << "FieldAssociation: " << this->FieldAssociation << "\n";
  os << indent << "ArrayName: " << this->ArrayName << "\n";
  os << indent << "NumberOfValues: " << this->NumberOfValues << "\n";
  os << indent << "Minimum: " << this->Minimum << "\n";
  os << indent << "Maximum: " << this->Maximum << "\n";
  os << indent << "MinimumPositive: " << this->MinimumPositive << "\n";
}
