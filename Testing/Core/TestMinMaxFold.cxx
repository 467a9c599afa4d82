// SPDX-License-Identifier: BSD-3-Clause
// The vectorised min/max fold against the scalar rule it replaces (lo = v < lo ? v : lo): rows of
// every length from 0 to 40 at strides, NaN never taken, +-Inf taken, incoming bounds kept, and
// the bounds of the finite range of a hierarchy with infinities.
#include "amrsp/MinMaxFold.h"
#include "amrsp/RayCastingData.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace
{
using namespace amrsp;

void ScalarFold(
  const float* first, int64_t rowLength, int64_t rowStride, int64_t rows, float& lo, float& hi)
{
  for (int64_t r = 0; r < rows; ++r)
  {
    for (int64_t i = 0; i < rowLength; ++i)
    {
      const float v = first[r * rowStride + i];
      lo = v < lo ? v : lo;
      hi = v > hi ? v : hi;
    }
  }
}

/// Values in [-1000, 1000], with NaN, +Inf and -Inf at the given per-value odds.
std::vector<float> RandomValues(std::size_t n, double nanOdds, double infOdds, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1000.0f, 1000.0f);
  std::uniform_real_distribution<double> odds(0.0, 1.0);
  std::vector<float> v(n);
  for (float& x : v)
  {
    const double o = odds(rng);
    x = o < nanOdds               ? std::numeric_limits<float>::quiet_NaN()
      : o < nanOdds + infOdds / 2 ? std::numeric_limits<float>::infinity()
      : o < nanOdds + infOdds     ? -std::numeric_limits<float>::infinity()
                                  : value(rng);
  }
  return v;
}

TEST(MinMaxFold, RowsOfEveryLengthGiveTheScalarBounds)
{
  const std::vector<float> values = RandomValues(64 * 50, 0.05, 0.0, 1);
  int checked = 0;
  for (int64_t length = 0; length <= 40; ++length)
  {
    for (const int64_t stride : { length, length + 3, int64_t(64) })
    {
      for (const int64_t rows : { 1, 2, 7 })
      {
        for (int64_t offset = 0; offset < 5; ++offset)
        {
          float lo = FLT_MAX, hi = -FLT_MAX, slo = FLT_MAX, shi = -FLT_MAX;
          FoldMinMaxRows(values.data() + offset, length, stride, rows, lo, hi);
          ScalarFold(values.data() + offset, length, stride, rows, slo, shi);
          ASSERT_EQ(lo, slo) << "length " << length << " stride " << stride << " rows " << rows;
          ASSERT_EQ(hi, shi) << "length " << length << " stride " << stride << " rows " << rows;
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 41 * 3 * 3 * 5);
}

TEST(MinMaxFold, NaNIsNeverTakenAndInfinitiesAre)
{
  std::vector<float> values(37, std::numeric_limits<float>::quiet_NaN());
  float lo = FLT_MAX, hi = -FLT_MAX;
  FoldMinMax(values.data(), 37, lo, hi);
  EXPECT_EQ(lo, FLT_MAX); // all NaN: the bounds stay empty
  EXPECT_EQ(hi, -FLT_MAX);
  values[33] = 2.5f; // in the tail of a row of 37 (read by the overlapping load)
  values[3] = -std::numeric_limits<float>::infinity();
  FoldMinMax(values.data(), 37, lo, hi);
  EXPECT_EQ(lo, -std::numeric_limits<float>::infinity());
  EXPECT_EQ(hi, 2.5f);
}

TEST(MinMaxFold, IncomingBoundsAreKept)
{
  const std::vector<float> values = { 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f, 8.0f, 9.0f };
  float lo = -5.0f, hi = 50.0f;
  FoldMinMax(values.data(), static_cast<int64_t>(values.size()), lo, hi);
  EXPECT_EQ(lo, -5.0f);
  EXPECT_EQ(hi, 50.0f);
}

TEST(MinMaxFold, LongRunsWithInfinitiesGiveTheScalarBounds)
{
  for (unsigned seed = 0; seed < 4; ++seed)
  {
    const std::vector<float> values = RandomValues(100003, 0.01, seed % 2 ? 0.001 : 0.0, seed);
    float lo = FLT_MAX, hi = -FLT_MAX, slo = FLT_MAX, shi = -FLT_MAX;
    FoldMinMax(values.data(), static_cast<int64_t>(values.size()), lo, hi);
    ScalarFold(values.data(), static_cast<int64_t>(values.size()), 0, 1, slo, shi);
    EXPECT_EQ(lo, slo);
    EXPECT_EQ(hi, shi);
  }
}

TEST(MinMaxFold, FiniteValueRangeSkipsInfinitiesAndNaN)
{
  Hierarchy h = test::PaperExample();
  ASSERT_TRUE(h.HasValues());
  double plain[2];
  ASSERT_TRUE(FiniteValueRange(h, plain));
  // an infinity and a NaN in a grid's longest run: the finite range is unchanged
  h.Values[0].data()[1] = std::numeric_limits<float>::infinity();
  h.Values[0].data()[2] = std::numeric_limits<float>::quiet_NaN();
  h.Values[1].data()[0] = -std::numeric_limits<float>::infinity();
  double withInf[2];
  ASSERT_TRUE(FiniteValueRange(h, withInf));
  double expected[2] = { DBL_MAX, -DBL_MAX };
  for (const GridValues& values : h.Values)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      const float v = values.data()[i];
      if (std::isfinite(v))
      {
        expected[0] = std::min<double>(expected[0], v);
        expected[1] = std::max<double>(expected[1], v);
      }
    }
  }
  EXPECT_EQ(withInf[0], expected[0]);
  EXPECT_EQ(withInf[1], expected[1]);
}

} // namespace
