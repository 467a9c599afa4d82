// SPDX-License-Identifier: BSD-3-Clause
// amrsp::TransferFunction: VTK's piecewise-linear functions, with and without log scale.
#include "amrsp/TransferFunction.h"

#include <gtest/gtest.h>

#include <cmath>

using amrsp::TransferFunction;

namespace
{
TransferFunction TwoPoints()
{
  TransferFunction tf;
  tf.Color = { { 1.0, glm::dvec3(0.0) }, { 100.0, glm::dvec3(1.0) } };
  tf.Opacity = { { 1.0, 0.0 }, { 100.0, 1.0 } };
  return tf;
}
} // namespace

TEST(TransferFunction, LinearInterpolatesInTheScalar)
{
  const TransferFunction tf = TwoPoints();
  EXPECT_FALSE(tf.IsLogarithmic());
  EXPECT_NEAR(tf.EvaluateOpacity(10.0), 9.0 / 99.0, 1e-12);
  EXPECT_NEAR(tf.EvaluateColor(50.5).r, 0.5, 1e-12);
  EXPECT_EQ(tf.EvaluateOpacity(-5.0), 0.0); // clamped below
  EXPECT_EQ(tf.EvaluateOpacity(1e9), 1.0);  // and above
}

TEST(TransferFunction, LogScaleInterpolatesInLog10OfTheScalar)
{
  TransferFunction tf = TwoPoints();
  tf.OpacityLogScale = true;
  EXPECT_TRUE(tf.IsLogarithmic());
  EXPECT_NEAR(tf.EvaluateOpacity(10.0), 0.5, 1e-12);        // halfway in log10
  EXPECT_NEAR(tf.EvaluateColor(10.0).r, 9.0 / 99.0, 1e-12); // colours stay linear
  tf.ColorLogScale = true;
  EXPECT_NEAR(tf.EvaluateColor(std::pow(10.0, 1.5)).g, 0.75, 1e-12);
  // at or below 0 (no logarithm) and below the first point: the first point's value
  EXPECT_EQ(tf.EvaluateOpacity(0.0), 0.0);
  EXPECT_EQ(tf.EvaluateOpacity(-3.0), 0.0);
  EXPECT_EQ(tf.EvaluateColor(0.5), glm::dvec3(0.0));
  EXPECT_EQ(tf.EvaluateOpacity(1e9), 1.0);
}

TEST(TransferFunction, LogScaleBetweenAPointAtZeroAndAPositiveOneIsLinear)
{
  // log10 of the first point does not exist: that segment keeps linear interpolation, as VTK's
  TransferFunction tf;
  tf.Opacity = { { 0.0, 0.0 }, { 10.0, 1.0 }, { 1000.0, 0.0 } };
  tf.OpacityLogScale = true;
  EXPECT_NEAR(tf.EvaluateOpacity(5.0), 0.5, 1e-12);
  EXPECT_NEAR(tf.EvaluateOpacity(100.0), 0.5, 1e-12);
}
