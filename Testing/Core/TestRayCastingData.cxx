// SPDX-License-Identifier: BSD-3-Clause
// The GPU ray casters' CPU build (amrsp/RayCastingData.h) without OpenGL: the level table, the
// refinement exponents the shader specialises on, the two data-node encodings, and the errors
// that stop a hierarchy from being rendered.
#include "TestHierarchies.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/RayCastingData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

using namespace amrsp;
using amrsp::test::MakeBox;

TEST(RayCastingData, PowerOfTwoExponents)
{
  EXPECT_EQ(PowerOfTwoExponents({ 1, 2, 4, 1024 }), (std::vector<int>{ 0, 1, 2, 10 }));
  EXPECT_TRUE(PowerOfTwoExponents({ 1, 3 }).empty());
  EXPECT_TRUE(PowerOfTwoExponents({ 4, 6, 8 }).empty());
  EXPECT_TRUE(PowerOfTwoExponents({ (1 << 30) + 1 }).empty());
  EXPECT_EQ(PowerOfTwoExponents({ 1 << 30 }), std::vector<int>{ 30 });
}

TEST(RayCastingData, UniformRefinementExponent)
{
  // three levels of ratio 4: level l has 2 (2 - l) on every axis
  EXPECT_EQ(UniformRefinementExponent({ 4, 4, 4, 2, 2, 2, 0, 0, 0 }), 2);
  EXPECT_EQ(UniformRefinementExponent({ 0, 0, 0 }), 1); // one level
  EXPECT_EQ(UniformRefinementExponent({}), 0);
  EXPECT_EQ(UniformRefinementExponent({ 2, 2, 1, 1, 1, 0, 0, 0, 0 }), 0); // anisotropic
  EXPECT_EQ(UniformRefinementExponent({ 3, 3, 3, 1, 1, 1, 0, 0, 0 }), 0); // ratios 4 then 2
  // 31 levels of ratio 2 would need 2^30 on level 0: over the limit
  std::vector<int> deep;
  for (int l = 0; l < 32; ++l)
  {
    deep.insert(deep.end(), 3, 31 - l);
  }
  EXPECT_EQ(UniformRefinementExponent(deep), 0);
}

TEST(RayCastingData, LevelTableOfThePaperExample)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const KdTree tree = BuildKdTree(h);
  const LevelTable t = ComputeLevelTable(h, tree);
  EXPECT_EQ(t.LevelToFinest, (std::vector<int>{ 4, 4, 4, 2, 2, 2, 1, 1, 1 }));
  EXPECT_EQ(t.LevelToFinestLog2, (std::vector<int>{ 2, 2, 2, 1, 1, 1, 0, 0, 0 }));
  EXPECT_EQ(t.UniformRefinementLog2, 1);
  EXPECT_TRUE(t.RootFitsShaderIntegers);
  ASSERT_EQ(t.LevelMinEdge.size(), 3u);
  EXPECT_DOUBLE_EQ(t.LevelMinEdge[0], 0.25); // spacing (0.5, 0.25, 1)
  EXPECT_DOUBLE_EQ(t.LevelMinEdge[2], 0.0625);
  // the root box: the level-0 grid, 16 x 16 x 4 cells from the origin (-3, 1, 2)
  EXPECT_EQ(t.RootLoFinest, glm::ivec3(0));
  EXPECT_EQ(t.RootHiFinest, glm::ivec3(64, 64, 16));
  const double expected[6] = { -3.0, 5.0, 1.0, 5.0, 2.0, 6.0 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_DOUBLE_EQ(t.Bounds[i], expected[i]) << "bound " << i;
  }
}

TEST(RayCastingData, RootBoxOverTwoToTheThirtyFinestCellsIsAnError)
{
  Hierarchy h;
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 4, 4, 4) });
  for (int l = 1; l <= 29; ++l)
  {
    h.RefinementRatio.push_back(glm::ivec3(2));
  }
  h.Grids.push_back(Grid{ 29, MakeBox(0, 0, 0, 2, 2, 2) });
  amrsp::test::FillValues(h);
  // 4 level-0 cells are 2^31 cells of level 29
  EXPECT_FALSE(ComputeLevelTable(h, BuildKdTree(h)).RootFitsShaderIntegers);
  try
  {
    PrepareRayCasting(h, 0);
    FAIL() << "no error";
  }
  catch (const std::runtime_error& e)
  {
    EXPECT_NE(std::string(e.what()).find("2^30"), std::string::npos) << e.what();
  }
  // 2^30 exactly still fits
  h.Grids[0].Cells = MakeBox(0, 0, 0, 2, 2, 2);
  amrsp::test::FillValues(h);
  EXPECT_NO_THROW(PrepareRayCasting(h, 0));
}

TEST(RayCastingData, NoFiniteValueIsAnError)
{
  Hierarchy h = amrsp::test::PaperExample();
  for (GridValues& v : h.Values)
  {
    std::fill(v.begin(), v.end(), std::numeric_limits<float>::quiet_NaN());
  }
  h.Values[1][0] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(PrepareRayCasting(h, 0), std::runtime_error);
  h.Values[2][3] = 7.5f; // one finite value is enough
  const RayCastingData d = PrepareRayCasting(h, 0);
  EXPECT_EQ(d.ScalarRange[0], 7.5);
  EXPECT_EQ(d.ScalarRange[1], 7.5);
}

TEST(RayCastingData, BothEncodingsAndTheFigures)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const RayCastingData d = PrepareRayCasting(h, 0);
  EXPECT_TRUE(d.PackingError.empty());
  EXPECT_EQ(d.Grids, 6);
  EXPECT_GT(d.DataNodes, 0);
  EXPECT_GE(d.KdNodes, d.DataNodes);
  EXPECT_EQ(d.NodeRanges.size(), static_cast<std::size_t>(d.DataNodes) + 1); // texel 0 unused
  EXPECT_EQ(d.PackedDataNodeTexels.Dims, d.BrickLocalDataNodeTexels.Dims);
  EXPECT_NE(d.PackedDataNodeTexels.Texels, d.BrickLocalDataNodeTexels.Texels); // offsets differ
  ASSERT_EQ(d.Atlas.Pages.size(), 1u); // one page without a page budget
  EXPECT_GT(d.Atlas.Pages[0].Dims.x, 0);
  EXPECT_GT(d.PackedBytes, 0);
  EXPECT_GT(d.BindlessBytes, 0);
  // the tree textures are in every storage's figure: an atlas of float texels, or the bricks and
  // one 8-byte handle texel each (padded to the handles texture's rows)
  const AtlasLayout& atlas = d.Atlas.Pages[0];
  EXPECT_EQ(d.PackedBytes,
    d.TreeBytes + static_cast<long long>(atlas.Dims.x) * atlas.Dims.y * atlas.Dims.z * 4);
  EXPECT_EQ(
    d.BindlessBytes, d.TreeBytes + d.BrickBytes + static_cast<long long>(HandleTextureBytes(6)));
  double range[2];
  ASSERT_TRUE(FiniteValueRange(h, range));
  EXPECT_EQ(d.ScalarRange[0], range[0]);
  EXPECT_EQ(d.ScalarRange[1], range[1]);
  EXPECT_EQ(d.Data.Values.size(), 6u); // the bricks wait for the upload

  RayCastingData freed = d;
  freed.FreeUploadData();
  EXPECT_TRUE(freed.Data.Values.empty());
  EXPECT_TRUE(freed.TreeTexels.Texels.empty());
  EXPECT_EQ(freed.KdNodes, d.KdNodes); // the figures stay
  EXPECT_EQ(freed.AtlasDims, d.Atlas.Pages[0].Dims);
  EXPECT_EQ(freed.PageDims, d.PageDims);
}

TEST(RayCastingData, DeferredNodeRangesAreTheSameAfterTheUploadDataIsFreed)
{
  Hierarchy h = amrsp::test::PaperExample();
  for (std::size_t g = 0; g < h.Values.size(); ++g)
  {
    for (std::size_t i = 0; i < h.Values[g].size(); ++i)
    {
      h.Values[g][i] = static_cast<float>(g * 100 + (i * 7) % 13); // ranges differ per node
    }
  }
  const RayCastingData now = PrepareRayCasting(h, 0);
  RayCastingData later = PrepareRayCasting(h, 0, 0, nullptr, true);
  EXPECT_TRUE(later.NodeRanges.empty());
  EXPECT_TRUE(later.PendingNodeRanges.valid());
  later.FreeUploadData(); // as the mapper does before it needs them: the worker has its own copies
  later.WaitForNodeRanges();
  EXPECT_FALSE(later.PendingNodeRanges.valid());
  ASSERT_EQ(later.NodeRanges.size(), now.NodeRanges.size());
  EXPECT_EQ(later.NodeRanges, now.NodeRanges);
  later.WaitForNodeRanges(); // nothing pending: the ranges stay
  EXPECT_EQ(later.NodeRanges, now.NodeRanges);
}

TEST(RayCastingData, UnpackableBricksLeaveTheBindlessEncoding)
{
  const Hierarchy h = amrsp::test::PaperExample();
  // a 4-texel atlas cannot hold the 16 x 16 x 4 root brick
  const RayCastingData d = PrepareRayCasting(h, 4);
  EXPECT_FALSE(d.PackingError.empty());
  EXPECT_TRUE(d.Atlas.Pages.empty());
  EXPECT_EQ(d.AtlasDims, glm::ivec3(0));
  EXPECT_TRUE(d.PackedDataNodeTexels.Texels.empty());
  EXPECT_EQ(d.PackedBytes, 0);
  EXPECT_FALSE(d.BrickLocalDataNodeTexels.Texels.empty());
}

TEST(RayCastingData, APageBudgetSpreadsTheBricksOverPagesThatEncodeTheirPage)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const RayCastingData one = PrepareRayCasting(h, 0);
  ASSERT_EQ(one.Atlas.Pages.size(), 1u);
  // a budget below the one atlas: several pages, each within it
  const int64_t budget = one.Atlas.Pages[0].TotalTexels * 2 / 3;
  const RayCastingData paged = PrepareRayCasting(h, 0, budget);
  ASSERT_TRUE(paged.PackingError.empty()) << paged.PackingError;
  ASSERT_GE(paged.Atlas.Pages.size(), 2u);
  ASSERT_EQ(paged.PageDims.size(), paged.Atlas.Pages.size());
  std::size_t grids = 0;
  for (std::size_t p = 0; p < paged.Atlas.Pages.size(); ++p)
  {
    EXPECT_LE(paged.Atlas.Pages[p].TotalTexels, budget) << "page " << p;
    grids += paged.Atlas.GridsOfPage[p].size();
    const Hierarchy page = PageHierarchy(h, paged.Atlas, static_cast<int>(p));
    ASSERT_EQ(page.Grids.size(), paged.Atlas.GridsOfPage[p].size());
    for (std::size_t i = 0; i < page.Grids.size(); ++i)
    {
      const std::size_t g = paged.Atlas.GridsOfPage[p][i];
      EXPECT_EQ(paged.Atlas.PageOfGrid[g], static_cast<int>(p));
      EXPECT_EQ(paged.Atlas.Origins[g], paged.Atlas.Pages[p].Origins[i]);
      // the page's hierarchy shares the values
      EXPECT_EQ(page.Values[i].data(), h.Values[g].data());
    }
  }
  EXPECT_EQ(grids, h.Grids.size());
  // every data node names its brick's page and its offset in that page; nothing else changes
  using namespace amrsp::layout;
  ASSERT_EQ(paged.PackedDataNodeTexels.Texels.size(), one.PackedDataNodeTexels.Texels.size());
  bool pageBeyondZero = false;
  for (std::size_t i = 1; i < paged.PackedDataNodeTexels.Texels.size(); ++i)
  {
    const uvec2 a = paged.PackedDataNodeTexels.Texels[i];
    const uvec2 b = one.PackedDataNodeTexels.Texels[i];
    if (a == uvec2(0u) && b == uvec2(0u))
    {
      continue; // padding texels
    }
    const uint brick = amrspDataBrick(a);
    EXPECT_EQ(brick, amrspDataBrick(b));
    EXPECT_EQ(amrspDataLevel(a), amrspDataLevel(b));
    EXPECT_EQ(amrspDataPage(a), static_cast<uint>(paged.Atlas.PageOfGrid[brick]));
    EXPECT_EQ(amrspDataPage(b), 0u);
    pageBeyondZero = pageBeyondZero || amrspDataPage(a) > 0u;
  }
  EXPECT_TRUE(pageBeyondZero);
}

TEST(RayCastingData, TooSmallAPageBudgetIsAPackingErrorNamingThePages)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const RayCastingData d = PrepareRayCasting(h, 0, 64);
  EXPECT_NE(d.PackingError.find("atlas pages"), std::string::npos) << d.PackingError;
  EXPECT_TRUE(d.Atlas.Pages.empty());
}

// A new time step of the same structure: RefreshValues keeps the tree, the encodings and the
// atlas layout and gives the ranges a full build of that step computes.
TEST(RayCastingData, RefreshedValuesEqualAFullBuildOfTheNewStep)
{
  Hierarchy first = amrsp::test::PaperExample();
  Hierarchy second = first;
  for (std::size_t g = 0; g < first.Values.size(); ++g)
  {
    for (std::size_t i = 0; i < first.Values[g].size(); ++i)
    {
      first.Values[g][i] = static_cast<float>(g * 100 + (i * 7) % 13);
      second.Values[g][i] = static_cast<float>(1000 - g * 50 - (i * 5) % 11);
    }
  }
  for (bool deferred : { false, true })
  {
    RayCastingData refreshed = PrepareRayCasting(first, 0, 0, nullptr, deferred);
    refreshed.WaitForNodeRanges();
    const auto tree = refreshed.TreeTexels.Texels;
    refreshed.FreeUploadData(); // as the mapper does after the first step's upload
    ASSERT_TRUE(refreshed.NodeBlocks);
    RefreshValues(refreshed, second, deferred);
    refreshed.WaitForNodeRanges();
    const RayCastingData full = PrepareRayCasting(second, 0);
    EXPECT_EQ(tree, full.TreeTexels.Texels); // what the kept textures hold
    EXPECT_EQ(refreshed.NodeRanges, full.NodeRanges);
    EXPECT_EQ(refreshed.ScalarRange[0], full.ScalarRange[0]);
    EXPECT_EQ(refreshed.ScalarRange[1], full.ScalarRange[1]);
    EXPECT_EQ(refreshed.Atlas.Origins, full.Atlas.Origins);
    EXPECT_EQ(refreshed.Atlas.PageOfGrid, full.Atlas.PageOfGrid);
    ASSERT_TRUE(refreshed.Data.HasValues());
    EXPECT_EQ(refreshed.Data.Values[1], second.Values[1]);
    // the check sees a range that is not the new step's
    EXPECT_NE(PrepareRayCasting(first, 0).NodeRanges, full.NodeRanges);
  }
}

TEST(RayCastingData, RefreshValuesRefusesAnotherStructure)
{
  const Hierarchy h = amrsp::test::PaperExample();
  RayCastingData d = PrepareRayCasting(h, 0);
  Hierarchy moved = h;
  moved.Grids.back().Cells.Lo.x += 1;
  moved.Grids.back().Cells.Hi.x += 1;
  EXPECT_FALSE(SameStructure(h, moved));
  EXPECT_THROW(RefreshValues(d, moved), std::logic_error);
  Hierarchy renamed = h;
  renamed.ArrayName = "other";
  EXPECT_FALSE(SameStructure(h, renamed));
  Hierarchy other = h;
  other.Values[0][0] += 1.0f; // values are not structure
  EXPECT_TRUE(SameStructure(h, other));
  Hierarchy nan = h;
  for (GridValues& v : nan.Values)
  {
    std::fill(v.begin(), v.end(), std::numeric_limits<float>::quiet_NaN());
  }
  EXPECT_THROW(RefreshValues(d, nan), std::runtime_error);
}
