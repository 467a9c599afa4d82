// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The camera of the CPU integrators, with VTK's conventions so that images can be compared: a
/// pinhole at Position looking at FocalPoint, ViewAngle the full vertical angle in degrees; or
/// parallel projection with ParallelScale = half the view height (world units). Pixel (i, j) is
/// sampled through its centre; row 0 is the bottom row (as vtkImageData).

#include <glm/glm.hpp>

namespace amrsp
{

struct Camera
{
  glm::dvec3 Position{ 0.0, 0.0, 1.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::dvec3 ViewUp{ 0.0, 1.0, 0.0 };
  double ViewAngle = 30.0; ///< degrees, full vertical angle
  bool Parallel = false;
  double ParallelScale = 1.0;

  /// World-space ray through the pixel position (px, py) in [0, width] x [0, height].
  void Ray(
    int width, int height, double px, double py, glm::dvec3& origin, glm::dvec3& direction) const;

  /// vtkRenderer::ResetCamera for the box [lo, hi] seen along -z with +y up: focal point at the
  /// centre, distance = half diagonal / sin(ViewAngle / 2), ParallelScale = half diagonal.
  static Camera ResetTo(const glm::dvec3& lo, const glm::dvec3& hi);
  /// vtkCamera::Azimuth: rotates the position about ViewUp through the focal point (degrees).
  void Azimuth(double degrees);
  /// vtkCamera::Elevation: rotates the position about the camera's left axis (degrees).
  void Elevation(double degrees);
  /// vtkCamera::OrthogonalizeViewUp.
  void OrthogonalizeViewUp();
  /// vtkCamera::Zoom: divides ViewAngle (perspective) or ParallelScale (parallel).
  void Zoom(double factor);
};

} // namespace amrsp
