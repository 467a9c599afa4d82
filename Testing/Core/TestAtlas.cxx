// SPDX-License-Identifier: BSD-3-Clause
// The packed atlas and vertex-centred data: texel contents, the packing path's addressing,
// continuity across grid and level interfaces.
#include "amrsp/BrickAtlas.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/Render.h"
#include "amrsp/Resample.h"
#include "amrsp/VertexData.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <limits>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

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

TEST(Atlas, SlabsConcatenateToTheWholeAtlas)
{
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 6; ++trial)
  {
    Hierarchy h = trial == 0 ? PaperExample() : RandomHierarchy(rng);
    if (trial > 0)
    {
      FillValues(h);
    }
    h.VertexCentred = trial == 1;
    if (h.VertexCentred)
    {
      // one value per vertex: extent + 1 per axis
      for (std::size_t g = 0; g < h.Grids.size(); ++g)
      {
        const glm::i64vec3 e = h.Grids[g].Cells.Extent() + glm::i64vec3(1);
        h.Values[g] = GridValues(static_cast<std::size_t>(e.x * e.y * e.z));
        for (std::size_t i = 0; i < h.Values[g].size(); ++i)
        {
          h.Values[g][i] = static_cast<float>(g) + 0.001f * static_cast<float>(i);
        }
      }
    }
    const BrickAtlas whole = BuildBrickAtlas(h, Packer::Best, glm::ivec3(2048, 2048, 1024));
    const glm::ivec3 d = whole.Layout.Dims;
    const std::size_t layer = static_cast<std::size_t>(d.x) * d.y;
    for (int slab : { 1, 3, d.z })
    {
      // NaN-filled first: every texel of the slab must be written (bricks or 0)
      std::vector<float> joined(whole.Texels.size(), std::numeric_limits<float>::quiet_NaN());
      for (int z0 = 0; z0 < d.z; z0 += slab)
      {
        const int z1 = std::min(d.z, z0 + slab);
        FillAtlasSlab(
          h, whole.Layout, z0, z1, joined.data() + static_cast<std::size_t>(z0) * layer);
      }
      ASSERT_EQ(joined, whole.Texels) << "trial " << trial << ", slabs of " << slab;
    }
    std::vector<float> out(layer);
    EXPECT_THROW(FillAtlasSlab(h, whole.Layout, d.z, d.z + 1, out.data()), std::invalid_argument);
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

/// Largest jump of the sampled field across the boundaries between consecutive segments
/// (different kD leaves: other grids or other levels), over many random rays.
double LargestJumpAcrossNodes(const Hierarchy& h, std::mt19937_64& rng, int& crossings)
{
  using namespace layout;
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  double worst = 0.0;
  crossings = 0;
  std::vector<RaySegment> segs;
  for (int r = 0; r < 400; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::dvec3 oi = (o - h.Origin) / h.Spacing0, di = d / h.Spacing0;
    segs.clear();
    TraverseKdTree(enc, glm::vec3(oi), glm::vec3(di), 0.0f, 1e30f, LevelOfDetail(), segs);
    for (std::size_t i = 1; i < segs.size(); ++i)
    {
      const RaySegment& a = segs[i - 1];
      const RaySegment& b = segs[i];
      if (a.Data == 0 || b.Data == 0)
      {
        continue;
      }
      const int32_t ga = static_cast<int32_t>(amrspDataBrick(enc.DataNodes.Texels[a.Data]));
      const int32_t gb = static_cast<int32_t>(amrspDataBrick(enc.DataNodes.Texels[b.Data]));
      if (ga == gb)
      {
        continue; // a split inside one grid: trivially continuous
      }
      const glm::dvec3 p = oi + static_cast<double>(a.T1) * di;
      const double va = InterpolateVertices(
        h, ga, p * glm::dvec3(h.CumulativeRatio(a.Level)) - glm::dvec3(h.Grids[ga].Cells.Lo));
      const double vb = InterpolateVertices(
        h, gb, p * glm::dvec3(h.CumulativeRatio(b.Level)) - glm::dvec3(h.Grids[gb].Cells.Lo));
      worst = std::max(worst, std::abs(va - vb));
      ++crossings;
    }
  }
  return worst;
}

TEST(VertexData, ContinuousAcrossGridAndLevelInterfaces)
{
  std::mt19937_64 rng(8);
  Hierarchy h = PaperExample();
  ConvertCellsToVertices(h);
  int crossings = 0;
  const double fixedJump = LargestJumpAcrossNodes(h, rng, crossings);
  EXPECT_GT(crossings, 100);
  EXPECT_LT(fixedJump, 1e-4) << "over " << crossings << " interface crossings";

  // a field whose levels disagree jumps at coarse-fine interfaces unless fixed: the test can fail
  Hierarchy unfixed = PaperExample();
  unfixed.VertexCentred = true;
  for (std::size_t g = 0; g < unfixed.Grids.size(); ++g)
  {
    const glm::i64vec3 e = unfixed.Grids[g].Cells.Extent() + glm::i64vec3(1);
    GridValues v(static_cast<std::size_t>(e.x * e.y * e.z));
    const glm::dvec3 cs = unfixed.CellSize(unfixed.Grids[g].Level);
    for (int64_t k = 0; k < e.z; ++k)
      for (int64_t j = 0; j < e.y; ++j)
        for (int64_t i = 0; i < e.x; ++i)
        {
          // a field sampled exactly at each level's vertices, plus a level-dependent offset as
          // real simulations have (different resolution, different values)
          const glm::dvec3 p = glm::dvec3(unfixed.Grids[g].Cells.Lo + glm::i64vec3(i, j, k)) * cs;
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] =
            static_cast<float>(std::sin(0.7 * p.x) + 0.1 * unfixed.Grids[g].Level);
        }
    unfixed.Values[g] = std::move(v);
  }
  Hierarchy fixed = unfixed;
  MakeVertexDataContinuous(fixed);
  std::mt19937_64 rng2(9), rng3(9);
  int c1 = 0, c2 = 0;
  EXPECT_GT(LargestJumpAcrossNodes(unfixed, rng2, c1), 0.05);
  EXPECT_LT(LargestJumpAcrossNodes(fixed, rng3, c2), 1e-4);
}

TEST(VertexData, AtlasPathMatchesDirectTrilinearSampling)
{
  Hierarchy h = PaperExample();
  ConvertCellsToVertices(h);
  const BrickAtlas atlas = BuildBrickAtlas(h, Packer::Best, glm::ivec3(2048, 2048, 1024));
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const glm::i64vec3 e = h.Grids[g].Cells.Extent() + glm::i64vec3(1);
    EXPECT_EQ(
      atlas.At(atlas.Layout.Origins[g] + glm::ivec3(e) - 1), h.Values[g][h.Values[g].size() - 1]);
  }
  const KdTree tree = BuildKdTree(h);
  const EncodedKdTree plain = EncodeKdTree(h, tree);
  const EncodedKdTree packed = EncodeKdTree(h, tree, &atlas.Layout.Origins);
  const RenderSettings s = SmallView(h);
  const Image direct = RenderKdTree(h, plain, s);
  EXPECT_LT(Rmse(direct, RenderKdTree(h, packed, s, &atlas)), 0.05);
  EXPECT_LT(Rmse(direct, RenderReference(h, s)), 2.0);
}

TEST(Resample, VoxelsHoldTheFinestCellAndLimitsAreErrors)
{
  const Hierarchy h = PaperExample();
  const UniformGrid u = ResampleToLevel(h, 2, 1 << 24, 2048);
  EXPECT_EQ(u.Dims, glm::ivec3(64, 64, 16));
  const FinestCellLocator locator(h);
  std::mt19937_64 rng(4);
  for (int probe = 0; probe < 2000; ++probe)
  {
    const glm::ivec3 v(rng() % 64, rng() % 64, rng() % 16);
    const glm::dvec3 p = (glm::dvec3(v) + 0.5) * h.CellSize(2);
    glm::i64vec3 c;
    const int32_t g = locator.Find(p, c);
    const float value = u.Values[(static_cast<std::size_t>(v.z) * 64 + v.y) * 64 + v.x];
    ASSERT_EQ(value, CellValue(h, g, c));
  }
  EXPECT_THROW(ResampleToLevel(h, 2, 1000, 2048), ResampleError);
  EXPECT_THROW(ResampleToLevel(h, 2, 1 << 24, 32), ResampleError);
}

} // namespace
