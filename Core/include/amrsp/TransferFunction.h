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

  glm::dvec3 EvaluateColor(double s) const;
  double EvaluateOpacity(double s) const;

  /// A named preset spanning [lo, hi]: "default" (blue-white-red, opacity ramp), "grey",
  /// "hot", "grey-opaque" (grey levels at opacity 1, for the intensity projections), "sparse"
  /// ("hot" colours, zero opacity below 60 % of the range: for empty-space skipping). Throws
  /// std::invalid_argument for an unknown name.
  static TransferFunction Preset(
    const std::string& name, double lo, double hi, double unitDistance);
  static std::vector<std::string> PresetNames();
};

} // namespace amrsp
