// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperTransferFunctionTable.h
 * @brief   a volume property's colour and opacity as one RGBA table texture (private to the module)
 *
 * Shared by both mappers so that they colour a scalar identically, linear or log-scaled.
 */
#ifndef vtkAMRMapperTransferFunctionTable_h
#define vtkAMRMapperTransferFunctionTable_h

#include "vtkSmartPointer.h"
#include "vtkTextureObject.h" // for GetTexture
#include "vtkTimeStamp.h"
#include "vtkType.h"

#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkVolumeProperty;
class vtkWindow;

/**
 * The transfer function of component 0 of a vtkVolumeProperty as an RGBA32F table of
 * Size entries (colour or grey, and the scalar opacity per unit distance). The table
 * spans the union of the functions' ranges (both clamp beyond their end points); when the
 * functions have no range, the data's scalar range.
 */
class vtkAMRMapperTransferFunctionTable
{
public:
  /// Entries of the RGBA table (linear filtering between entries).
  static constexpr int Size = 4096;

  /// Re-tabulates when the property, its MTime or `dataTime` (the data's build time) changed.
  /// Returns false when the texture cannot be created.
  bool Update(vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property,
    const double scalarRange[2], const vtkTimeStamp& dataTime);
  vtkTextureObject* GetTexture() const { return this->Texture; }
  /// The opacity column of the table (Size entries) and when it was last tabulated.
  const std::vector<float>& GetOpacityTable() const { return this->Opacity; }
  vtkMTimeType GetTableTime() const { return this->Time.GetMTime(); }
  /// Scalar at the first entry and 1 / (last - first): the shader's amrspTransferRange (in
  /// log10 of the scalar when IsLogarithmic).
  void GetShaderRange(float range[2]) const;
  /// Whether the table is indexed by log10 of the scalar (a log-scaled colour or opacity
  /// function over a positive range): the shaders then need AMRSP_LOG_TRANSFER.
  bool IsLogarithmic() const { return this->Logarithmic; }
  /// The scalar in the table's units (its log10 when IsLogarithmic; -FLT_MAX at or below 0).
  float TableScalar(float scalar) const;
  /// Why a requested log scale was not used by the last Update (empty when none).
  const std::string& GetWarning() const { return this->Warning; }
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkSmartPointer<vtkTextureObject> Texture;
  vtkVolumeProperty* Property = nullptr; // identity only
  vtkMTimeType PropertyMTime = 0;
  vtkTimeStamp Time;
  double Range[2] = { 0.0, 1.0 };
  std::vector<float> Opacity;
  bool Logarithmic = false;
  std::string Warning;
};

#endif
