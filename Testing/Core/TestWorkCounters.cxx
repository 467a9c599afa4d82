// SPDX-License-Identifier: BSD-3-Clause
// The cost model (amrsp/WorkCounters.h): lockstep steps and texel fetches by hand, and frames
// whose sample counts are known from the geometry alone (a parallel view straight through one
// grid, and through a refined strip that makes the lanes of a tile diverge).
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"
#include "amrsp/WorkCounters.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

SegmentWork Step(uint32_t descent, uint32_t samples, bool data = true)
{
  SegmentWork w;
  w.Descent = descent;
  w.Samples = samples;
  w.Data = data;
  return w;
}

TEST(WorkCounters, LockstepTakesTheLargestCountOfEachLoopPerIteration)
{
  // iteration 0: 1 + max(2, 4) descent + max(3, 1) samples = 8; iteration 1: 1 + 1 + 0 = 2
  const std::vector<std::vector<SegmentWork>> rays = { { Step(2, 3), Step(1, 0, false) },
    { Step(4, 1) } };
  EXPECT_EQ(TileLockstepSteps(rays), 10);
  // the largest sum of one lane (1 + 4 + 1 = 6, then 2) would undercount divergence: 8 != 6 + 2
  EXPECT_EQ(TileLockstepSteps({ { Step(0, 5) }, { Step(5, 0) } }), 11);
  EXPECT_EQ(TileLockstepSteps({}), 0);
}

TEST(WorkCounters, FlatLoopCountsOneOperationPerIterationAndDivergenceTwice)
{
  // lane a: traverse 1 + 2, sample 3; lane b: traverse 1 + 4, sample 1:
  // iterations 1-3 both traverse (1 each), 4-5 a samples while b traverses (2 each),
  // 6 both sample (1): 3 + 4 + 1 = 8
  EXPECT_EQ(TileFlatLoopSteps({ { Step(2, 3) }, { Step(4, 1) } }), 8);
  // one lane: its operations one by one, 1 + 2 + 3 and 1 + 1 + 0
  EXPECT_EQ(TileFlatLoopSteps({ { Step(2, 3), Step(1, 0, false) } }), 8);
  EXPECT_EQ(TileFlatLoopSteps({}), 0);
}

TEST(WorkCounters, TexelFetchesPerStorage)
{
  // root; a far child then 2 levels down into a sampled leaf of 3 samples; 1 level down into an
  // empty leaf; 1 level down into a skipped leaf
  SegmentWork a = Step(2, 3);
  a.FromFar = true;
  SegmentWork skipped = Step(1, 0);
  skipped.Skipped = true;
  const std::vector<SegmentWork> ray = { a, Step(1, 0, false), skipped };
  FetchModel m;
  // root + (far child + 2 levels) + [data node + 3 x (atlas + transfer)] + 1 level + 1 level
  EXPECT_EQ(RayTexelFetches(ray, m), 1 + 3 + 1 + 6 + 1 + 1);
  m.SkipFlags = true; // two data segments read their flag
  EXPECT_EQ(RayTexelFetches(ray, m), 13 + 2);
  m.SkipFlags = false;
  m.Storage = DataStorage::BindlessTextures; // + one handle per sampled segment
  EXPECT_EQ(RayTexelFetches(ray, m), 14);
  m.BrickLookupPerSegment = false; // + one handle per sample instead
  EXPECT_EQ(RayTexelFetches(ray, m), 16);
  m.BrickLookupPerSegment = true;
  m.VertexCentred = true; // eight texels per sample instead of one
  EXPECT_EQ(RayTexelFetches(ray, m), 14 + 3 * 7);
  m.Storage = DataStorage::PackedAtlas; // one hardware-filtered read
  EXPECT_EQ(RayTexelFetches(ray, m), 13);
}

/// Parallel view down -z through the unit cube, the image's pixels 1/16 world unit wide.
RenderSettings TopView(int width, int height)
{
  RenderSettings s;
  s.Width = width;
  s.Height = height;
  s.View.Parallel = true;
  s.View.ParallelScale = 0.5 * height / 16.0;
  s.View.FocalPoint = glm::dvec3(0.5 * width / 16.0, 0.5 * height / 16.0, 0.5);
  s.View.Position = s.View.FocalPoint + glm::dvec3(0.0, 0.0, 4.0);
  s.Transfer.Color = { { 0.0, glm::dvec3(0.0) }, { 2.0, glm::dvec3(1.0) } };
  s.Transfer.Opacity = { { 0.0, 0.01 }, { 2.0, 0.01 } };
  s.Threads = 2;
  return s;
}

TEST(WorkCounters, OneGridEveryLaneDoesTheSameWork)
{
  // one grid of 8^3 cells over the unit cube: the root is its leaf, every ray crosses 8 cells
  // of 1/8 at a step of one cell: 1 segment, no descent, 8 samples
  Hierarchy h = LevelPatch(1, 8, [](const glm::dvec3& p) { return p.x; });
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const RenderSettings s = TopView(16, 8);
  const WorkSummary w = MeasureSinglePassWork(h, tree, s, FetchModel());
  EXPECT_EQ(w.Pixels, 128);
  EXPECT_EQ(w.Tiles, 4);
  EXPECT_EQ(w.Rays, 128);
  EXPECT_DOUBLE_EQ(w.Segments.Mean, 1.0);
  EXPECT_DOUBLE_EQ(w.DescentSteps.Mean, 0.0);
  EXPECT_DOUBLE_EQ(w.Samples.Mean, 8.0);
  EXPECT_DOUBLE_EQ(w.Samples.P95, 8.0);
  EXPECT_DOUBLE_EQ(w.Steps.Mean, 9.0);
  EXPECT_DOUBLE_EQ(w.TexelFetches.Mean, 1 + 1 + 8 * 2); // root, data node, atlas + transfer
  EXPECT_DOUBLE_EQ(w.StepsPerPixel, 9.0);
  EXPECT_DOUBLE_EQ(w.LockstepStepsPerPixel, 9.0 / 32.0); // each tile's group: 9 steps
  EXPECT_DOUBLE_EQ(w.LockstepEfficiency, 1.0);

  // multi-pass: one draw, one fragment of 8 samples per pixel
  const WorkSummary mp = MeasureMultipassWork(h, tree, s);
  EXPECT_EQ(mp.Draws, 1);
  EXPECT_DOUBLE_EQ(mp.FragmentsPerPixel, 1.0);
  EXPECT_DOUBLE_EQ(mp.Samples.Mean, 8.0);
  EXPECT_DOUBLE_EQ(mp.LockstepStepsPerPixel, 9.0 / 32.0);

  // half the image misses the cube (x in [1, 2)): idle lanes still cost their tile
  const WorkSummary wide = MeasureSinglePassWork(h, tree, TopView(32, 8), FetchModel());
  EXPECT_EQ(wide.Rays, 128);
  EXPECT_DOUBLE_EQ(wide.StepsPerPixel, 4.5);
  EXPECT_DOUBLE_EQ(wide.LockstepStepsPerPixel, 4.5 / 32.0); // whole idle tiles cost nothing
  EXPECT_DOUBLE_EQ(wide.LockstepEfficiency, 1.0);
}

TEST(WorkCounters, ARefinedStripMakesTheLanesOfATileDiverge)
{
  // level 0: 8^3 cells over the unit cube; level 1 (ratio 2) over x in [0, 1/4): rays there
  // cross 16 cells of 1/16, the others 8 cells of 1/8, each at a step of one of its cells
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 8.0);
  h.RefinementRatio.push_back(glm::ivec3(2));
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 8, 8, 8) });
  h.Grids.push_back(Grid{ 1, MakeBox(0, 0, 0, 4, 16, 16) });
  h.Grids[1].SourceId = 1;
  FillValues(h);
  h.ArrayName = "field";
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const RenderSettings s = TopView(16, 8); // columns 0-3 fine, 4-15 coarse
  const WorkSummary w = MeasureSinglePassWork(h, tree, s, FetchModel());
  EXPECT_EQ(w.Rays, 128);
  EXPECT_DOUBLE_EQ(w.Samples.Mean, (4 * 16 + 12 * 8) / 16.0);
  EXPECT_DOUBLE_EQ(w.Samples.P95, 16.0);
  // the first tile's coarse lanes wait for the fine ones: at least 8 idle sample steps in each
  // of its 16 coarse lanes (4 tiles of 32 lanes)
  EXPECT_GE(32.0 * w.LockstepStepsPerPixel - w.StepsPerPixel, 16.0 * 8.0 / 128.0);
  EXPECT_LT(w.LockstepEfficiency, 1.0);

  // the same rays as the renderer: its counters give the same samples and data segments
  RenderStats stats;
  RenderSettings counted = s;
  counted.Stats = &stats;
  RenderKdTree(h, tree, counted);
  EXPECT_EQ(stats.Samples, static_cast<long long>(w.Samples.Mean * w.Rays + 0.5));
  EXPECT_EQ(stats.Rays, w.Rays);

  // multi-pass samples every fragment to its end: the same samples here (no termination)
  const WorkSummary mp = MeasureMultipassWork(h, tree, s);
  EXPECT_DOUBLE_EQ(mp.Samples.Mean, w.Samples.Mean);
  EXPECT_GE(mp.Draws, 2);
  EXPECT_DOUBLE_EQ(mp.DescentSteps.Mean, 0.0);
}

TEST(WorkCounters, EarlyTerminationEndsTheSegmentLoop)
{
  Hierarchy h = LevelPatch(2, 16, [](const glm::dvec3&) { return 1.0; });
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  RenderSettings s = TopView(16, 16);
  s.Transfer.Opacity = { { 0.0, 1.0 }, { 2.0, 1.0 } }; // opaque
  const WorkSummary all = MeasureSinglePassWork(h, tree, s, FetchModel());
  s.OpacityThreshold = 0.5;
  const WorkSummary stopped = MeasureSinglePassWork(h, tree, s, FetchModel());
  // an opaque first sample stops every ray at its first data segment's first sample
  EXPECT_DOUBLE_EQ(stopped.Samples.Mean, 1.0);
  EXPECT_DOUBLE_EQ(stopped.Segments.Mean, 1.0);
  EXPECT_GT(all.Samples.Mean, 8.0);
  EXPECT_GT(all.Segments.Mean, 1.0);
}

} // namespace
