// SPDX-License-Identifier: BSD-3-Clause
// PartitionRootBox: the regions tile the root box, every grid cell falls in exactly one region,
// the cuts balance the cells, and degenerate boxes give empty parts.
#include "TestHierarchies.h"
#include "amrsp/RankPartition.h"

#include <gtest/gtest.h>

#include <random>

using namespace amrsp;
using amrsp::test::MakeBox;

namespace
{

/// Cells of all grids inside `region` (each grid clipped to it).
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
