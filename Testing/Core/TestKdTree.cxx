// SPDX-License-Identifier: BSD-3-Clause
// Tests of the kD-tree builder, its texture encoding and the CPU traversal that mirrors the shader.
#include "amrsp/Invariants.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/Render.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <random>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

TEST(Layout, FieldsRoundTrip)
{
  using namespace layout;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i)
  {
    const uint axis = static_cast<uint>(rng() % 4), level = static_cast<uint>(rng() % 64);
    const uint child = static_cast<uint>(rng() % MaxNodes);
    const uint split = static_cast<uint>(rng() % (MaxSplit + 1));
    const uint data = static_cast<uint>(rng() % (MaxDataNodes + 1));
    const uvec2 t = amrspPackNode(axis, level, child, split, data);
    ASSERT_EQ(amrspNodeAxis(t), axis);
    ASSERT_EQ(amrspNodeLevel(t), level);
    ASSERT_EQ(amrspNodeFirstChild(t), child);
    ASSERT_EQ(amrspNodeSplit(t), split);
    ASSERT_EQ(amrspNodeData(t), data);
    const uint brick = static_cast<uint>(rng() % MaxBricks);
    const glm::uvec3 o(
      rng() % (MaxOffsetX + 1), rng() % (MaxOffsetY + 1), rng() % (MaxOffsetZ + 1));
    const uint page = static_cast<uint>(rng() % MaxAtlasPages);
    const uvec2 d = amrspPackDataNode(level, brick, o.x, o.y, o.z, page);
    ASSERT_EQ(amrspDataLevel(d), level);
    ASSERT_EQ(amrspDataBrick(d), brick);
    ASSERT_EQ(amrspDataPage(d), page);
    ASSERT_EQ(glm::uvec3(amrspDataOffset(d)), o);
  }
  EXPECT_EQ(amrspTexelOf(0), glm::ivec3(0));
  EXPECT_EQ(amrspTexelOf(257), glm::ivec3(1, 1, 0));
  EXPECT_EQ(amrspTexelOf(65536 * 3 + 256 * 2 + 5), glm::ivec3(5, 2, 3));
  // the paper: the 24-bit child field is the texel coordinate (8 bits per axis) of a 256^3 texture
  EXPECT_EQ(TextureDimsFor(1), glm::ivec3(1, 1, 1));
  EXPECT_EQ(TextureDimsFor(300), glm::ivec3(256, 2, 1));
  EXPECT_EQ(TextureDimsFor(65537), glm::ivec3(256, 256, 2));
}

TEST(KdTree, PaperExample)
{
  const Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  const InvariantReport r = CheckKdTree(h, tree, &enc);
  for (const std::string& f : r.Failures)
  {
    ADD_FAILURE() << f;
  }
  EXPECT_TRUE(r.Ok);
  const KdTreeStatistics s = tree.Statistics();
  EXPECT_EQ(s.Nodes, s.DataNodes + s.Mixed + s.Empty);
  EXPECT_EQ(s.Nodes % 2, 1); // a full binary tree
  EXPECT_GT(s.Leaves, 5);
  EXPECT_EQ(s.Empty, 0); // one root grid covers the whole root box
  // the root is the level-0 grid, split at level 1 (it is partially refined)
  EXPECT_EQ(tree.Root().Type, NodeType::Mixed);
  EXPECT_EQ(tree.Root().Level, 1);
  EXPECT_EQ(tree.Root().Region.Hi, glm::i64vec3(64, 64, 16));
}

TEST(KdTree, InvariantCheckerCatchesCorruptTrees)
{
  const Hierarchy h = PaperExample();
  const KdTree good = BuildKdTree(h);
  ASSERT_TRUE(CheckKdTree(h, good).Ok);
  std::size_t leaf = 0, inner = 0;
  for (std::size_t i = 0; i < good.Nodes.size(); ++i)
  {
    if (good.Nodes[i].IsLeaf() && h.Grids[good.Nodes[i].Grid].Level == 2)
    {
      leaf = i;
    }
    if (!good.Nodes[i].IsLeaf() && i > 0)
    {
      inner = i;
    }
  }
  KdTree coarser = good; // a level-2 leaf claims the level-0 grid under it
  coarser.Nodes[leaf].Grid = 0;
  coarser.Nodes[leaf].Level = 0;
  EXPECT_FALSE(CheckKdTree(h, coarser).Ok);
  KdTree shifted = good; // a split moved without moving the children
  shifted.Nodes[inner].Split += 1;
  EXPECT_FALSE(CheckKdTree(h, shifted).Ok);
  KdTree retyped = good;
  retyped.Nodes[0].Type = NodeType::Refined;
  EXPECT_FALSE(CheckKdTree(h, retyped).Ok);
  EncodedKdTree enc = EncodeKdTree(h, good);
  enc.Tree.Texels[inner].y ^= 1u; // one flipped bit of a split position
  EXPECT_FALSE(CheckKdTree(h, good, &enc).Ok);
}

TEST(KdTree, FullyRefinedNodeIsTypeA)
{
  // A root grid exactly covered by two level-1 grids: the root keeps level-0 data for LOD.
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2) };
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 4, 4, 4) }, Grid{ 1, MakeBox(0, 0, 0, 3, 8, 8) },
    Grid{ 1, MakeBox(3, 0, 0, 8, 8, 8) } };
  FillValues(h);
  const KdTree tree = BuildKdTree(h);
  ASSERT_EQ(tree.Nodes.size(), 3u);
  EXPECT_EQ(tree.Root().Type, NodeType::Refined);
  EXPECT_EQ(tree.Root().Grid, 0);
  EXPECT_EQ(tree.Root().Axis, 0);
  EXPECT_EQ(tree.Root().Split, 3); // in level-1 cells: not on a level-0 cell face
  EXPECT_EQ(tree.Nodes[1].Grid, 1);
  EXPECT_EQ(tree.Nodes[2].Grid, 2);
  EXPECT_TRUE(CheckKdTree(h, tree).Ok);
}

TEST(KdTree, OneGridRefiningAWholeLeafLeavesATypeANode)
{
  // A level-1 grid over the middle of a level-0 grid: the splits cut out the patch's region, which
  // one grid covers whole; it must stay a type (a) node with the level-0 data (over two halves of
  // the level-1 grid), or the level of detail could never show level 0 there.
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2) };
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 8, 8, 8) }, Grid{ 1, MakeBox(4, 4, 4, 12, 12, 12) } };
  FillValues(h);
  const KdTree tree = BuildKdTree(h);
  const Box patch = MakeBox(4, 4, 4, 12, 12, 12); // finest (level-1) cells
  int typeA = -1;
  for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
  {
    if (tree.Nodes[i].Region == patch && tree.Nodes[i].Type == NodeType::Refined)
    {
      typeA = static_cast<int>(i);
    }
  }
  ASSERT_GE(typeA, 0) << "no type (a) node over the patch";
  EXPECT_EQ(tree.Nodes[typeA].Grid, 0);
  for (int c = 0; c < 2; ++c)
  {
    const KdNode& half = tree.Nodes[tree.Nodes[typeA].FirstChild + c];
    EXPECT_TRUE(half.IsLeaf());
    EXPECT_EQ(half.Grid, 1);
  }
  EXPECT_TRUE(CheckKdTree(h, tree).Ok);
}

TEST(KdTree, SplitMinimisesCrossingsThenBalances)
{
  // Four level-0 grids: a y-plane at 6 cuts none; x = 4 would cut one. Expect the y split.
  Hierarchy h;
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 8, 6, 2) }, Grid{ 0, MakeBox(0, 6, 0, 4, 12, 2) },
    Grid{ 0, MakeBox(4, 6, 0, 8, 12, 2) } };
  FillValues(h);
  const KdTree tree = BuildKdTree(h);
  EXPECT_EQ(tree.Root().Axis, 1);
  EXPECT_EQ(tree.Root().Split, 6);
  EXPECT_EQ(tree.Nodes.size(), 5u);
  EXPECT_TRUE(CheckKdTree(h, tree).Ok);
}

TEST(KdTree, RootGridsWithGapsGiveEmptyLeaves)
{
  Hierarchy h;
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 4, 4, 4) }, Grid{ 0, MakeBox(8, 8, 8, 12, 12, 12) } };
  FillValues(h);
  const KdTree tree = BuildKdTree(h);
  const KdTreeStatistics s = tree.Statistics();
  EXPECT_GT(s.Empty, 0);
  EXPECT_EQ(s.Leaves, 2);
  EXPECT_TRUE(CheckKdTree(h, tree).Ok);
}

TEST(KdTree, RandomHierarchiesKeepEveryInvariant)
{
  std::mt19937_64 rng(20130101);
  for (int trial = 0; trial < 2000; ++trial)
  {
    const Hierarchy h = RandomHierarchy(rng);
    const KdTree tree = BuildKdTree(h);
    const EncodedKdTree enc = EncodeKdTree(h, tree);
    const InvariantReport r = CheckKdTree(h, tree, &enc);
    ASSERT_TRUE(r.Ok) << "trial " << trial << ": " << (r.Failures.empty() ? "" : r.Failures[0]);
  }
}

TEST(Traversal, AgreesWithReferenceLookupOnEverySample)
{
  std::mt19937_64 rng(42);
  std::size_t samples = 0, rays = 0, onFace = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    const Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    const KdTree tree = BuildKdTree(h);
    const EncodedKdTree enc = EncodeKdTree(h, tree);
    const FinestCellLocator locator(h);
    std::vector<TreeSample> s;
    for (int r = 0; r < 100; ++r, ++rays)
    {
      glm::dvec3 o, d;
      RandomRay(rng, h, o, d);
      s.clear();
      SampleRayKdTree(h, enc, o, d, 0.7, s);
      for (const TreeSample& ts : s)
      {
        ++samples;
        glm::i64vec3 cell;
        const int32_t g = locator.Find(ts.Position, cell);
        if (g == ts.Grid && cell == ts.Cell)
        {
          continue;
        }
        // A point exactly on a cell face (rays placed on cell corners) belongs to both sides;
        // the float ray of the traversal and the double point of the check may round apart.
        const glm::dvec3 c = ts.Position * glm::dvec3(h.CumulativeRatio(h.Grids[ts.Grid].Level));
        const glm::dvec3 nearestFace = glm::abs(c - glm::round(c));
        ASSERT_LT(std::min(nearestFace.x, std::min(nearestFace.y, nearestFace.z)), 1e-4)
          << "trial " << trial << " ray " << r << ": tree grid " << ts.Grid << ", reference grid "
          << g << " at (" << c.x << ", " << c.y << ", " << c.z << ") cells of level "
          << h.Grids[ts.Grid].Level;
        ++onFace;
      }
    }
  }
  std::cout << samples << " samples on " << rays << " rays; " << onFace
            << " on a cell face resolved to the other side\n";
  EXPECT_LT(onFace * 100, samples); // under 1%
  EXPECT_GT(samples, 100000u);
  EXPECT_EQ(rays, 20000u);
}

TEST(Traversal, SegmentsAreOrderedContiguousAndInsideTheirNodes)
{
  std::mt19937_64 rng(5);
  const Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  std::vector<RaySegment> segs;
  for (int r = 0; r < 2000; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
    segs.clear();
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), segs);
    for (std::size_t i = 0; i < segs.size(); ++i)
    {
      ASSERT_LT(segs[i].T0, segs[i].T1);
      if (i > 0)
      {
        ASSERT_EQ(segs[i].T0, segs[i - 1].T1);
      }
      const KdNode& n = tree.Nodes[segs[i].Node];
      ASSERT_TRUE(n.IsLeaf());
      const glm::dvec3 mid =
        glm::dvec3(oi) + 0.5 * (double(segs[i].T0) + segs[i].T1) * glm::dvec3(di);
      const glm::dvec3 lo = RegionLoIndex(h, tree, n.Region), hi = RegionHiIndex(h, tree, n.Region);
      for (int a = 0; a < 3; ++a)
      {
        ASSERT_GE(mid[a], lo[a] - 1e-4);
        ASSERT_LE(mid[a], hi[a] + 1e-4);
      }
    }
  }
}

TEST(Traversal, PushDownGivesTheSegmentsOfRestartsFromTheRoot)
{
  // Push-down and the far-child shortcut must be invisible: bit-identical segments (t, node,
  // box) to the paper's restart from the root, on random hierarchies, with and without a
  // parallel-projection LOD cut-off.
  std::mt19937_64 rng(17);
  std::size_t segments = 0;
  for (int trial = 0; trial < 30; ++trial)
  {
    const Hierarchy h = RandomHierarchy(rng);
    const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
    LevelOfDetail parallelLod;
    parallelLod.ThresholdPixels = 2.0f;
    parallelLod.ParallelPixelSize = 0.3f;
    for (const LevelOfDetail& lod : { LevelOfDetail(), parallelLod })
    {
      for (int r = 0; r < 300; ++r)
      {
        glm::dvec3 o, d;
        RandomRay(rng, h, o, d);
        const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
        std::vector<RaySegment> pushed, fromRoot;
        TraverseKdTree(enc, oi, di, 0.0f, 1e30f, lod, pushed, false, false);
        TraverseKdTree(enc, oi, di, 0.0f, 1e30f, lod, fromRoot, true);
        ASSERT_EQ(pushed.size(), fromRoot.size()) << "trial " << trial << " ray " << r;
        for (std::size_t i = 0; i < pushed.size(); ++i)
        {
          ASSERT_EQ(pushed[i].T0, fromRoot[i].T0);
          ASSERT_EQ(pushed[i].T1, fromRoot[i].T1);
          ASSERT_EQ(pushed[i].Node, fromRoot[i].Node);
          ASSERT_EQ(pushed[i].NodeLo, fromRoot[i].NodeLo);
          ASSERT_EQ(pushed[i].NodeHi, fromRoot[i].NodeHi);
        }
        segments += pushed.size();
      }
    }
  }
  EXPECT_GT(segments, 10000u);
}

TEST(Traversal, PushDownShortensDescentsOnADeepHierarchy)
{
  // The paper's dataset-3 shape (13 levels, 39,061 grids): tree levels descended per segment,
  // push-down with the far-child shortcut against restarts from the root, on rays through the
  // root box's centre region (measured: 7.1 against 16.4; push-down alone gave 13.6).
  const Hierarchy h = amrsp::test::PaperDataset3Boxes();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  std::mt19937_64 rng(3);
  std::uint64_t pushedSteps = 0, rootSteps = 0, segments = 0;
  for (int r = 0; r < 400; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::vec3 oi((o - h.Origin) / h.Spacing0), di(d / h.Spacing0);
    std::vector<RaySegment> pushed, fromRoot;
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), pushed, false, false);
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), fromRoot, true);
    ASSERT_EQ(pushed.size(), fromRoot.size());
    for (std::size_t i = 0; i < pushed.size(); ++i)
    {
      ASSERT_EQ(pushed[i].Node, fromRoot[i].Node);
      pushedSteps += pushed[i].Descent;
      rootSteps += fromRoot[i].Descent;
    }
    segments += pushed.size();
  }
  std::cout << segments << " segments; levels descended per segment: from the root "
            << double(rootSteps) / double(segments) << ", with push-down "
            << double(pushedSteps) / double(segments) << "\n";
  EXPECT_GT(segments, 1000u);
  EXPECT_LT(2 * pushedSteps, rootSteps);
}

TEST(Encoding, LimitsGiveClearErrors)
{
  // split position beyond 11 bits: a 5000-cell root grid with a level-0 neighbour at 3000
  Hierarchy wide;
  wide.Grids = { Grid{ 0, MakeBox(0, 0, 0, 3000, 1, 1) },
    Grid{ 0, MakeBox(3000, 0, 0, 5000, 1, 1) } };
  const KdTree t = BuildKdTree(wide);
  try
  {
    EncodeKdTree(wide, t);
    FAIL() << "expected an EncodingError";
  }
  catch (const EncodingError& e)
  {
    EXPECT_NE(std::string(e.what()).find("2047"), std::string::npos) << e.what();
  }

  // more than 64 levels
  Hierarchy deep;
  deep.RefinementRatio.assign(65, glm::ivec3(1));
  deep.Grids = { Grid{ 0, MakeBox(0, 0, 0, 2, 2, 2) } };
  EXPECT_THROW(EncodeKdTree(deep, BuildKdTree(deep)), EncodingError);

  // more data nodes than the 21-bit index: a tree object with 2^21 data leaves
  Hierarchy one;
  one.Grids = { Grid{ 0, MakeBox(0, 0, 0, 1, 1, 1) } };
  KdTree many;
  KdNode leaf;
  leaf.Grid = 0;
  leaf.Type = NodeType::Leaf;
  many.Nodes.assign(std::size_t(1) << 21, leaf);
  EXPECT_THROW(EncodeKdTree(one, many), EncodingError);

  // atlas offsets beyond 2048 x 2048 x 1024
  const Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  std::vector<glm::ivec3> origins(h.Grids.size(), glm::ivec3(0));
  EXPECT_NO_THROW(EncodeKdTree(h, tree, &origins));
  origins.back() = glm::ivec3(0, 0, 1024);
  EXPECT_THROW(EncodeKdTree(h, tree, &origins), EncodingError);

  // no level-0 grid
  Hierarchy noRoot;
  noRoot.RefinementRatio = { glm::ivec3(1), glm::ivec3(2) };
  noRoot.Grids = { Grid{ 1, MakeBox(0, 0, 0, 2, 2, 2) } };
  EXPECT_THROW(BuildKdTree(noRoot), HierarchyError);
}

TEST(Encoding, DataNodeOffsetsPointAtTheNodesCorner)
{
  using namespace layout;
  const Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  std::vector<glm::ivec3> origins;
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    origins.push_back(glm::ivec3(static_cast<int>(g) * 40, 3, 1));
  }
  const EncodedKdTree enc = EncodeKdTree(h, tree, &origins);
  const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
  for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
  {
    const uint data = amrspNodeData(enc.Tree.Texels[i]);
    if (data == 0)
    {
      continue;
    }
    const KdNode& n = tree.Nodes[i];
    const Grid& g = h.Grids[n.Grid];
    const glm::i64vec3 toData = finest / h.CumulativeRatio(g.Level);
    const glm::i64vec3 corner = n.Region.Lo / toData - g.Cells.Lo;
    EXPECT_EQ(glm::i64vec3(amrspDataOffset(enc.DataNodes.Texels[data])),
      glm::i64vec3(origins[n.Grid]) + corner);
  }
}

TEST(Render, KdTreeIntegratorMatchesReference)
{
  const Hierarchy h = PaperExample();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  RenderSettings s = SmallView(h);
  s.SampleDistanceFactor = 0.25;
  s.ReferenceSampleFactor = 0.25;
  const Image tree = RenderKdTree(h, enc, s);
  const Image ref = RenderReference(h, s);
  double coverage = 0.0;
  for (const glm::vec4& p : ref.Pixels)
  {
    coverage += p.a > 0.01f ? 1.0 : 0.0;
  }
  EXPECT_GT(coverage / ref.Pixels.size(), 0.2); // the volume fills a good part of the image
  const double rmse = Rmse(tree, ref);
  EXPECT_LT(rmse, 2.0) << "RMSE " << rmse;

  // the test can fail: a wrong data node (every sample from grid 0) is far off
  Hierarchy broken = h;
  for (std::size_t g = 1; g < broken.Values.size(); ++g)
  {
    for (float& v : broken.Values[g])
    {
      v = 1.0f - v;
    }
  }
  EXPECT_GT(Rmse(RenderKdTree(broken, enc, s), ref), 4.0);
}

TEST(Render, LevelOfDetailCoarsensFarAway)
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(4) };
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 8, 8, 8) }, Grid{ 1, MakeBox(0, 0, 0, 16, 32, 32) },
    Grid{ 1, MakeBox(16, 0, 0, 32, 32, 32) } };
  FillValues(h);
  const KdTree tree = BuildKdTree(h);
  ASSERT_EQ(tree.Root().Type, NodeType::Refined);
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  RenderSettings s = SmallView(h);
  const Image finest = RenderKdTree(h, enc, s);
  s.LodThresholdPixels = 1000.0f; // any level-1 cell is "too small": show level 0
  const Image coarse = RenderKdTree(h, enc, s);
  EXPECT_GT(Rmse(finest, coarse), 0.5);
  s.LodThresholdPixels = 1e-6f; // nothing is too small: identical to no LOD
  EXPECT_EQ(Rmse(finest, RenderKdTree(h, enc, s)), 0.0);
}

} // namespace
