// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The loop structure the single-pass shader marches its rays with: the one enumeration and name
/// table of the setting, used by the mapper (vtkSinglePassAMRVolumeMapper::RayLoops has these
/// values), the ParaView plugin, the amrsp tool (METHOD:CASTER-LOOP) and its bench ("ray_loop").
/// The images are the same; the rule that resolves Auto is the mapper's
/// (vtkSinglePassAMRRayLoopChoice.h).

#include "amrsp/SettingNames.h"

namespace amrsp
{

enum class RayLoop : int
{
  Nested = 0, ///< per segment a descent loop, then a sample loop
  Flat = 1,   ///< one loop of single descent steps, segment set-ups and samples
  Auto = 2    ///< the mapper's rule
};

constexpr SettingName<RayLoop> RayLoopNames[] = {
  { RayLoop::Auto, "auto" },
  { RayLoop::Nested, "nested" },
  { RayLoop::Flat, "flat" },
};

/// "nested", "flat", "auto", or "none".
inline const char* RayLoopName(RayLoop loop)
{
  return NameIn(RayLoopNames, loop);
}

} // namespace amrsp
