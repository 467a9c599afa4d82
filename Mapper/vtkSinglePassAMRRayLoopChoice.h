// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRRayLoopChoice.h
 * @brief   which loop structure the single-pass shader marches its rays with
 *
 * Private to the module; no OpenGL, no VTK, so that the rule is tested on its own
 * (Mapper.RayLoopChoice.*). The setting's values and names are amrsp::RayLoop's (amrsp/RayLoop.h);
 * vtkSinglePassAMRVolumeMapper::RayLoops has the same values (a static_assert in the mapper).
 */
#ifndef vtkSinglePassAMRRayLoopChoice_h
#define vtkSinglePassAMRRayLoopChoice_h

#include "amrsp/RayLoop.h"

/**
 * The loop a frame uses. Auto: the flat loop on a GPU, the nested loops on a CPU driver (Mesa's
 * llvmpipe, softpipe, or zink on lavapipe). A GPU runs 32 pixels in lockstep, and the work
 * counters predict fewer lockstep steps for the flat loop (amrsp/WorkCounters.h; at 512x512
 * datasets 2 and 3 8.87 and 11.47 per pixel against 11.25 and 15.22); a CPU driver runs no
 * lockstep groups of that width, and there the flat loop measured 30-42 % slower
 * (docs/performance.md, "The flat loop"). The image is the same either way.
 */
inline amrsp::RayLoop vtkSinglePassAMRChooseRayLoop(amrsp::RayLoop requested, bool cpuDriver)
{
  if (requested != amrsp::RayLoop::Auto)
  {
    return requested;
  }
  return cpuDriver ? amrsp::RayLoop::Nested : amrsp::RayLoop::Flat;
}

#endif
