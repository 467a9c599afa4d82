// SPDX-License-Identifier: BSD-3-Clause
// The AUTO_LOOP rule on its own (vtkSinglePassAMRRayLoopChoice.h): the flat loop on a GPU, the
// nested loops on a CPU driver, an explicit request kept as it is.
#include "vtkSinglePassAMRRayLoopChoice.h"

#include <gtest/gtest.h>

namespace
{
using Loop = amrsp::RayLoop;

TEST(RayLoopChoice, AutoTakesTheFlatLoopOnAGpu)
{
  EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Auto, false), Loop::Flat);
}

TEST(RayLoopChoice, AutoTakesTheNestedLoopsOnACpuDriver)
{
  EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Auto, true), Loop::Nested);
}

TEST(RayLoopChoice, AnExplicitLoopIsKept)
{
  for (const bool cpu : { false, true })
  {
    EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Nested, cpu), Loop::Nested);
    EXPECT_EQ(vtkSinglePassAMRChooseRayLoop(Loop::Flat, cpu), Loop::Flat);
  }
}
} // namespace
