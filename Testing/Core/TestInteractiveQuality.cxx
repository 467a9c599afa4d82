// SPDX-License-Identifier: BSD-3-Clause
// amrsp::InteractiveQuality: the interactive frame's image sample distance and sample-distance
// scale within a frame-time budget.
#include "amrsp/InteractiveQuality.h"

#include <gtest/gtest.h>

using amrsp::FrameQuality;
using amrsp::InteractiveQuality;

TEST(InteractiveQuality, WithoutAnEstimateTheCoarsestRung)
{
  InteractiveQuality quality;
  InteractiveQuality::Limits limits;
  const FrameQuality q = quality.Choose(0.2, limits);
  EXPECT_EQ(q.ImageSampleDistance, limits.MaximumImageSampleDistance);
  EXPECT_EQ(q.SampleDistanceScale, limits.MaximumImageSampleDistance);
  limits.AdjustSampleDistance = false;
  EXPECT_EQ(quality.Choose(0.2, limits).SampleDistanceScale, 1.0);
}

TEST(InteractiveQuality, TheFinestRungPredictedToFit)
{
  InteractiveQuality quality;
  InteractiveQuality::Limits limits;
  quality.Record(FrameQuality(), 1.2); // a still frame of 1.2 s
  EXPECT_DOUBLE_EQ(quality.GetFullSeconds(), 1.2);
  // 0.2 s: d = 1.5 costs (0.3 + 0.7 / 1.5) / 2.25 = 0.34 (0.41 s), d = 2 costs 0.1625 (0.195 s)
  const FrameQuality q = quality.Choose(0.2, limits);
  EXPECT_EQ(q.ImageSampleDistance, 2.0);
  EXPECT_EQ(q.SampleDistanceScale, 2.0);
  EXPECT_LE(quality.Predict(q), 0.2);
  // a budget the full frame fits: full quality
  EXPECT_TRUE(quality.Choose(2.0, limits).IsFull());
  // a budget nothing fits: the coarsest rung
  EXPECT_EQ(quality.Choose(1e-6, limits).ImageSampleDistance, 10.0);
}

TEST(InteractiveQuality, RungsStayWithinTheLimits)
{
  InteractiveQuality quality;
  quality.Record(FrameQuality(), 1.0);
  InteractiveQuality::Limits limits;
  limits.MinimumImageSampleDistance = 3.0;
  limits.MaximumImageSampleDistance = 5.0;
  EXPECT_EQ(quality.Choose(100.0, limits).ImageSampleDistance, 3.0);
  EXPECT_EQ(quality.Choose(1e-6, limits).ImageSampleDistance, 5.0);
  EXPECT_EQ(quality.Choose(0.05, limits).ImageSampleDistance, 4.0); // 4: 0.034 s, 3: 0.059 s
}

TEST(InteractiveQuality, EveryQualityKeepsItsOwnMeasurement)
{
  InteractiveQuality quality;
  InteractiveQuality::Limits limits;
  quality.Record(FrameQuality(), 1.0);
  FrameQuality two;
  two.ImageSampleDistance = two.SampleDistanceScale = 2.0;
  FrameQuality three;
  three.ImageSampleDistance = three.SampleDistanceScale = 3.0;
  // d = 2 took 0.5 s where the model said 0.1625: its own measurement counts, and d = 3 is
  // scaled from it (the nearest measured cost), not from the full frame
  quality.Record(two, 0.5);
  EXPECT_DOUBLE_EQ(quality.Predict(two), 0.5);
  EXPECT_DOUBLE_EQ(quality.GetFullSeconds(), 1.0);
  EXPECT_DOUBLE_EQ(quality.Predict(three),
    0.5 * InteractiveQuality::CostFraction(three) / InteractiveQuality::CostFraction(two));
  // so a budget of 0.3 s moves one rung coarser than the model alone would
  EXPECT_EQ(quality.Choose(0.3, limits).ImageSampleDistance, 3.0);
  quality.Record(two, 0.3); // the mean of the old and the new measurement
  EXPECT_DOUBLE_EQ(quality.Predict(two), 0.4);
  quality.Record(two, 0.0); // not a measurement
  EXPECT_DOUBLE_EQ(quality.Predict(two), 0.4);
  quality.Reset();
  EXPECT_EQ(quality.GetFullSeconds(), 0.0);
  EXPECT_EQ(quality.Choose(10.0, limits).ImageSampleDistance, 10.0);
}
