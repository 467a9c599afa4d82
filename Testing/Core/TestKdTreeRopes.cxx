// SPDX-License-Identifier: BSD-3-Clause
// Neighbour links of the kD-tree (amrsp/KdTreeRopes.h): ropes by hand, the rope property checked
// by brute force on the node boxes (independent of the traversal), the traversal with ropes
// against restarts from the root, and the exactness guard.
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/KdTreeRopes.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <iostream>
#include <random>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

/// The region just outside face (axis, upper) of `b`: one finest cell thick.
Box Beyond(const Box& b, int axis, bool upper)
{
  Box f = b;
  if (upper)
  {
    f.Lo[axis] = b.Hi[axis];
    f.Hi[axis] = b.Hi[axis] + 1;
  }
  else
  {
    f.Hi[axis] = b.Lo[axis];
    f.Lo[axis] = b.Lo[axis] - 1;
  }
  return f;
}

/// Every rope by brute force: 0 exactly where the face lies on the root box; otherwise a node
/// whose box holds the face's outside slab, none of whose children does.
void ExpectRopesHold(const KdTree& tree)
{
  const std::vector<uint32_t> ropes = ComputeKdTreeRopes(tree);
  const Box& root = tree.Root().Region;
  std::size_t checked = 0;
  for (std::size_t n = 0; n < tree.Nodes.size(); ++n)
  {
    for (int f = 0; f < 6; ++f)
    {
      const int axis = f / 2;
      const bool upper = f % 2 == 1;
      const Box& b = tree.Nodes[n].Region;
      const uint32_t rope = ropes[6 * n + f];
      const bool onRoot = upper ? b.Hi[axis] == root.Hi[axis] : b.Lo[axis] == root.Lo[axis];
      ASSERT_EQ(rope == 0u, onRoot) << "node " << n << " face " << f;
      if (onRoot)
      {
        continue;
      }
      const Box slab = Beyond(b, axis, upper);
      const KdNode& target = tree.Nodes[rope];
      ASSERT_TRUE(target.Region.Contains(slab)) << "node " << n << " face " << f;
      if (!target.IsLeaf())
      {
        for (int k = 0; k < 2; ++k)
        {
          ASSERT_FALSE(tree.Nodes[target.FirstChild + k].Region.Contains(slab))
            << "node " << n << " face " << f << ": a child of the rope holds the face";
        }
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 0u);
}

TEST(Ropes, ByHand)
{
  // two level-0 grids side by side along x: the root splits at x = 4 into two leaves
  Hierarchy h;
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 4, 4, 4) }, Grid{ 0, MakeBox(4, 0, 0, 8, 4, 4) } };
  const KdTree tree = BuildKdTree(h);
  ASSERT_EQ(tree.Nodes.size(), 3u);
  ASSERT_EQ(tree.Root().Axis, 0);
  const std::vector<uint32_t> ropes = ComputeKdTreeRopes(tree);
  const std::vector<uint32_t> expected = { 0, 0, 0, 0, 0, 0, // the root: every face on the root
    0, 2, 0, 0, 0, 0,                                        // lower leaf: +x -> upper leaf
    1, 0, 0, 0, 0, 0 };                                      // upper leaf: -x -> lower leaf
  EXPECT_EQ(ropes, expected);
  // encoded: rope texel 1 of node 1 holds the x ropes after the box's hi.y, hi.z
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  ASSERT_FALSE(enc.Ropes.Texels.empty());
  EXPECT_EQ(enc.Ropes.Texels[3 * 1 + 1], glm::uvec4(4u, 4u, 0u, 2u));
  EXPECT_EQ(enc.Ropes.Texels[3 * 2 + 0], glm::uvec4(4u, 0u, 0u, 8u));
}

TEST(Ropes, HoldTheirFacesAndAreTheDeepestSuchNodes)
{
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 40; ++trial)
  {
    ExpectRopesHold(BuildKdTree(RandomHierarchy(rng)));
  }
  CosmoParameters p;
  p.Grids = 2666;
  p.Cells = 2000000;
  p.GenerateValues = false;
  ExpectRopesHold(BuildKdTree(GenerateCosmo(p)));
}

TEST(Ropes, TraversalGivesTheSegmentsOfRestartsFromTheRoot)
{
  std::mt19937_64 rng(23);
  std::size_t segments = 0, fromRope = 0, treesWithRopes = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    const Hierarchy h = RandomHierarchy(rng);
    const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
    treesWithRopes += enc.Ropes.Texels.empty() ? 0 : 1;
    for (int r = 0; r < 300; ++r)
    {
      glm::dvec3 o, d;
      RandomRay(rng, h, o, d);
      const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
      std::vector<RaySegment> roped, fromRoot;
      TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), roped);
      TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), fromRoot, true);
      ASSERT_EQ(roped.size(), fromRoot.size()) << "trial " << trial << " ray " << r;
      for (std::size_t i = 0; i < roped.size(); ++i)
      {
        ASSERT_EQ(roped[i].T0, fromRoot[i].T0);
        ASSERT_EQ(roped[i].T1, fromRoot[i].T1);
        ASSERT_EQ(roped[i].Node, fromRoot[i].Node);
        ASSERT_EQ(roped[i].NodeLo, fromRoot[i].NodeLo);
        ASSERT_EQ(roped[i].NodeHi, fromRoot[i].NodeHi);
        fromRope += roped[i].FromRope ? 1 : 0;
      }
      segments += roped.size();
    }
  }
  EXPECT_GT(treesWithRopes, 30u);
  EXPECT_GT(fromRope, segments / 3);
}

TEST(Ropes, AWrongRopeChangesTheSegments)
{
  // the comparison above can fail: one leaf's rope pointed at the root's other child
  CosmoParameters p;
  p.Grids = 200;
  p.Cells = 500000;
  p.GenerateValues = false;
  const Hierarchy h = GenerateCosmo(p);
  EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  ASSERT_FALSE(enc.Ropes.Texels.empty());
  std::mt19937_64 rng(2);
  std::size_t differing = 0;
  for (int r = 0; r < 300 && differing == 0; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
    std::vector<RaySegment> good;
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), good);
    for (std::size_t i = 1; i < good.size() && differing == 0; ++i)
    {
      if (!good[i].FromRope)
      {
        continue;
      }
      // corrupt every rope of the previous leaf, then traverse again
      EncodedKdTree bad = enc;
      const uint32_t leaf = good[i - 1].Node;
      bad.Ropes.Texels[3 * leaf + 1].z = bad.Ropes.Texels[3 * leaf + 1].w = 1u;
      bad.Ropes.Texels[3 * leaf + 2] = glm::uvec4(1u);
      std::vector<RaySegment> wrong;
      TraverseKdTree(bad, oi, di, 0.0f, 1e30f, LevelOfDetail(), wrong);
      differing += wrong.size() != good.size() || wrong[i].Node != good[i].Node ? 1 : 0;
    }
  }
  EXPECT_EQ(differing, 1u);
}

TEST(Ropes, NotEncodedWhereTheBoxesWouldNotBeExact)
{
  Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  EncodedKdTree enc = EncodeKdTree(h, tree);
  EXPECT_FALSE(enc.Ropes.Texels.empty());
  enc.FinestCellSize *= 1.0f + 1e-6f; // boxes from finest cells no longer equal the descent's
  EXPECT_TRUE(EncodeKdTreeRopes(tree, enc).Texels.empty());
  EXPECT_TRUE(EncodeKdTree(h, tree, nullptr, nullptr, false).Ropes.Texels.empty());
}

TEST(Ropes, ShortenTheDescentsOnADeepHierarchy)
{
  // the paper's dataset-3 shape: tree levels descended per segment with ropes, against
  // push-down with the far-child shortcut (measured: about 2.3 against 7.1)
  const Hierarchy h = PaperDataset3Boxes();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  ASSERT_FALSE(enc.Ropes.Texels.empty());
  std::mt19937_64 rng(3);
  std::uint64_t ropeSteps = 0, pushSteps = 0, segments = 0;
  for (int r = 0; r < 400; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
    std::vector<RaySegment> roped, pushed;
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), roped);
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), pushed, false, false);
    ASSERT_EQ(roped.size(), pushed.size());
    for (std::size_t i = 0; i < roped.size(); ++i)
    {
      ASSERT_EQ(roped[i].Node, pushed[i].Node);
      ropeSteps += roped[i].Descent;
      pushSteps += pushed[i].Descent;
    }
    segments += roped.size();
  }
  std::cout << segments << " segments; levels descended per segment: push-down "
            << double(pushSteps) / double(segments) << ", ropes "
            << double(ropeSteps) / double(segments) << "\n";
  EXPECT_GT(segments, 1000u);
  EXPECT_LT(2 * ropeSteps, pushSteps);
}

} // namespace

TEST(Ropes, AFiniteRayEndClampsTheSegmentItFallsIn)
{
  // The expectation comes from the unbounded traversal alone: the segments of [tMin, tMax] are
  // those of [0, inf) that overlap it, cut to it. A rope-entered segment that the end falls in
  // must end exactly at tMax (the clamp), and no segment may begin at or after it.
  std::mt19937_64 rng(61);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::size_t clampedRopeSegments = 0, rays = 0, unclampedRejected = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    const Hierarchy h = RandomHierarchy(rng);
    const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
    for (int r = 0; r < 200; ++r)
    {
      glm::dvec3 o, d;
      RandomRay(rng, h, o, d);
      const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
      std::vector<RaySegment> full;
      TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), full);
      if (full.size() < 3)
      {
        continue;
      }
      // the end strictly inside a segment after the second, so that ropes led to it
      const std::size_t k = 2 + static_cast<std::size_t>(unit(rng) * (full.size() - 2));
      const RaySegment& last = full[std::min(k, full.size() - 1)];
      const float tMax = last.T0 + (0.25f + 0.5f * unit(rng)) * (last.T1 - last.T0);
      if (!(tMax > last.T0 && tMax < last.T1))
      {
        continue;
      }
      std::vector<RaySegment> bounded;
      TraverseKdTree(enc, oi, di, 0.0f, tMax, LevelOfDetail(), bounded);
      std::vector<RaySegment> expected;
      for (const RaySegment& s : full)
      {
        if (s.T0 < tMax)
        {
          expected.push_back(s);
          expected.back().T1 = std::min(s.T1, tMax);
        }
      }
      ++rays;
      ASSERT_EQ(bounded.size(), expected.size()) << "trial " << trial << " ray " << r;
      for (std::size_t i = 0; i < bounded.size(); ++i)
      {
        ASSERT_EQ(bounded[i].Node, expected[i].Node) << "segment " << i;
        ASSERT_EQ(bounded[i].T0, expected[i].T0) << "segment " << i;
        ASSERT_EQ(bounded[i].T1, expected[i].T1) << "segment " << i;
      }
      ASSERT_EQ(bounded.back().T1, tMax);
      clampedRopeSegments += bounded.back().FromRope ? 1 : 0;
      // the unclamped last segment (what a rope-entered segment without the clamp would give)
      // fails the same comparison
      unclampedRejected += last.T1 != expected.back().T1 ? 1 : 0;
    }
  }
  EXPECT_GT(rays, 2000u);
  EXPECT_GT(clampedRopeSegments, rays / 3) << "the end must fall in rope-entered segments";
  EXPECT_EQ(unclampedRejected, rays);
}
