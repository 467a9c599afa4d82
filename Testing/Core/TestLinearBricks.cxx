// SPDX-License-Identifier: BSD-3-Clause
// The linear storage: the page layout, the brick table the shader reads, and the slab filler.
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

// The pages' texels, filled `rowsPerSlab` rows at a time into NaN-filled buffers.
std::vector<std::vector<float>> FillPages(
  const Hierarchy& h, const LinearBrickLayout& layout, int rowsPerSlab)
{
  const LinearSlabFiller filler(h, layout);
  std::vector<std::vector<float>> pages;
  for (std::size_t p = 0; p < layout.PageRows.size(); ++p)
  {
    const int rows = layout.PageRows[p];
    std::vector<float> texels(
      static_cast<std::size_t>(rows) << layout.WidthLog2, std::numeric_limits<float>::quiet_NaN());
    for (int r0 = 0; r0 < rows; r0 += rowsPerSlab)
    {
      filler.Fill(static_cast<int>(p), r0, std::min(rows, r0 + rowsPerSlab),
        texels.data() + (static_cast<std::size_t>(r0) << layout.WidthLog2));
    }
    pages.push_back(std::move(texels));
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
    // narrow rows and few of them, so that slabs cut bricks and bricks spread over pages
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
    for (int rowsPerSlab : { 1, 2, 1 << 20 })
    {
      const std::vector<std::vector<float>> pages = FillPages(h, layout, rowsPerSlab);
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
      // after the last brick every texel is written, with 0
      for (std::size_t p = 0; p < pages.size(); ++p)
      {
        for (std::size_t i = static_cast<std::size_t>(layout.PageTexels[p]); i < pages[p].size();
             ++i)
        {
          ASSERT_EQ(pages[p][i], 0.0f) << "page " << p << ", texel " << i;
        }
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
  const LinearSlabFiller filler(h, small);
  std::vector<float> out(16);
  EXPECT_THROW(filler.Fill(1, 0, 1, out.data()), std::invalid_argument);
  EXPECT_THROW(filler.Fill(0, 0, small.PageRows[0] + 1, out.data()), std::invalid_argument);
  h.Values.pop_back();
  EXPECT_THROW(LinearSlabFiller(h, small), std::invalid_argument);
}

} // namespace
