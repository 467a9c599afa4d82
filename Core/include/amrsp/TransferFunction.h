// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Transfer functions with the conventions of VTK's vtkColorTransferFunction and
/// vtkPiecewiseFunction with clamping: piecewise linear in the scalar, constant beyond the end
/// points. Opacity applies unchanged over UnitDistance (vtkVolumeProperty's
/// ScalarOpacityUnitDistance, world units).

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace amrsp
{

struct TransferFunction
{
  struct ColorPoint
  {
    double X;
    glm::dvec3 Rgb;
  };
  struct OpacityPoint
  {
    double X;
    double Opacity;
  };
  std::vector<ColorPoint> Color;     ///< sorted by X
  std::vector<OpacityPoint> Opacity; ///< sorted by X
  double UnitDistance = 1.0;         ///< world length over which Opacity applies unchanged
  /// Log scale (vtkColorTransferFunction::SetScaleToLog10, vtkPiecewiseFunction::UseLogScale):
  /// between two control points with positive X the value is interpolated linearly in log10 of
  /// the scalar; a scalar at or below 0 takes the first point's value. The GPU mappers then
  /// index their table by log10 of the scalar (TransferFunctionIsLogarithmic).
  bool ColorLogScale = false;
  bool OpacityLogScale = false;

  glm::dvec3 EvaluateColor(double s) const;
  double EvaluateOpacity(double s) const;
  /// Whether the colours or the opacities are log-scaled.
  bool IsLogarithmic() const { return this->ColorLogScale || this->OpacityLogScale; }

  /// A named preset spanning [lo, hi]: "default" (blue-white-red, opacity ramp), "grey",
  /// "hot", "grey-opaque" (grey levels at opacity 1, for the intensity projections), "sparse"
  /// ("hot" colours, zero opacity below 60 % of the range: for empty-space skipping). Throws
  /// std::invalid_argument for an unknown name.
  static TransferFunction Preset(
    const std::string& name, double lo, double hi, double unitDistance);
  static std::vector<std::string> PresetNames();
};

} // namespace amrsp
