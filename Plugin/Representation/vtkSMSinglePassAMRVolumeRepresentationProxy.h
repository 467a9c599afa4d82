// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSMSinglePassAMRVolumeRepresentationProxy
 * @brief   client-side proxy of the "AMR Single-Pass Volume" representation: its defaults
 *
 * The server-manager class of the subproxy that ParaView's AMRRepresentation shows as the type
 * "AMR Single-Pass Volume" (element SinglePassAMRVolumeRepresentationProxy in
 * SinglePassAMRRepresentation.xml). It gives that type what vtkSMPVRepresentationProxy's
 * SetRepresentationType gives the types "Volume" and "Slice" by name only: an array to render and
 * a colour map for it, so that switching a display to the type draws something.
 *
 * It observes its parent (the display's AMRRepresentation proxy). When the parent's
 * "Representation" property is pushed with the value "AMR Single-Pass Volume" (the GUI's
 * representation menu, `display.Representation = ...` in Python, a representation created with
 * that type), and no state file is being loaded, then, once the parent's update has finished:
 *   1. the array: the parent's ColorArrayName when it names an array of the input; else the
 *      input's active scalars (point, then cell) when ParaView lists them for colouring; else
 *      ParaView's own choice for "Volume" (the first point array in the colouring list, else the
 *      first array), never vtkGhostType;
 *   2. when the array is not the one already coloured with a colour map, SetScalarColoring and
 *      RescaleTransferFunctionToDataRange(extend) on the parent, as ParaView does for "Volume";
 *   3. the density-like rule (the first switch of the display, and whenever step 2 ran): a
 *      one-component array whose values are all >= 0 and whose maximum exceeds its smallest
 *      positive value by more than three decades (vtkSinglePassAMRPositiveRangeInformation) gets
 *      its colour map and opacity function rescaled to [smallest positive, maximum] and mapped
 *      to log space, as the colour-map editor's "Use log scale" does, unless the colour map is
 *      in log scale already or its range is locked (AutomaticRescaleRangeMode "Never").
 * A display already coloured that is switched again keeps its array and colour map untouched.
 */
#ifndef vtkSMSinglePassAMRVolumeRepresentationProxy_h
#define vtkSMSinglePassAMRVolumeRepresentationProxy_h

#include "vtkSMRepresentationProxy.h"
#include "vtkSinglePassAMRParaViewModule.h" // for export macro
#include "vtkWeakPointer.h"                 // for ivar

#include <string> // for ivar

class vtkSMPVRepresentationProxy;

class VTKSINGLEPASSAMRPARAVIEW_EXPORT vtkSMSinglePassAMRVolumeRepresentationProxy
  : public vtkSMRepresentationProxy
{
public:
  static vtkSMSinglePassAMRVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSMSinglePassAMRVolumeRepresentationProxy, vtkSMRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The representation type this proxy stands for in its parent (the text of its
   * RepresentationType element in SinglePassAMRRepresentation.xml).
   */
  static const char* GetRepresentationTypeName() { return "AMR Single-Pass Volume"; }

  /**
   * Steps 1 to 3 of the class description on `parent` (a vtkSMPVRepresentationProxy whose type
   * is this one). `first`: the display has not been switched to this type before. Returns true
   * when an array is coloured afterwards.
   */
  static bool ApplyDefaults(vtkSMPVRepresentationProxy* parent, bool first);

protected:
  vtkSMSinglePassAMRVolumeRepresentationProxy();
  ~vtkSMSinglePassAMRVolumeRepresentationProxy() override;

  /**
   * Also starts observing the parent proxy (set by the time its subproxies are created).
   */
  void CreateVTKObjects() override;

private:
  vtkSMSinglePassAMRVolumeRepresentationProxy(
    const vtkSMSinglePassAMRVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSMSinglePassAMRVolumeRepresentationProxy&) = delete;

  void OnParentPropertyUpdated(vtkObject* caller, unsigned long event, void* name);
  void OnParentUpdated(vtkObject* caller, unsigned long event, void* data);

  vtkWeakPointer<vtkSMProxy> ObservedParent;
  unsigned long PropertyObserver = 0;
  unsigned long UpdateObserver = 0;
  // the parent's Representation value at its last push
  std::string LastRepresentation;
  // the parent switched to this type and has not finished its update yet
  bool SwitchPending = false;
  // the defaults have been applied to this display once
  bool DefaultsApplied = false;
};

#endif
