// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The lighting settings of a render: vtkVolumeProperty's shading parameters, one light and the
/// shadow-ray settings. The rules that use them are in amrsp/Shading.h.

#include <glm/glm.hpp>

namespace amrsp
{

/// vtkVolumeProperty's shading parameters, one light (vtkLight) and the shadow-ray settings.
struct Lighting
{
  bool Shade = false; ///< vtkVolumeProperty::ShadeOn
  double Ambient = 0.1;
  double Diffuse = 0.7;
  double Specular = 0.2;
  double SpecularPower = 10.0;
  /// The light: a headlight follows the camera (position = camera position, focal point = the
  /// camera's focal point, directional), else Position/FocalPoint/Positional as set (world).
  bool Headlight = true;
  bool Positional = false;
  glm::dvec3 Position{ 0.0, 0.0, 1.0 };
  glm::dvec3 FocalPoint{ 0.0 };
  glm::dvec3 Colour{ 1.0 }; ///< diffuse colour times intensity
  bool Shadows = false;
  double ShadowStep = 0.0; ///< world units; must be > 0 when Shadows is on
};

} // namespace amrsp
