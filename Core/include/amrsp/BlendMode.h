// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// vtkVolumeMapper's blend modes as our renderers take them: the one enumeration and name table
/// of the setting, used by the CPU integrators (RenderSettings::Blend), the single-pass shader
/// (its AMRSP_BLEND_MODE is the value), and the amrsp tool (--blend).

#include "amrsp/SettingNames.h"

namespace amrsp
{

/// Maximum/Minimum keep the extreme scalar along the ray, Average its length-weighted mean; the
/// pixel is then the transfer function's colour and (uncorrected) opacity of that scalar over the
/// background. IsoSurface composites the crossings of RenderSettings::IsoValues (rules in
/// amrsp/Shading.h).
enum class BlendMode : int
{
  Composite = 0,
  Maximum = 1,
  Minimum = 2,
  Average = 3,
  IsoSurface = 4
};

constexpr SettingName<BlendMode> BlendModeNames[] = {
  { BlendMode::Composite, "composite" },
  { BlendMode::Maximum, "maximum" },
  { BlendMode::Minimum, "minimum" },
  { BlendMode::Average, "average" },
  { BlendMode::IsoSurface, "iso" },
};

/// "composite", "maximum", "minimum", "average", "iso", or "none".
inline const char* BlendModeName(BlendMode blend)
{
  return NameIn(BlendModeNames, blend);
}

} // namespace amrsp
