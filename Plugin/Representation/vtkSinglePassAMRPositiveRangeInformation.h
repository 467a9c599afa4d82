// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRPositiveRangeInformation
 * @brief   finite range and smallest positive value of one array, over every rank's blocks
 *
 * Gathered from a source proxy (vtkSMProxy::GatherInformation) the way ParaView gathers its data
 * information: the parameters (output port, array association and name) travel to the data
 * server, CopyFromObject scans the port's output there, and the ranks' results are merged with
 * AddInformation. vtkPVArrayInformation has the range but not the smallest positive value, which
 * the density-like rule of the "AMR Single-Pass Volume" defaults needs when an array's minimum
 * is zero (vtkSMSinglePassAMRVolumeRepresentationProxy).
 *
 * Scanned: component 0 of the named point or cell array in every leaf dataset of the output
 * (a composite dataset's blocks, or the dataset itself). Skipped: non-finite values and the
 * elements whose ghost type marks them duplicate, hidden or refined (cells covered by a finer AMR
 * level, which the mapper never samples).
 *
 * Invariants: after a gather, NumberOfValues counts the values scanned; when it is positive,
 * Minimum <= Maximum over them, and MinimumPositive is the smallest value > 0 among them, or 0
 * when none is positive.
 */
#ifndef vtkSinglePassAMRPositiveRangeInformation_h
#define vtkSinglePassAMRPositiveRangeInformation_h

#include "vtkPVInformation.h"
#include "vtkSinglePassAMRParaViewModule.h" // for export macro

#include <string> // for ivar

class vtkDataObject;

class VTKSINGLEPASSAMRPARAVIEW_EXPORT vtkSinglePassAMRPositiveRangeInformation
  : public vtkPVInformation
{
public:
  static vtkSinglePassAMRPositiveRangeInformation* New();
  vtkTypeMacro(vtkSinglePassAMRPositiveRangeInformation, vtkPVInformation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * What to scan: the output port of the source the information is gathered from, and the array
   * (association vtkDataObject::POINT or CELL, name).
   */
  vtkSetMacro(PortNumber, int);
  vtkGetMacro(PortNumber, int);
  vtkSetMacro(FieldAssociation, int);
  vtkGetMacro(FieldAssociation, int);
  void SetArrayName(const char* name);
  const char* GetArrayName() const { return this->ArrayName.c_str(); }
  ///@}

  ///@{
  /**
   * The result (see the class invariants).
   */
  vtkGetMacro(NumberOfValues, vtkIdType);
  vtkGetMacro(Minimum, double);
  vtkGetMacro(Maximum, double);
  vtkGetMacro(MinimumPositive, double);
  ///@}

  /**
   * The density-like rule: true when every value is >= 0, some are positive, and the largest
   * exceeds the smallest positive one by more than `decades` decades (Maximum / MinimumPositive
   * > 10^decades). The defaults use 3 decades.
   */
  bool IsDensityLike(double decades = 3.0) const;

  ///@{
  /**
   * vtkPVInformation: scan a vtkAlgorithm's output port (or a vtkDataObject), merge the ranks'
   * results, and move the parameters and the result between processes.
   */
  void CopyFromObject(vtkObject* object) override;
  void AddInformation(vtkPVInformation* other) override;
  void CopyToStream(vtkClientServerStream* stream) override;
  void CopyFromStream(const vtkClientServerStream* stream) override;
  void CopyParametersToStream(vtkMultiProcessStream& stream) override;
  void CopyParametersFromStream(vtkMultiProcessStream& stream) override;
  ///@}

protected:
  vtkSinglePassAMRPositiveRangeInformation();
  ~vtkSinglePassAMRPositiveRangeInformation() override;

private:
  vtkSinglePassAMRPositiveRangeInformation(
    const vtkSinglePassAMRPositiveRangeInformation&) = delete;
  void operator=(const vtkSinglePassAMRPositiveRangeInformation&) = delete;

  void ResetResult();
  void ScanDataObject(vtkDataObject* data);
  void AddValue(double value);

  int PortNumber = 0;
  int FieldAssociation = 1; // vtkDataObject::CELL
  std::string ArrayName;
  vtkIdType NumberOfValues = 0;
  double Minimum = 0.0;
  double Maximum = 0.0;
  double MinimumPositive = 0.0;
};

#endif
