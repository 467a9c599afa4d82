// SPDX-License-Identifier: BSD-3-Clause
// The AUTO_CASTER rule on its own (vtkSinglePassAMRRayCasterChoice.h): the compute shader on a GPU
// with compute shaders, the fragment shader on a CPU driver, and the fragment shader with a reason
// wherever the context has no compute shaders.
#include "vtkSinglePassAMRRayCasterChoice.h"

#include <gtest/gtest.h>

namespace
{
using amrsp::RayCaster;

vtkSinglePassAMRRayCasterFacts Facts(bool compute, bool cpuDriver)
{
  vtkSinglePassAMRRayCasterFacts f;
  f.Compute = compute;
  f.NoCompute = compute ? "" : "no compute shaders here";
  f.CpuDriver = cpuDriver;
  return f;
}
} // namespace

TEST(RayCasterChoice, AutoTakesTheComputeShaderOnAGpu)
{
  const auto d = vtkSinglePassAMRChooseRayCaster(RayCaster::Auto, Facts(true, false));
  EXPECT_EQ(d.Caster, RayCaster::Compute);
  EXPECT_TRUE(d.FallbackReason.empty());
}

TEST(RayCasterChoice, AutoTakesTheFragmentShaderOnACpuDriver)
{
  const auto d = vtkSinglePassAMRChooseRayCaster(RayCaster::Auto, Facts(true, true));
  EXPECT_EQ(d.Caster, RayCaster::Fragment);
  EXPECT_TRUE(d.FallbackReason.empty()); // a choice, not a fallback: nothing to warn about
}

TEST(RayCasterChoice, ComputeIsKeptWhereTheContextHasIt)
{
  for (bool cpu : { false, true })
  {
    const auto d = vtkSinglePassAMRChooseRayCaster(RayCaster::Compute, Facts(true, cpu));
    EXPECT_EQ(d.Caster, RayCaster::Compute);
    EXPECT_TRUE(d.FallbackReason.empty());
  }
}

TEST(RayCasterChoice, WithoutComputeShadersTheFragmentShaderRunsAndSaysWhy)
{
  for (RayCaster requested : { RayCaster::Compute, RayCaster::Auto })
  {
    for (bool cpu : { false, true })
    {
      const auto d = vtkSinglePassAMRChooseRayCaster(requested, Facts(false, cpu));
      EXPECT_EQ(d.Caster, RayCaster::Fragment);
      EXPECT_EQ(d.FallbackReason, "no compute shaders here");
    }
  }
}

TEST(RayCasterChoice, FragmentIsKeptEverywhere)
{
  for (bool compute : { false, true })
  {
    for (bool cpu : { false, true })
    {
      const auto d = vtkSinglePassAMRChooseRayCaster(RayCaster::Fragment, Facts(compute, cpu));
      EXPECT_EQ(d.Caster, RayCaster::Fragment);
      EXPECT_TRUE(d.FallbackReason.empty());
    }
  }
}

TEST(RayCasterChoice, NamesReadBack)
{
  for (RayCaster c : { RayCaster::Fragment, RayCaster::Compute, RayCaster::Auto })
  {
    RayCaster parsed = RayCaster::Auto;
    ASSERT_TRUE(amrsp::ParseRayCaster(amrsp::RayCasterName(c), parsed));
    EXPECT_EQ(parsed, c);
  }
  RayCaster unchanged = RayCaster::Compute;
  EXPECT_FALSE(amrsp::ParseRayCaster("vertex", unchanged));
  EXPECT_FALSE(amrsp::ParseRayCaster(nullptr, unchanged));
  EXPECT_EQ(unchanged, RayCaster::Compute);
}
