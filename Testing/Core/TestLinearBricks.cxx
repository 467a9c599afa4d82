// SPDX-License-Identifier: BSD-3-Clause
// The linear storage: the page layout, the brick table the shader reads, and the rectangles each
// brick is uploaded to.
#include "amrsp/FinestCellLocator.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/LinearBricks.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

// The pages' texels as the mapper uploads them: every brick's runs (LinearBrickRuns) copied from
// its values into NaN-filled pages. Fails the test when a run is malformed, leaves its page or
// writes a texel that an earlier run wrote.
std::vector<std::vector<float>> UploadPages(const Hierarchy& h, const LinearBrickLayout& layout)
{
  std::vector<std::vector<float>> pages;
  std::vector<std::vector<bool>> written;
  for (int rows : layout.PageRows)
  {
    pages.emplace_back(
      static_cast<std::size_t>(rows) << layout.WidthLog2, std::numeric_limits<float>::quiet_NaN());
    written.emplace_back(pages.back().size(), false);
  }
  const int64_t width = layout.Width();
  for (std::size_t g = 0; g < layout.Base.size(); ++g)
  {
    const std::vector<LinearRun> runs = LinearBrickRuns(layout, g);
    EXPECT_LE(runs.size(), 3u) << "grid " << g;
    const std::size_t p = static_cast<std::size_t>(layout.PageOfGrid[g]);
    int64_t values = 0;
    for (const LinearRun& run : runs)
    {
      // one partial row, or whole rows
      EXPECT_TRUE(run.Rows == 1 ? run.X + run.Width <= width : run.X == 0 && run.Width == width)
        << "grid " << g;
      EXPECT_EQ(run.FirstValue, values) << "grid " << g; // in the brick's own order
      EXPECT_LE(static_cast<int64_t>(run.Y) + run.Rows, layout.PageRows[p]) << "grid " << g;
      for (int64_t k = 0; k < static_cast<int64_t>(run.Width) * run.Rows; ++k)
      {
        const std::size_t t =
          static_cast<std::size_t>((static_cast<int64_t>(run.Y) << layout.WidthLog2) + run.X + k);
        if (t >= pages[p].size())
        {
          ADD_FAILURE() << "grid " << g << " writes past its page";
          return pages;
        }
        EXPECT_FALSE(written[p][t]) << "grid " << g << " writes texel " << t << " again";
        written[p][t] = true;
        pages[p][t] = h.Values[g][static_cast<std::size_t>(run.FirstValue + k)];
      }
      values += static_cast<int64_t>(run.Width) * run.Rows;
    }
    const glm::ivec3 e = layout.Extents[g];
    EXPECT_EQ(values, static_cast<int64_t>(e.x) * e.y * e.z) << "grid " << g;
  }
  return pages;
}

TEST(LinearBricks, TheTableAddressesEveryCellAsTheShaderDoes)
{
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 10; ++trial)
  {
    Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    if (trial > 0)
    {
      FillValues(h);
    }
    std::vector<glm::ivec3> extents;
    int64_t total = 0;
    for (const Grid& g : h.Grids)
    {
      extents.emplace_back(g.Cells.Extent());
      total += g.Cells.Cells();
    }
    // narrow rows and few of them, so that bricks cross rows and spread over pages
    const int widthLog2 = 3 + trial % 4;
    const int maxRows =
      static_cast<int>(std::max<int64_t>((total >> widthLog2) / 2 + 1,
                         (h.Grids.empty() ? 1 : h.Grids[0].Cells.Cells()) >> widthLog2) +
        1);
    LinearBrickLayout layout;
    try
    {
      layout = LayOutLinearBricks(extents, widthLog2, maxRows);
    }
    catch (const std::runtime_error&)
    {
      layout = LayOutLinearBricks(extents, widthLog2, 1 << 20);
    }
    const UIntTexture3D table = LinearBrickTable(layout);
    const std::vector<std::vector<float>> pages = UploadPages(h, layout);
    for (std::size_t g = 0; g < h.Grids.size(); ++g)
    {
      // decoded as SinglePassAMR.frag.glsl does
      const glm::uvec2 entry = table.Texels[g];
      const uint32_t page = entry.x >> LinearBaseBits;
      const int64_t base = entry.x & ((1u << LinearBaseBits) - 1u);
      const int64_t nx = entry.y & 0xffffu, ny = entry.y >> 16;
      ASSERT_LT(page, pages.size());
      const glm::i64vec3 e = h.Grids[g].Cells.Extent();
      ASSERT_EQ(nx, e.x);
      ASSERT_EQ(ny, e.y);
      for (int probe = 0; probe < 40; ++probe)
      {
        const glm::i64vec3 c(rng() % e.x, rng() % e.y, rng() % e.z);
        const int64_t i = base + c.x + nx * (c.y + ny * c.z);
        ASSERT_EQ(pages[page][static_cast<std::size_t>(i)],
          CellValue(h, static_cast<int32_t>(g), h.Grids[g].Cells.Lo + c))
          << "trial " << trial << ", grid " << g;
      }
    }
    // no gaps: the pages' used texels are the cells
    int64_t used = 0;
    for (int64_t t : layout.PageTexels)
    {
      used += t;
    }
    EXPECT_EQ(used, total);
  }
}

TEST(LinearBricks, PagesSplitBetweenBricksAndTheLimitsAreNamed)
{
  // bricks of 10, 20, 30 and 40 texels in pages of 4 rows of 16 texels: 10 + 20 + 30 = 60 fit in
  // the first page's 64; 40 opens the second
  const std::vector<glm::ivec3> extents = { { 10, 1, 1 }, { 5, 4, 1 }, { 3, 5, 2 }, { 2, 2, 10 } };
  const LinearBrickLayout layout = LayOutLinearBricks(extents, 4, 4);
  EXPECT_EQ(layout.PageOfGrid, (std::vector<int>{ 0, 0, 0, 1 }));
  EXPECT_EQ(layout.Base, (std::vector<int64_t>{ 0, 10, 30, 0 }));
  EXPECT_EQ(layout.PageRows, (std::vector<int>{ 4, 3 }));
  EXPECT_EQ(layout.TotalTexels(), 7 * 16);
  // a brick larger than a page, or more pages than the shader addresses
  EXPECT_THROW(LayOutLinearBricks({ { 65, 1, 1 } }, 4, 4), std::runtime_error);
  EXPECT_THROW(
    LayOutLinearBricks(std::vector<glm::ivec3>(5, glm::ivec3(64, 1, 1)), 4, 4), std::runtime_error);
  EXPECT_THROW(LayOutLinearBricks({ { 70000, 1, 1 } }, 20, 1), std::runtime_error);
  Hierarchy h = PaperExample();
  std::vector<glm::ivec3> paper;
  for (const Grid& g : h.Grids)
  {
    paper.emplace_back(g.Cells.Extent());
  }
  const LinearBrickLayout small = LayOutLinearBricks(paper, 4, 1 << 10);
  EXPECT_THROW(LinearBrickRuns(small, paper.size()), std::out_of_range);
  // a brick of 3 x 5 x 2 = 30 texels from texel 30 of rows of 16: the rest of row 1 (2 texels),
  // row 2 whole, and 12 texels of row 3
  const std::vector<LinearRun> runs = LinearBrickRuns(layout, 2);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(glm::ivec4(runs[0].X, runs[0].Y, runs[0].Width, runs[0].Rows), glm::ivec4(14, 1, 2, 1));
  EXPECT_EQ(glm::ivec4(runs[1].X, runs[1].Y, runs[1].Width, runs[1].Rows), glm::ivec4(0, 2, 16, 1));
  EXPECT_EQ(glm::ivec4(runs[2].X, runs[2].Y, runs[2].Width, runs[2].Rows), glm::ivec4(0, 3, 12, 1));
  EXPECT_EQ(runs[2].FirstValue, 18);
}

} // namespace
