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
 * The loop a frame uses. Auto: the nested loops, everywhere. The work counters predict fewer
 * lockstep steps for the flat loop (amrsp/WorkCounters.h: at 1024x1024 dataset 3 10.90 per pixel
 * against 13.08), but on an NVIDIA H200 it measured slower with both casters (compute caster,
 * dataset 3 7.15 ms against 5.52, a billion cells 16.0 against 14.6, dataset 2 5.34 against
 * 3.84), and on a CPU driver, which runs no lockstep groups of that width, 30-42 % slower
 * (docs/performance.md, "On an NVIDIA H200" and "The flat loop"). The image is the same either
 * way.
 */
inline amrsp::RayLoop vtkSinglePassAMRChooseRayLoop(amrsp::RayLoop requested)
{
  return requested == amrsp::RayLoop::Auto ? amrsp::RayLoop::Nested : requested;
}

#endif
