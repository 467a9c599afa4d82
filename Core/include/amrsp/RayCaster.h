// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Which shader stage casts the single-pass mapper's rays: the one enumeration and name table of
/// the setting, used by the mapper (vtkSinglePassAMRVolumeMapper::RayCasters has these values),
/// the ParaView plugin, the amrsp tool (--caster) and its bench ("caster"). The images are the
/// same; the rule that resolves Auto is the mapper's (vtkSinglePassAMRRayCasterChoice.h).

#include "amrsp/SettingNames.h"

namespace amrsp
{

enum class RayCaster : int
{
  Fragment = 0, ///< a fragment shader over the proxy box's back faces, blended into the frame
  Compute = 1,  ///< a compute shader over the rays' image, then one composite draw
  Auto = 2      ///< the mapper's rule
};

constexpr SettingName<RayCaster> RayCasterNames[] = {
  { RayCaster::Auto, "auto" },
  { RayCaster::Fragment, "fragment" },
  { RayCaster::Compute, "compute" },
};

/// "fragment", "compute", "auto", or "none" (the tool's and the bench's words).
inline const char* RayCasterName(RayCaster caster)
{
  return NameIn(RayCasterNames, caster);
}

/// The caster named `name` (RayCasterName's words); false for any other word.
inline bool ParseRayCaster(const char* name, RayCaster& caster)
{
  return ParseIn(RayCasterNames, name, caster);
}

} // namespace amrsp
