// SPDX-License-Identifier: BSD-3-Clause
// Tests of the kD-tree builder, its texture encoding and the CPU traversal that mirrors the shader.
#include "amrsp/BrickAtlas.h"
#include "amrsp/Invariants.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/Render.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <random>

namespace
{
using namespace amrsp;

Box MakeBox(int64_t x0, int64_t y0, int64_t z0, int64_t x1, int64_t y1, int64_t z1)
{
  return Box{ glm::i64vec3(x0, y0, z0), glm::i64vec3(x1, y1, z1) };
}

/// Analytic field sampled at cell centres (level-0 index units), so values differ per level.
void FillValues(Hierarchy& h)
{
  h.Values.clear();
  for (const Grid& g : h.Grids)
  {
    const glm::dvec3 cs = h.CellSize(g.Level);
    const glm::i64vec3 e = g.Cells.Extent();
    GridValues v(static_cast<std::size_t>(g.Cells.Cells()));
    for (int64_t k = 0; k < e.z; ++k)
      for (int64_t j = 0; j < e.y; ++j)
        for (int64_t i = 0; i < e.x; ++i)
        {
          const glm::dvec3 p = (glm::dvec3(g.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * cs;
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] = static_cast<float>(
            0.5 + 0.5 * std::sin(0.7 * p.x) * std::cos(0.5 * p.y) + 0.05 * p.z);
        }
    h.Values.push_back(std::move(v));
  }
}

/// The 2D example of the paper's Figure 2, extruded: one root grid, three level-1 grids (one of
/// them overlapping two parents' worth of cells), two level-2 grids abutting level-0 cells.
Hierarchy PaperExample()
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2), glm::ivec3(2) };
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 16, 16, 4) });
  h.Grids.push_back(Grid{ 1, MakeBox(2, 2, 0, 12, 10, 8) });
  h.Grids.push_back(Grid{ 1, MakeBox(16, 4, 0, 28, 14, 8) });
  h.Grids.push_back(Grid{ 1, MakeBox(6, 20, 2, 24, 30, 6) });
  h.Grids.push_back(Grid{ 2, MakeBox(6, 6, 0, 20, 18, 16) });
  h.Grids.push_back(Grid{ 2, MakeBox(36, 10, 4, 52, 26, 12) });
  h.Spacing0 = glm::dvec3(0.5, 0.25, 1.0); // anisotropic
  h.Origin = glm::dvec3(-3.0, 1.0, 2.0);
  for (std::size_t i = 0; i < h.Grids.size(); ++i)
  {
    h.Grids[i].SourceId = static_cast<int64_t>(i);
  }
  FillValues(h);
  return h;
}

/// A random hierarchy: several root grids with gaps, per-level ratios 2 or 4 (sometimes
/// anisotropic), fine grids that may straddle several parents, stick out of their parents'
/// coverage, or skip a level. Same-level grids never overlap.
Hierarchy RandomHierarchy(std::mt19937_64& rng)
{ // structure only: the tree and traversal tests compare grids and cells, not values
  auto uni = [&](int64_t lo, int64_t hi) {
    return lo + static_cast<int64_t>(rng() % static_cast<uint64_t>(hi - lo + 1));
  };
  Hierarchy h;
  const int levels = static_cast<int>(uni(1, 5));
  h.RefinementRatio.assign(1, glm::ivec3(1));
  for (int l = 1; l < levels; ++l)
  {
    glm::ivec3 r(uni(0, 3) == 0 ? 4 : 2);
    if (uni(0, 5) == 0)
    {
      r[static_cast<int>(uni(0, 2))] = 1 + static_cast<int>(uni(1, 3)); // anisotropic ratio
    }
    h.RefinementRatio.push_back(r);
  }
  h.Spacing0 = glm::dvec3(0.5 + uni(0, 10) * 0.1, 0.5 + uni(0, 10) * 0.1, 0.5 + uni(0, 10) * 0.1);
  h.Origin = glm::dvec3(uni(-5, 5), uni(-5, 5), uni(-5, 5));

  const glm::i64vec3 domain(uni(6, 20), uni(6, 20), uni(6, 20));
  std::vector<Box> previous;
  for (int l = 0; l < levels; ++l)
  {
    std::vector<Box> boxes;
    const glm::i64vec3 extent = l == 0 ? domain : domain * h.CumulativeRatio(l);
    const int attempts = l == 0 ? 12 : static_cast<int>(uni(0, 30));
    if (l > 0 && uni(0, 6) == 0)
    {
      continue; // a level with no grids: the next level jumps two levels
    }
    for (int a = 0; a < attempts; ++a)
    {
      glm::i64vec3 lo, hi;
      if (l > 0 && !previous.empty() && uni(0, 4) != 0)
      {
        // mostly near a grid of the previous level, possibly straddling its boundary
        const Box& p = previous[static_cast<std::size_t>(uni(0, static_cast<int64_t>(previous.size()) - 1))];
        const Box pr = p.Refined(glm::i64vec3(h.RefinementRatio[l]));
        for (int c = 0; c < 3; ++c)
        {
          lo[c] = uni(pr.Lo[c] - 2, pr.Hi[c] - 1);
          hi[c] = std::min(extent[c], lo[c] + uni(1, std::max<int64_t>(1, (pr.Hi[c] - pr.Lo[c]))));
          lo[c] = std::max<int64_t>(0, lo[c]);
          if (hi[c] <= lo[c])
          {
            hi[c] = lo[c] + 1;
          }
        }
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          lo[c] = uni(0, extent[c] - 1);
          hi[c] = std::min(extent[c], lo[c] + uni(1, std::max<int64_t>(1, extent[c] / 2)));
        }
      }
      const Box b{ lo, hi };
      bool free = true;
      for (const Box& o : boxes)
      {
        free = free && !o.Overlaps(b);
      }
      if (free)
      {
        boxes.push_back(b);
      }
    }
    for (const Box& b : boxes)
    {
      h.Grids.push_back(Grid{ l, b, static_cast<int64_t>(h.Grids.size()) });
    }
    if (!boxes.empty())
    {
      previous = boxes;
    }
  }
  return h;
}

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
    const glm::uvec3 o(rng() % (MaxOffsetX + 1), rng() % (MaxOffsetY + 1), rng() % (MaxOffsetZ + 1));
    const uvec2 d = amrspPackDataNode(level, brick, o.x, o.y, o.z);
    ASSERT_EQ(amrspDataLevel(d), level);
    ASSERT_EQ(amrspDataBrick(d), brick);
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

/// Rays from outside and inside the root box, axis-parallel rays and rays through cell corners.
void RandomRay(std::mt19937_64& rng, const Hierarchy& h, glm::dvec3& o, glm::dvec3& d)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Grid& g : h.Grids)
  {
    if (g.Level == 0)
    {
      lo = glm::min(lo, h.WorldLo(g.Cells, 0));
      hi = glm::max(hi, h.WorldHi(g.Cells, 0));
    }
  }
  const glm::dvec3 size = hi - lo;
  const int kind = static_cast<int>(rng() % 4);
  const glm::dvec3 target = lo + size * glm::dvec3(u(rng), u(rng), u(rng));
  if (kind == 0)
  {
    o = lo + size * glm::dvec3(u(rng), u(rng), u(rng)); // inside
  }
  else
  {
    o = lo - size + 3.0 * size * glm::dvec3(u(rng), u(rng), u(rng));
  }
  d = glm::normalize(target - o + 1e-9);
  if (kind == 2)
  {
    // axis-parallel through a level-0 cell corner-aligned line
    const int a = static_cast<int>(rng() % 3);
    d = glm::dvec3(0.0);
    d[a] = (rng() % 2) ? 1.0 : -1.0;
    o = h.Origin + glm::floor((target - h.Origin) / h.Spacing0) * h.Spacing0;
    o[a] = d[a] > 0 ? lo[a] - 1.0 : hi[a] + 1.0;
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
        const glm::dvec3 c =
          ts.Position * glm::dvec3(h.CumulativeRatio(h.Grids[ts.Grid].Level));
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
      const glm::dvec3 mid = glm::dvec3(oi) + 0.5 * (double(segs[i].T0) + segs[i].T1) * glm::dvec3(di);
      const glm::dvec3 lo = RegionLoIndex(h, tree, n.Region), hi = RegionHiIndex(h, tree, n.Region);
      for (int a = 0; a < 3; ++a)
      {
        ASSERT_GE(mid[a], lo[a] - 1e-4);
        ASSERT_LE(mid[a], hi[a] + 1e-4);
      }
    }
  }
}

TEST(Encoding, LimitsGiveClearErrors)
{
  // split position beyond 11 bits: a 5000-cell root grid with a level-0 neighbour at 3000
  Hierarchy wide;
  wide.Grids = { Grid{ 0, MakeBox(0, 0, 0, 3000, 1, 1) }, Grid{ 0, MakeBox(3000, 0, 0, 5000, 1, 1) } };
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

RenderSettings SmallView(const Hierarchy& h)
{
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Grid& g : h.Grids)
  {
    if (g.Level == 0)
    {
      lo = glm::min(lo, h.WorldLo(g.Cells, 0));
      hi = glm::max(hi, h.WorldHi(g.Cells, 0));
    }
  }
  RenderSettings s;
  s.Width = 64;
  s.Height = 48;
  s.View.FocalPoint = 0.5 * (lo + hi);
  s.View.Position = s.View.FocalPoint + glm::dvec3(0.6, 0.5, 1.0) * 1.2 * glm::length(hi - lo);
  s.Transfer = TransferFunction::Preset("default", 0.0, 1.2, 0.1 * glm::length(hi - lo));
  return s;
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

namespace
{
TEST(Atlas, EveryTexelHoldsItsCellAndThePackingPathMatches)
{
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 12; ++trial)
  {
    Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    if (trial > 0)
    {
      FillValues(h);
    }
    for (Packer packer : { Packer::NextFitDecreasingHeight, Packer::Best })
    {
      const BrickAtlas atlas = BuildBrickAtlas(h, packer, glm::ivec3(2048, 2048, 1024));
      for (std::size_t g = 0; g < h.Grids.size(); ++g)
      {
        const glm::i64vec3 e = h.Grids[g].Cells.Extent();
        for (int probe = 0; probe < 50; ++probe)
        {
          const glm::i64vec3 c(rng() % e.x, rng() % e.y, rng() % e.z);
          ASSERT_EQ(atlas.At(atlas.Layout.Origins[g] + glm::ivec3(c)),
            CellValue(h, static_cast<int32_t>(g), h.Grids[g].Cells.Lo + c));
        }
      }
      // the shader's addressing (data-node offsets into the atlas) samples the same values as
      // looking the grids up directly
      const KdTree tree = BuildKdTree(h);
      const EncodedKdTree plain = EncodeKdTree(h, tree);
      const EncodedKdTree packed = EncodeKdTree(h, tree, &atlas.Layout.Origins);
      RenderSettings s = SmallView(h);
      s.Width = 40;
      s.Height = 30;
      const Image direct = RenderKdTree(h, plain, s);
      const Image viaAtlas = RenderKdTree(h, packed, s, &atlas);
      ASSERT_EQ(Rmse(direct, viaAtlas), 0.0) << "trial " << trial;
    }
  }
}

TEST(Render, NaNSamplesAreTransparent)
{
  Hierarchy h = PaperExample();
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  RenderSettings s = SmallView(h);
  for (float& v : h.Values[0])
  {
    v = std::numeric_limits<float>::quiet_NaN();
  }
  const Image withNaN = RenderKdTree(h, enc, s);
  for (const glm::vec4& p : withNaN.Pixels)
  {
    ASSERT_FALSE(std::isnan(p.r) || std::isnan(p.a));
  }
  for (float& v : h.Values[0])
  {
    v = -1e30f; // below the transfer function: opacity 0, like a NaN
  }
  EXPECT_EQ(Rmse(withNaN, RenderKdTree(h, enc, s)), 0.0);
}
} // namespace
