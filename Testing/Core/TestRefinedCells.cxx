// SPDX-License-Identifier: BSD-3-Clause
// RefinedRegions / RefinedCellMask against a cell-by-cell brute force, and on a deep, sparse
// hierarchy (the paper's dataset-3 shape) whose level index spaces span 2^12 root cells.
#include "TestHierarchies.h"
#include "amrsp/RefinedCells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace amrsp;
using amrsp::test::MakeBox;

namespace
{

/// 1 where the cell of grid g overlaps any grid of the next level, cell by cell.
std::vector<unsigned char> BruteForceMask(const Hierarchy& h, std::size_t g)
{
  const Grid& grid = h.Grids[g];
  const glm::i64vec3 e = grid.Cells.Extent();
  std::vector<unsigned char> mask(static_cast<std::size_t>(grid.Cells.Cells()), 0);
  if (grid.Level + 1 >= h.NumberOfLevels())
  {
    return mask; // the finest level: no next level, no ratio to it
  }
  for (int64_t k = 0; k < e.z; ++k)
    for (int64_t j = 0; j < e.y; ++j)
      for (int64_t i = 0; i < e.x; ++i)
      {
        const glm::i64vec3 c = grid.Cells.Lo + glm::i64vec3(i, j, k);
        const Box fine = h.ToLevel(Box{ c, c + glm::i64vec3(1) }, grid.Level, grid.Level + 1);
        for (const Grid& child : h.Grids)
        {
          if (child.Level == grid.Level + 1 && child.Cells.Overlaps(fine))
          {
            mask[static_cast<std::size_t>((k * e.y + j) * e.x + i)] = 1;
          }
        }
      }
  return mask;
}

void ExpectMatchesBruteForce(const Hierarchy& h)
{
  const std::vector<std::vector<Box>> regions = RefinedRegions(h);
  ASSERT_EQ(regions.size(), h.Grids.size());
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    EXPECT_EQ(RefinedCellMask(h.Grids[g].Cells, regions[g]), BruteForceMask(h, g)) << "grid " << g;
    for (const Box& b : regions[g])
    {
      EXPECT_TRUE(h.Grids[g].Cells.Contains(b)) << "grid " << g;
    }
  }
}

} // namespace

TEST(RefinedCells, PaperExampleMatchesBruteForce)
{
  const Hierarchy h = amrsp::test::PaperExample();
  ExpectMatchesBruteForce(h);
  // The level-1 grid (2,2,0)-(12,10,8) refines root cells (1,1,0)-(6,5,4): 5*4*4 = 80 cells
  const std::vector<std::vector<Box>> regions = RefinedRegions(h);
  const std::vector<unsigned char> root = RefinedCellMask(h.Grids[0].Cells, regions[0]);
  EXPECT_GT(std::count(root.begin(), root.end(), 1), 80);
  // The finest level refines nothing.
  EXPECT_TRUE(regions[4].empty());
  EXPECT_TRUE(regions[5].empty());
}

TEST(RefinedCells, RandomHierarchiesMatchBruteForce)
{
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 40; ++trial)
  {
    SCOPED_TRACE(trial);
    ExpectMatchesBruteForce(amrsp::test::RandomHierarchy(rng));
  }
}

TEST(RefinedCells, OddRatioAndUnalignedChildCoarsenOutward)
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(3, 2, 4) };
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 6, 6, 6) });
  h.Grids.push_back(Grid{ 1, MakeBox(4, 3, 5, 8, 5, 9) }); // not aligned to coarse cells
  ExpectMatchesBruteForce(h);
  const std::vector<std::vector<Box>> regions = RefinedRegions(h);
  ASSERT_EQ(regions[0].size(), 1u);
  EXPECT_EQ(regions[0][0], MakeBox(1, 1, 1, 3, 3, 3));
}

TEST(RefinedCells, DeepSparseHierarchyStaysSmall)
{
  // 13 levels: level 12 spans 2^12 times the root per axis. A bin grid over each level's
  // index space (VTK's GenerateParentChildInformation) needs tens of GB here.
  const Hierarchy h = amrsp::test::PaperDataset3Boxes();
  const std::vector<std::vector<Box>> regions = RefinedRegions(h);
  std::size_t refinedGrids = 0;
  std::size_t boxes = 0;
  for (std::size_t g = 0; g < regions.size(); ++g)
  {
    refinedGrids += regions[g].empty() ? 0 : 1;
    boxes += regions[g].size();
    for (const Box& b : regions[g])
    {
      ASSERT_TRUE(h.Grids[g].Cells.Contains(b));
    }
  }
  // every grid above level 0 is properly nested, so it refines at least one parent cell
  std::size_t fine = 0;
  for (const Grid& g : h.Grids)
  {
    fine += g.Level > 0 ? 1 : 0;
  }
  EXPECT_GE(boxes, fine);
  EXPECT_GT(refinedGrids, 0u);
}
