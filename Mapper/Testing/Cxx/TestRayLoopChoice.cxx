// SPDX-License-Identifier: BSD-3-Clause
// The AUTO_LOOP rule on its own (vtkSinglePassAMRRayLoopChoice.h): the nested loops, which
// measured faster than the flat loop on an NVIDIA H200 and on llvmpipe; an explicit request kept
// as it is.
#include "vtkSinglePassAMRRayLoopChoice.h"

#include <gtest/gtest.h>

namespace
{
using Loop = amrsp::RayLoop;

TEST(RayLoopChoice, AutoTakesTheNestedLoops)
{
  EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Auto), Loop::Nested);
}

TEST(RayLoopChoice, AnExplicitLoopIsKept)
{
  EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Nested), Loop::Nested);
  EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Flat), Loop::Flat);
}
} // namespace
