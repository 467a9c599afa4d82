// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRRayCasterChoice.h
 * @brief   which shader stage casts the single-pass mapper's rays
 *
 * Private to the module; no OpenGL, no VTK, so that the rule is tested on its own
 * (Mapper.RayCasterChoice.*). The setting's values and names are amrsp::RayCaster's
 * (amrsp/RayCaster.h); vtkSinglePassAMRVolumeMapper::RayCasters has the same values.
 */
#ifndef vtkSinglePassAMRRayCasterChoice_h
#define vtkSinglePassAMRRayCasterChoice_h

#include "amrsp/RayCaster.h"

#include <string>

/// What the context offers the casters.
struct vtkSinglePassAMRRayCasterFacts
{
  bool Compute = false;   ///< compute shaders and image stores (OpenGL 4.3, or 4.2 with the ARB)
  std::string NoCompute;  ///< why not, when Compute is false
  bool CpuDriver = false; ///< Mesa's llvmpipe, softpipe, or zink on lavapipe
};

/// The caster a frame uses, and why a requested compute caster could not run.
struct vtkSinglePassAMRRayCasterDecision
{
  amrsp::RayCaster Caster = amrsp::RayCaster::Fragment;
  /// Why the fragment caster runs where Compute or Auto was asked for and the context has no
  /// compute shaders (empty otherwise).
  std::string FallbackReason;
};

/**
 * The rule. Fragment is kept. Compute and Auto need compute shaders: in a context without them
 * the fragment caster runs, with the reason (the mapper warns once). Auto: the compute caster on a
 * GPU with compute shaders, where it runs on every multiprocessor while fragments run only where
 * the chip rasterises (on NVIDIA's H100 and H200, 4 of 132 SMs; docs/design.md); on a CPU driver
 * the fragment caster, which measured as fast or faster there (docs/performance.md, "The
 * compute caster").
 */
inline vtkSinglePassAMRRayCasterDecision vtkSinglePassAMRChooseRayCaster(
  amrsp::RayCaster requested, const vtkSinglePassAMRRayCasterFacts& facts)
{
  vtkSinglePassAMRRayCasterDecision d;
  if (requested == amrsp::RayCaster::Fragment)
  {
    return d;
  }
  if (requested == amrsp::RayCaster::Compute)
  {
    if (facts.Compute)
    {
      d.Caster = amrsp::RayCaster::Compute;
    }
    else
    {
      d.FallbackReason = facts.NoCompute;
    }
    return d;
  }
  if (!facts.Compute)
  {
    d.FallbackReason = facts.NoCompute;
    return d;
  }
  d.Caster = facts.CpuDriver ? amrsp::RayCaster::Fragment : amrsp::RayCaster::Compute;
  return d;
}

#endif
