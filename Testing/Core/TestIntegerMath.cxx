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

/// Samples (k + offset) / n of a segment that crosses `cells` cells between two faces of one
/// axis that lie exactly on a cell face, counted in exact rational arithmetic: an offset in
/// [0.25, 1) is a float's exact value m / 2^25, so sample k is on a face when
/// (k 2^25 + m) cells / (n 2^25) is an integer.
int SamplesOnFaces(float offset, int cells, int n)
{
  const long long scale = 1LL << 25;
  const long long m = static_cast<long long>(static_cast<double>(offset) * scale);
  EXPECT_EQ(static_cast<double>(m) / scale, static_cast<double>(offset)); // exactly m / 2^24
  int onFaces = 0;
  for (int k = 0; k < n; ++k)
  {
    onFaces += ((k * scale + m) * cells) % (n * scale) == 0 ? 1 : 0;
  }
  return onFaces;
}

TEST(SampleStep, NoSampleSitsExactlyOnACellFace)
{
  // segments between two faces of one axis, up to 2048 cells (a texture's edge) with one to
  // three samples per cell: with midpoints the middle sample of an odd n over an even span is
  // on a face (the wrong rule), with SampleOffset none is
  long long midpointFaces = 0, offsetFaces = 0;
  for (int cells = 1; cells <= 2048; cells = cells < 64 ? cells + 1 : cells * 2)
  {
    for (int n = cells; n <= 3 * cells; ++n)
    {
      midpointFaces += SamplesOnFaces(0.5f, cells, n);
      offsetFaces += SamplesOnFaces(SampleOffset, cells, n);
    }
  }
  EXPECT_GT(midpointFaces, 1000);
  EXPECT_EQ(offsetFaces, 0);
  // and the samples stay inside their steps, away from the ends
  EXPECT_GT(SampleOffset, 0.4f);
  EXPECT_LT(SampleOffset, 0.5f);
}
