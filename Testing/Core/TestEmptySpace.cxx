// SPDX-License-Identifier: BSD-3-Clause
// Empty-space skipping and early ray termination of the CPU integrators: per-data-node value
// ranges, the transparency tests (exact and tabulated), images unchanged by skipping, bounded
// by the threshold for early termination, and counters that show the work really went away.
#include "amrsp/EmptySpace.h"
#include "amrsp/ImageDifference.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/Render.h"
#include "amrsp/VertexData.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cstdlib>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

/// The ranges by brute force: every cell (or vertex) of the node's grid whose box touches the
/// node's region, tested one by one in finest-level cells.
std::vector<glm::vec2> BruteForceRanges(const Hierarchy& h, const EncodedKdTree& enc)
{
  const KdTree tree = DecodeKdTree(h, enc);
  const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
  std::vector<glm::vec2> out(
    static_cast<std::size_t>(enc.DataNodeCount + 1), glm::vec2(FLT_MAX, -FLT_MAX));
  for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
  {
    const KdNode& n = tree.Nodes[i];
    if (!n.HasData())
    {
      continue;
    }
    const uint32_t data = layout::amrspNodeData(enc.Tree.Texels[i]);
    const Grid& g = h.Grids[n.Grid];
    const glm::i64vec3 r = finest / h.CumulativeRatio(g.Level);
    const glm::i64vec3 e = g.Cells.Extent() + glm::i64vec3(h.VertexCentred ? 1 : 0);
    glm::vec2& range = out[data];
    // a window of the grid two cells wider than the node on every side (the test below decides)
    glm::i64vec3 w0, w1;
    for (int a = 0; a < 3; ++a)
    {
      w0[a] = std::max<int64_t>(0, n.Region.Lo[a] / r[a] - 2 - g.Cells.Lo[a]);
      w1[a] = std::min<int64_t>(e[a], n.Region.Hi[a] / r[a] + 2 - g.Cells.Lo[a]);
    }
    for (int64_t z = w0.z; z < w1.z; ++z)
      for (int64_t y = w0.y; y < w1.y; ++y)
        for (int64_t x = w0.x; x < w1.x; ++x)
        {
          const glm::i64vec3 c = g.Cells.Lo + glm::i64vec3(x, y, z);
          bool touches = true;
          for (int a = 0; a < 3; ++a)
          {
            // a cell touches when it overlaps the region; a vertex when it lies on its closure
            touches = touches &&
              (h.VertexCentred
                  ? (c[a] * r[a] >= n.Region.Lo[a] - r[a] + 1 &&
                      c[a] * r[a] <= n.Region.Hi[a] + r[a] - 1)
                  : (c[a] * r[a] < n.Region.Hi[a] && (c[a] + 1) * r[a] > n.Region.Lo[a]));
          }
          if (touches)
          {
            const float v = h.Values[n.Grid][static_cast<std::size_t>((z * e.y + y) * e.x + x)];
            range.x = std::min(range.x, v);
            range.y = std::max(range.y, v);
          }
        }
  }
  return out;
}

TEST(EmptySpace, RangesHoldEveryValueANodeCanSample)
{
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 12; ++trial)
  {
    Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    if (trial > 0)
    {
      FillValues(h);
    }
    if (trial % 4 == 3)
    {
      ConvertCellsToVertices(h);
    }
    const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
    const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(h, enc);
    const std::vector<glm::vec2> brute = BruteForceRanges(h, enc);
    ASSERT_EQ(ranges.size(), static_cast<std::size_t>(enc.DataNodeCount + 1));
    for (std::size_t k = 1; k < ranges.size(); ++k)
    {
      ASSERT_EQ(ranges[k].x, brute[k].x) << "trial " << trial << " data node " << k;
      ASSERT_EQ(ranges[k].y, brute[k].y) << "trial " << trial << " data node " << k;
      ASSERT_LE(ranges[k].x, ranges[k].y);
    }
  }
  // NaN values are left out; a node of NaNs only has the empty range
  Hierarchy h = PaperExample();
  for (float& v : h.Values[0])
  {
    v = std::numeric_limits<float>::quiet_NaN();
  }
  const KdTree tree = BuildKdTree(h);
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(h, enc);
  int nanNodes = 0;
  for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
  {
    if (tree.Nodes[i].Grid == 0)
    {
      const glm::vec2 r = ranges[layout::amrspNodeData(enc.Tree.Texels[i])];
      EXPECT_GT(r.x, r.y);
      ++nanNodes;
    }
  }
  EXPECT_GT(nanNodes, 0);
}

TEST(EmptySpace, TransparentRangeIsExactForPiecewiseLinearOpacity)
{
  TransferFunction tf = TransferFunction::Preset("sparse", 0.0, 1.0, 1.0);
  EXPECT_TRUE(TransparentRange(tf, 0.0, 0.6));
  EXPECT_TRUE(TransparentRange(tf, -5.0, 0.3)); // clamped below the first point
  EXPECT_FALSE(TransparentRange(tf, 0.0, 0.61));
  EXPECT_FALSE(TransparentRange(tf, 2.0, 3.0)); // clamped above: opacity 0.9
  EXPECT_TRUE(TransparentRange(tf, 1.0, 0.0));  // empty range
  // a bump strictly inside the interval, zero at both ends
  tf.Opacity = { { 0.0, 0.0 }, { 0.4, 0.0 }, { 0.5, 0.2 }, { 0.6, 0.0 }, { 1.0, 0.0 } };
  EXPECT_FALSE(TransparentRange(tf, 0.3, 0.7));
  EXPECT_TRUE(TransparentRange(tf, 0.6, 0.9));
  // random functions and intervals against dense sampling
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial)
  {
    tf.Opacity.clear();
    double x = -0.2;
    for (int p = 0; p < 6; ++p)
    {
      x += 0.25 * u(rng);
      tf.Opacity.push_back({ x, u(rng) < 0.6 ? 0.0 : u(rng) });
    }
    double lo = 1.6 * u(rng) - 0.3, hi = lo + 0.5 * u(rng);
    double peak = 0.0;
    for (int k = 0; k <= 4000; ++k)
    {
      peak = std::max(peak, tf.EvaluateOpacity(lo + (hi - lo) * k / 4000.0));
    }
    for (const auto& p : tf.Opacity)
    {
      if (p.X >= lo && p.X <= hi)
      {
        peak = std::max(peak, p.Opacity);
      }
    }
    ASSERT_EQ(TransparentRange(tf, lo, hi), peak == 0.0) << "trial " << trial;
  }
}

TEST(EmptySpace, TableTestCoversEveryFilteredLookup)
{
  // a table as the mapper builds it (entries at first + i/(n-1) * (last - first)), then lookups
  // with linear filtering between neighbouring entries, as the shader's texture() does
  const int n = 256;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 500; ++trial)
  {
    std::vector<float> opacity(n, 0.0f);
    const int runs = 1 + static_cast<int>(rng() % 4);
    for (int r = 0; r < runs; ++r)
    {
      const int a = static_cast<int>(rng() % n),
                b = std::min(n - 1, a + static_cast<int>(rng() % 20));
      for (int i = a; i <= b; ++i)
      {
        opacity[i] = 0.5f;
      }
    }
    const std::vector<float> prefix = OpacityPrefixCounts(opacity);
    const float first = -3.0f, last = 5.0f;
    const float range[2] = { first, 1.0f / (last - first) };
    const float lo = -4.0f + 10.0f * u(rng), hi = lo + 2.0f * u(rng) * u(rng);
    const bool transparent = TableRangeTransparent(prefix, range, lo, hi);
    float peak = 0.0f;
    for (int k = 0; k <= 1000; ++k)
    {
      const float s = lo + (hi - lo) * k / 1000.0f;
      const float x = std::min(1.0f, std::max(0.0f, (s - range[0]) * range[1])) * (n - 1);
      const int i = std::min(n - 2, static_cast<int>(std::floor(x)));
      const float w = x - i;
      peak = std::max(peak, (1.0f - w) * opacity[i] + w * opacity[i + 1]);
    }
    if (transparent)
    {
      ASSERT_EQ(peak, 0.0f) << "trial " << trial;
    }
  }
  const float unit[2] = { 0.0f, 1.0f };
  EXPECT_TRUE(TableRangeTransparent({ 1.0f, 2.0f, 3.0f }, unit, 0.5f, 0.2f)); // empty range
  EXPECT_FALSE(TableRangeTransparent({ 1.0f, 2.0f, 3.0f }, unit, 0.2f, 0.5f));
  EXPECT_TRUE(TableRangeTransparent({ 0.0f, 0.0f, 0.0f, 0.0f, 1.0f }, unit, 0.0f, 0.5f));
  EXPECT_FALSE(TableRangeTransparent({ 0.0f, 0.0f, 0.0f, 0.0f, 1.0f }, unit, 0.0f, 0.51f));
}

RenderSettings SparseView(const Hierarchy& h)
{
  RenderSettings s = SmallView(h);
  s.Width = 48;
  s.Height = 36;
  s.Transfer = TransferFunction::Preset("sparse", 0.0, 1.2, s.Transfer.UnitDistance);
  s.Threads = 2;
  return s;
}

TEST(EmptySpace, SkippingNeverChangesTheImageAndSkipsWork)
{
  std::mt19937_64 rng(31);
  long long skippedTotal = 0;
  for (int trial = 0; trial < 16; ++trial)
  {
    Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    if (trial > 0)
    {
      FillValues(h);
    }
    if (trial % 4 == 3)
    {
      ConvertCellsToVertices(h);
    }
    const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
    RenderSettings s = SparseView(h);
    RenderStats plainStats, skipStats;
    s.Stats = &plainStats;
    const Image plain = RenderKdTree(h, enc, s);
    s.SkipEmptySpace = true;
    s.Stats = &skipStats;
    const Image skipped = RenderKdTree(h, enc, s);
    // every skipped sample would have had zero opacity: the very same image
    ASSERT_EQ(Rmse(plain, skipped), 0.0) << "trial " << trial;
    ASSERT_EQ(plainStats.SkippedSegments, 0);
    ASSERT_EQ(skipStats.DataSegments, plainStats.DataSegments);
    ASSERT_EQ(skipStats.Samples + skipStats.SkippedSamples, plainStats.Samples)
      << "trial " << trial;
    skippedTotal += skipStats.SkippedSamples;
  }
  EXPECT_GT(skippedTotal, 0);

  // the paper example with the "sparse" function
  const Hierarchy h = PaperExample();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  RenderSettings s = SparseView(h);
  RenderStats stats;
  s.SkipEmptySpace = true;
  s.Stats = &stats;
  const Image skipped = RenderKdTree(h, enc, s);
  EXPECT_GT(stats.SkippedSegments, 0);
  EXPECT_GT(stats.SkippedSamples, 0);

  // the test can fail: ranges that wrongly call every node transparent remove visible samples
  std::vector<glm::vec2> wrong(
    static_cast<std::size_t>(enc.DataNodeCount + 1), glm::vec2(FLT_MAX, -FLT_MAX));
  s.DataNodeRanges = &wrong;
  EXPECT_GT(Rmse(skipped, RenderKdTree(h, enc, s)), 1.0);
  std::vector<glm::vec2> mismatched(3);
  s.DataNodeRanges = &mismatched;
  EXPECT_THROW(RenderKdTree(h, enc, s), std::invalid_argument);
}

/// Largest difference of one 8-bit channel.
int MaxChannelDifference(const Image& a, const Image& b)
{
  return Compare(a, b).Largest;
}

TEST(EarlyRayTermination, BoundedByTheThresholdInBothIntegrators)
{
  Hierarchy h = PaperExample();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  RenderSettings s = SmallView(h);
  s.Transfer.UnitDistance *= 0.05; // dense: most rays become opaque
  s.Threads = 2;
  for (bool reference : { false, true })
  {
    auto render = [&](double threshold, RenderStats& stats)
    {
      s.OpacityThreshold = threshold;
      s.Stats = &stats;
      return reference ? RenderReference(h, s) : RenderKdTree(h, enc, s);
    };
    RenderStats full, stopped;
    const Image all = render(1.0, full);
    EXPECT_EQ(full.TerminatedRays, 0);
    for (double threshold : { 0.9, 0.99, 0.999 })
    {
      RenderStats st;
      const Image img = render(threshold, st);
      // a ray stopped at opacity A misses at most (1 - A) <= (1 - threshold) of any channel
      const int bound = static_cast<int>(std::ceil((1.0 - threshold) * 255.0)) + 1;
      EXPECT_LE(MaxChannelDifference(all, img), bound)
        << (reference ? "reference" : "kD-tree") << " threshold " << threshold;
      EXPECT_GT(st.TerminatedRays, st.Rays / 4);
      EXPECT_LT(st.Samples, full.Samples);
    }
    // the test can fail: stopping at opacity 0.5 is visibly different
    const Image half = render(0.5, stopped);
    EXPECT_GT(MaxChannelDifference(all, half), 20);
    EXPECT_LT(stopped.Samples, full.Samples / 2);
  }
}

} // namespace
