// SPDX-License-Identifier: BSD-3-Clause
// PartitionRootBox: the regions tile the root box, every grid cell falls in exactly one region,
// the cuts balance the cells, and degenerate boxes give empty parts. Clipping rays to a region:
// the region's ghosted pieces render exactly what the whole hierarchy renders there.
#include "TestHierarchies.h"
#include "amrsp/RankPartition.h"
#include "amrsp/Render.h"

#include <gtest/gtest.h>

#include <random>

using namespace amrsp;
using amrsp::test::MakeBox;

namespace
{

/// Cells of all grids inside `region` (each grid clipped to it).
/// The hierarchy a region's rank holds: every grid cut to `piece(grid)`, values copied
/// (cell-centred).
template <typename Piece>
Hierarchy PiecesOf(const Hierarchy& h, Piece piece)
{
  Hierarchy out = h;
  out.Grids.clear();
  out.Values.clear();
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const Grid& grid = h.Grids[g];
    const Box p = piece(grid);
    if (p.Empty())
    {
      continue;
    }
    const glm::i64vec3 e = grid.Cells.Extent(), pe = p.Extent();
    std::vector<float> values;
    for (int64_t k = p.Lo.z; k < p.Hi.z; ++k)
      for (int64_t j = p.Lo.y; j < p.Hi.y; ++j)
        for (int64_t i = p.Lo.x; i < p.Hi.x; ++i)
        {
          const glm::i64vec3 c = glm::i64vec3(i, j, k) - grid.Cells.Lo;
          values.push_back(h.Values[g][static_cast<std::size_t>((c.z * e.y + c.y) * e.x + c.x)]);
        }
    EXPECT_EQ(static_cast<int64_t>(values.size()), pe.x * pe.y * pe.z);
    out.Grids.push_back(Grid{ grid.Level, p, grid.SourceId });
    out.Values.push_back(std::move(values));
  }
  return out;
}

double LargestDifference(const Image& a, const Image& b)
{
  double largest = 0.0;
  for (std::size_t k = 0; k < a.Pixels.size(); ++k)
  {
    largest = std::max(largest, static_cast<double>(glm::length(a.Pixels[k] - b.Pixels[k])));
  }
  return largest;
}

int64_t CellsIn(const Hierarchy& h, const Box& region)
{
  int64_t n = 0;
  for (const Grid& g : h.Grids)
  {
    n += ClipToRegion(h, g.Cells, g.Level, region).Cells();
  }
  return n;
}

void ExpectTiling(const Hierarchy& h, int parts)
{
  const std::vector<Box> regions = PartitionRootBox(h, parts);
  ASSERT_EQ(regions.size(), static_cast<std::size_t>(parts));
  const Box root = h.RootCells();
  int64_t volume = 0;
  for (std::size_t i = 0; i < regions.size(); ++i)
  {
    if (regions[i].Empty())
    {
      continue;
    }
    EXPECT_TRUE(root.Contains(regions[i])) << "region " << i;
    volume += regions[i].Cells();
    for (std::size_t j = i + 1; j < regions.size(); ++j)
    {
      EXPECT_FALSE(regions[i].Overlaps(regions[j])) << "regions " << i << " and " << j;
    }
  }
  EXPECT_EQ(volume, root.Cells()) << parts << " parts";
  // every cell inside the root box (the kD-tree's root: cells outside it are never rendered) in
  // exactly one region
  int64_t cells = 0;
  for (const Box& r : regions)
  {
    cells += CellsIn(h, r);
  }
  EXPECT_EQ(cells, CellsIn(h, root)) << parts << " parts";
}

} // namespace

TEST(RankPartition, TilesThePaperExample)
{
  const Hierarchy h = amrsp::test::PaperExample();
  for (int parts = 1; parts <= 9; ++parts)
  {
    ExpectTiling(h, parts);
  }
}

TEST(RankPartition, TilesRandomHierarchies)
{
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 40; ++trial)
  {
    const Hierarchy h = amrsp::test::RandomHierarchy(rng);
    for (int parts : { 2, 3, 4, 7 })
    {
      ExpectTiling(h, parts);
    }
  }
}

TEST(RankPartition, BalancesAUniformGrid)
{
  Hierarchy h;
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 16, 8, 8) });
  const std::vector<Box> regions = PartitionRootBox(h, 4);
  for (const Box& r : regions)
  {
    EXPECT_EQ(r.Cells(), 16 * 8 * 8 / 4);
  }
  // the first cut is across the longest axis (x), at its middle; each 8^3 half is then cut
  // across its first axis of equal length (x again)
  EXPECT_EQ(regions[1], MakeBox(4, 0, 0, 8, 8, 8));
  EXPECT_EQ(regions[2], MakeBox(8, 0, 0, 12, 8, 8));
}

TEST(RankPartition, CutsFollowTheFineCellsNotTheVolume)
{
  // level 0: 16 cells along x; a ratio-4 patch over x in [0, 4) holds 64x as many cells per
  // level-0 slab as the coarse level: the balanced cut lies inside the patch, not at x = 8
  Hierarchy h;
  h.RefinementRatio.push_back(glm::ivec3(4));
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 16, 2, 2) });
  h.Grids.push_back(Grid{ 1, MakeBox(0, 0, 0, 16, 8, 8) });
  const std::vector<Box> regions = PartitionRootBox(h, 2);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[0].Hi.x, 2);
  const double lower = static_cast<double>(CellsIn(h, regions[0]));
  const double total = static_cast<double>(h.TotalCells());
  EXPECT_NEAR(lower / total, 0.5, 0.03);
}

TEST(RankPartition, OddPartsGetProportionalShares)
{
  Hierarchy h;
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 30, 3, 3) });
  const std::vector<Box> regions = PartitionRootBox(h, 3);
  for (const Box& r : regions)
  {
    EXPECT_EQ(r.Extent().x, 10);
  }
}

TEST(RankPartition, ACellThatCannotBeCutGoesToTheFirstPart)
{
  Hierarchy h;
  h.Grids.push_back(Grid{ 0, MakeBox(3, 3, 3, 4, 4, 4) });
  const std::vector<Box> regions = PartitionRootBox(h, 3);
  ASSERT_EQ(regions.size(), 3u);
  EXPECT_EQ(regions[0], h.RootCells());
  EXPECT_TRUE(regions[1].Empty());
  EXPECT_TRUE(regions[2].Empty());
  ExpectTiling(h, 3);
}

TEST(RankPartition, RejectsBadArguments)
{
  Hierarchy empty;
  EXPECT_THROW(PartitionRootBox(empty, 2), std::invalid_argument);
  Hierarchy h;
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 4, 4, 4) });
  EXPECT_THROW(PartitionRootBox(h, 0), std::invalid_argument);
}

namespace
{

/// Reference images of the paper example clipped to the upper region of a 2-part split: the whole
/// hierarchy, its ghosted pieces (what a rank holds) and its pieces without ghosts.
struct ClippedImages
{
  Image Whole, Ghosted, Bare;
  double Covered = 0.0; // share of pixels whose rays cross the region
};

ClippedImages RenderRegion(bool smooth, bool shade)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const std::vector<Box> regions = PartitionRootBox(h, 2);
  const Box region = regions[1];
  RenderSettings s = amrsp::test::SmallView(h);
  s.Threads = 1;
  s.SmoothCellData = smooth;
  s.Light.Shade = shade;
  s.Clip = true;
  s.ClipLo = h.WorldLo(region, 0);
  s.ClipHi = h.WorldHi(region, 0);
  ClippedImages out;
  out.Whole = RenderReference(h, s);
  out.Ghosted = RenderReference(
    PiecesOf(h, [&](const Grid& g) { return GhostedPiece(h, g.Cells, g.Level, region); }), s);
  out.Bare = RenderReference(
    PiecesOf(h, [&](const Grid& g) { return ClipToRegion(h, g.Cells, g.Level, region); }), s);
  RenderSettings unclipped = s;
  unclipped.Clip = false;
  const Image all = RenderReference(h, unclipped);
  int covered = 0;
  for (std::size_t k = 0; k < all.Pixels.size(); ++k)
  {
    covered += out.Whole.Pixels[k].a > 0.0f ? 1 : 0;
  }
  out.Covered = static_cast<double>(covered) / static_cast<double>(all.Pixels.size());
  EXPECT_GT(LargestDifference(all, out.Whole), 0.05) << "the clip box changes nothing";
  return out;
}

} // namespace

TEST(RankPartition, ClippedRaysSeeTheRegionOnly)
{
  const ClippedImages nearest = RenderRegion(false, false);
  EXPECT_GT(nearest.Covered, 0.1);
  // nearest cells: the region's cells alone give the same image
  EXPECT_LT(LargestDifference(nearest.Whole, nearest.Ghosted), 1e-6);
  EXPECT_LT(LargestDifference(nearest.Whole, nearest.Bare), 1e-6);
}

TEST(RankPartition, GhostCellsKeepSmoothShadingAtTheRegionFace)
{
  const ClippedImages smooth = RenderRegion(true, true);
  // smooth corners and gradient neighbours read across the face: the ghosted pieces give the
  // whole hierarchy's image, the bare pieces do not
  EXPECT_LT(LargestDifference(smooth.Whole, smooth.Ghosted), 1e-6);
  EXPECT_GT(LargestDifference(smooth.Whole, smooth.Bare), 0.01);
}
