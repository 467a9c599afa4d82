// SPDX-License-Identifier: BSD-3-Clause
// FloorDiv / CeilDiv (amrsp/IntegerMath.h) for every sign of the operands, and the per-level
// sampling distance (amrsp/SampleStep.h).
#include "amrsp/IntegerMath.h"
#include "amrsp/SampleStep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using namespace amrsp;

static_assert(FloorDiv(-7, 2) == -4 && CeilDiv(-7, 2) == -3, "usable in constant expressions");

TEST(IntegerMath, FloorAndCeilOfEverySign)
{
  EXPECT_EQ(FloorDiv(7, 2), 3);
  EXPECT_EQ(CeilDiv(7, 2), 4);
  EXPECT_EQ(FloorDiv(-7, 2), -4);
  EXPECT_EQ(CeilDiv(-7, 2), -3);
  EXPECT_EQ(FloorDiv(7, -2), -4);
  EXPECT_EQ(CeilDiv(7, -2), -3);
  EXPECT_EQ(FloorDiv(-7, -2), 3);
  EXPECT_EQ(CeilDiv(-7, -2), 4);
  // exact quotients are not rounded
  EXPECT_EQ(FloorDiv(-8, 2), -4);
  EXPECT_EQ(CeilDiv(-8, 2), -4);
  EXPECT_EQ(FloorDiv(0, 3), 0);
  EXPECT_EQ(CeilDiv(0, -3), 0);
  EXPECT_EQ(FloorDiv(-1, 4), -1);
  EXPECT_EQ(CeilDiv(1, 4), 1);
}

TEST(IntegerMath, AgreesWithRealDivision)
{
  for (int64_t a = -50; a <= 50; ++a)
  {
    for (int64_t b = -7; b <= 7; ++b)
    {
      if (b == 0)
      {
        continue;
      }
      const double q = static_cast<double>(a) / static_cast<double>(b);
      EXPECT_EQ(FloorDiv(a, b), static_cast<int64_t>(std::floor(q))) << a << " / " << b;
      EXPECT_EQ(CeilDiv(a, b), static_cast<int64_t>(std::ceil(q))) << a << " / " << b;
    }
  }
}

TEST(IntegerMath, LargeOperands)
{
  const int64_t big = int64_t(1) << 52;
  EXPECT_EQ(FloorDiv(-big - 1, 4), -(big / 4) - 1);
  EXPECT_EQ(CeilDiv(big + 1, 4), big / 4 + 1);
}

TEST(SampleStep, SmallestCellEdgeTimesTheFactor)
{
  Hierarchy h;
  h.Spacing0 = glm::dvec3(0.5, 0.25, 1.0);
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2), glm::ivec3(2, 4, 2) };
  EXPECT_DOUBLE_EQ(LevelMinEdge(h, 0), 0.25);
  EXPECT_DOUBLE_EQ(LevelMinEdge(h, 1), 0.125);
  EXPECT_DOUBLE_EQ(LevelMinEdge(h, 2), 0.25 / 8.0);
  EXPECT_DOUBLE_EQ(LevelSampleStep(h, 1, 0.5), 0.0625);
  EXPECT_EQ(LevelSampleStep(h, 2, 0.7), LevelSampleStep(0.7, LevelMinEdge(h, 2)));
}
