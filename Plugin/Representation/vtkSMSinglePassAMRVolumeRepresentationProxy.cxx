// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSMSinglePassAMRVolumeRepresentationProxy.h"

#include "vtkCommand.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVDataSetAttributesInformation.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMPVRepresentationProxy.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMTransferFunctionManager.h"
#include "vtkSMTransferFunctionProxy.h"
#include "vtkSinglePassAMRPositiveRangeInformation.h"

#include <cstring>
#include <initializer_list>
#include <string>

namespace
{
/** An array of the input: association (vtkDataObject::POINT or CELL) and name. */
struct ColorArray
{
  int Association = -1;
  std::string Name;
  bool IsSet() const { return !this->Name.empty(); }
};

bool IsGhostArray(const char* name)
{
  return name && std::strcmp(name, vtkDataSetAttributes::GhostArrayName()) == 0;
}

vtkSMSourceProxy* GetInput(vtkSMProxy* repr, unsigned int* port)
{
  vtkSMPropertyHelper input(repr, "Input", /*quiet=*/true);
  *port = input.GetNumberOfElements() > 0 ? input.GetOutputPort() : 0;
  return input.GetNumberOfElements() > 0 ? vtkSMSourceProxy::SafeDownCast(input.GetAsProxy())
                                         : nullptr;
}

/** The input's information of `array`, or nullptr when the input has no such array. */
vtkPVArrayInformation* GetArrayInformation(vtkSMProxy* repr, const ColorArray& array)
{
  unsigned int port = 0;
  vtkSMSourceProxy* input = GetInput(repr, &port);
  if (!input || !array.IsSet() || IsGhostArray(array.Name.c_str()))
  {
    return nullptr;
  }
  return input->GetDataInformation(port)->GetArrayInformation(
    array.Name.c_str(), array.Association);
}

/** Whether the colouring list (the ColorArrayName domain) offers `array`. */
bool IsListed(vtkSMArrayListDomain* domain, const ColorArray& array)
{
  for (unsigned int i = 0, n = domain ? domain->GetNumberOfStrings() : 0; i < n; ++i)
  {
    if (domain->GetFieldAssociation(i) == array.Association && array.Name == domain->GetString(i))
    {
      return true;
    }
  }
  return false;
}

/** Step 1 of the class description, after the current ColorArrayName: active scalars, then
 * ParaView's choice for "Volume". */
ColorArray ChooseArray(vtkSMPVRepresentationProxy* repr)
{
  ColorArray chosen;
  vtkSMProperty* property = repr->GetProperty("ColorArrayName");
  auto* domain = property ? property->FindDomain<vtkSMArrayListDomain>() : nullptr;
  unsigned int port = 0;
  vtkSMSourceProxy* input = GetInput(repr, &port);
  if (!domain || !input)
  {
    return chosen;
  }
  vtkPVDataInformation* data = input->GetDataInformation(port);
  for (int association : { vtkDataObject::POINT, vtkDataObject::CELL })
  {
    vtkPVDataSetAttributesInformation* attributes = data->GetAttributeInformation(association);
    vtkPVArrayInformation* scalars =
      attributes ? attributes->GetAttributeInformation(vtkDataSetAttributes::SCALARS) : nullptr;
    if (scalars && scalars->GetName() && !IsGhostArray(scalars->GetName()))
    {
      chosen.Association = association;
      chosen.Name = scalars->GetName();
      if (IsListed(domain, chosen))
      {
        return chosen;
      }
    }
  }
  chosen = ColorArray();
  for (unsigned int i = 0, n = domain->GetNumberOfStrings(); i < n; ++i)
  {
    const char* name = domain->GetString(i);
    if (!name || !name[0] || IsGhostArray(name))
    {
      continue;
    }
    const int association = domain->GetFieldAssociation(i);
    if (!chosen.IsSet() ||
      (chosen.Association != vtkDataObject::POINT && association == vtkDataObject::POINT))
    {
      chosen.Association = association;
      chosen.Name = name;
    }
  }
  return chosen;
}

/** Step 3 of the class description: log scale for a density-like array. */
void ApplyDensityRule(vtkSMPVRepresentationProxy* repr, const ColorArray& array)
{
  vtkSMProxy* lut = vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy();
  vtkSMProxy* opacity = vtkSMPropertyHelper(repr, "ScalarOpacityFunction", true).GetAsProxy();
  vtkPVArrayInformation* info = GetArrayInformation(repr, array);
  if (!lut || !info || info->GetNumberOfComponents() != 1 ||
    vtkSMPropertyHelper(lut, "UseLogScale", true).GetAsInt() != 0 ||
    vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", true).GetAsInt() ==
      vtkSMTransferFunctionManager::NEVER)
  {
    return;
  }
  unsigned int port = 0;
  vtkSMSourceProxy* input = GetInput(repr, &port);
  vtkNew<vtkSinglePassAMRPositiveRangeInformation> range;
  range->SetPortNumber(static_cast<int>(port));
  range->SetFieldAssociation(array.Association);
  range->SetArrayName(array.Name.c_str());
  input->GatherInformation(range);
  if (!range->IsDensityLike())
  {
    return;
  }
  // [smallest positive value, maximum], then the points moved to log space keeping their
  // relative places (what the colour-map editor's "Use log scale" does)
  for (vtkSMProxy* function : { lut, opacity })
  {
    if (!function || !function->GetProperty("UseLogScale"))
    {
      continue;
    }
    vtkSMTransferFunctionProxy::RescaleTransferFunction(
      function, range->GetMinimumPositive(), range->GetMaximum(), /*extend=*/false);
    vtkSMTransferFunctionProxy::MapControlPointsToLogSpace(function);
    vtkSMPropertyHelper(function, "UseLogScale").Set(1);
    function->UpdateVTKObjects();
  }
}
}

vtkStandardNewMacro(vtkSMSinglePassAMRVolumeRepresentationProxy);

//------------------------------------------------------------------------------
vtkSMSinglePassAMRVolumeRepresentationProxy::vtkSMSinglePassAMRVolumeRepresentationProxy() =
  default;

//------------------------------------------------------------------------------
vtkSMSinglePassAMRVolumeRepresentationProxy::~vtkSMSinglePassAMRVolumeRepresentationProxy()
{
  if (vtkSMProxy* parent = this->ObservedParent)
  {
    parent->RemoveObserver(this->PropertyObserver);
    parent->RemoveObserver(this->UpdateObserver);
  }
}

//------------------------------------------------------------------------------
void vtkSMSinglePassAMRVolumeRepresentationProxy::CreateVTKObjects()
{
  this->Superclass::CreateVTKObjects();
  vtkSMProxy* parent = this->GetParentProxy();
  if (!this->ObjectsCreated || !parent || this->ObservedParent == parent)
  {
    return;
  }
  this->ObservedParent = parent;
  this->PropertyObserver = parent->AddObserver(vtkCommand::UpdatePropertyEvent, this,
    &vtkSMSinglePassAMRVolumeRepresentationProxy::OnParentPropertyUpdated);
  this->UpdateObserver = parent->AddObserver(
    vtkCommand::UpdateEvent, this, &vtkSMSinglePassAMRVolumeRepresentationProxy::OnParentUpdated);
}

//------------------------------------------------------------------------------
void vtkSMSinglePassAMRVolumeRepresentationProxy::OnParentPropertyUpdated(
  vtkObject* caller, unsigned long, void* name)
{
  auto* parent = vtkSMProxy::SafeDownCast(caller);
  if (!parent || !name || std::strcmp(static_cast<const char*>(name), "Representation") != 0)
  {
    return;
  }
  const char* value = vtkSMPropertyHelper(parent, "Representation", true).GetAsString();
  const std::string representation = value ? value : "";
  if (representation != this->LastRepresentation && representation == GetRepresentationTypeName())
  {
    // acted on in OnParentUpdated: while the parent pushes its properties, properties set here
    // would not be pushed
    this->SwitchPending = true;
  }
  this->LastRepresentation = representation;
}

//------------------------------------------------------------------------------
void vtkSMSinglePassAMRVolumeRepresentationProxy::OnParentUpdated(
  vtkObject* caller, unsigned long, void*)
{
  if (!this->SwitchPending)
  {
    return;
  }
  this->SwitchPending = false;
  auto* parent = vtkSMPVRepresentationProxy::SafeDownCast(caller);
  vtkSMSessionProxyManager* pxm = parent ? parent->GetSessionProxyManager() : nullptr;
  if (!parent || (pxm && pxm->GetInLoadXMLState()))
  {
    // a state file sets the array and colour map it saved
    return;
  }
  // a display with no array to colour by counts as not switched yet
  const bool first = !this->DefaultsApplied;
  this->DefaultsApplied =
    vtkSMSinglePassAMRVolumeRepresentationProxy::ApplyDefaults(parent, first) || !first;
}

//------------------------------------------------------------------------------
bool vtkSMSinglePassAMRVolumeRepresentationProxy::ApplyDefaults(
  vtkSMPVRepresentationProxy* parent, bool first)
{
  if (!parent || !parent->GetProperty("ColorArrayName"))
  {
    return false;
  }
  vtkSMPropertyHelper colorArray(parent, "ColorArrayName");
  ColorArray current;
  if (parent->GetUsingScalarColoring())
  {
    current.Association = colorArray.GetInputArrayAssociation();
    current.Name = colorArray.GetInputArrayNameToProcess();
  }
  const bool valid = GetArrayInformation(parent, current) != nullptr;
  const bool mapped = vtkSMPropertyHelper(parent, "LookupTable", true).GetAsProxy() != nullptr;
  if (valid && mapped && !first)
  {
    return true; // coloured already: kept as it is (as ParaView's "Volume")
  }
  const ColorArray array = valid ? current : ChooseArray(parent);
  if (!array.IsSet())
  {
    return false;
  }
  if (!(valid && mapped))
  {
    // what vtkSMPVRepresentationProxy::SetRepresentationType does for "Volume"
    parent->SetScalarColoring(array.Name.c_str(), array.Association);
    parent->RescaleTransferFunctionToDataRange(/*extend=*/true);
  }
  ApplyDensityRule(parent, array);
  return parent->GetUsingScalarColoring();
}

//------------------------------------------------------------------------------
void vtkSMSinglePassAMRVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "LastRepresentation: " << this->LastRepresentation << "\n";
  os << indent << "DefaultsApplied: " << this->DefaultsApplied << "\n";
}
