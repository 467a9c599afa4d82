// SPDX-License-Identifier: BSD-3-Clause
// Smooth reconstruction of cell-centred data (RenderSettings::SmoothCellData): exact for linear
// fields inside a level, much smaller jumps across grid and level boundaries than nearest-cell
// sampling, the kD-tree integrator agreeing with the tree-free reference, and the packed-atlas
// path sampling exactly what the grids hold.
#include "amrsp/BrickAtlas.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/Render.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

/// A field sampled at every level's cell centres (level-0 index units).
template <typename F>
void Fill(Hierarchy& h, F f)
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
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] =
            static_cast<float>(f((glm::dvec3(g.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * cs));
        }
    h.Values.push_back(std::move(v));
  }
}

double Linear(const glm::dvec3& p)
{
  return 0.1 * p.x - 0.05 * p.y + 0.02 * p.z;
}

/// Largest jump of the sampled field across the boundaries between consecutive segments of
/// different grids, over random rays (the field sampled just before and just after the plane).
double LargestJump(const Hierarchy& h, bool smooth, int& crossings)
{
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  std::mt19937_64 rng(17);
  double worst = 0.0;
  crossings = 0;
  std::vector<RaySegment> segs;
  for (int r = 0; r < 400; ++r)
  {
    glm::dvec3 o, d;
    RandomRay(rng, h, o, d);
    const glm::vec3 oi = glm::vec3((o - h.Origin) / h.Spacing0), di = glm::vec3(d / h.Spacing0);
    segs.clear();
    TraverseKdTree(enc, oi, di, 0.0f, 1e30f, LevelOfDetail(), segs);
    for (std::size_t i = 1; i < segs.size(); ++i)
    {
      const RaySegment& a = segs[i - 1];
      const RaySegment& b = segs[i];
      if (a.Data == 0 || b.Data == 0 ||
        layout::amrspDataBrick(enc.DataNodes.Texels[a.Data]) ==
          layout::amrspDataBrick(enc.DataNodes.Texels[b.Data]))
      {
        continue;
      }
      const float eps = 1e-3f * (a.T1 - a.T0 + b.T1 - b.T0);
      const float va = SampleKdTreePoint(h, enc, oi + (a.T1 - eps) * di, smooth);
      const float vb = SampleKdTreePoint(h, enc, oi + (b.T0 + eps) * di, smooth);
      if (std::isnan(va) || std::isnan(vb))
      {
        continue;
      }
      worst = std::max(worst, static_cast<double>(std::abs(va - vb)));
      ++crossings;
    }
  }
  return worst;
}

TEST(SmoothCells, LinearFieldIsExactInsideTheDomain)
{
  Hierarchy h;
  h.Grids = { Grid{ 0, MakeBox(0, 0, 0, 8, 8, 8) }, Grid{ 0, MakeBox(8, 0, 0, 16, 8, 8) } };
  Fill(h, Linear);
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<float> u(0.5f, 7.5f), ux(0.5f, 15.5f);
  double worstSmooth = 0.0, worstNearest = 0.0;
  for (int k = 0; k < 2000; ++k)
  {
    const glm::vec3 p(ux(rng), u(rng), u(rng)); // at least half a cell inside
    const double exact = Linear(glm::dvec3(p));
    worstSmooth = std::max(worstSmooth, std::abs(SampleKdTreePoint(h, enc, p, true) - exact));
    worstNearest = std::max(worstNearest, std::abs(SampleKdTreePoint(h, enc, p, false) - exact));
  }
  EXPECT_LT(worstSmooth, 1e-5);  // across the two grids too
  EXPECT_GT(worstNearest, 0.04); // the test can fail: nearest is off by up to half a cell
}

TEST(SmoothCells, JumpsAcrossGridsAndLevelsShrink)
{
  for (int variant = 0; variant < 2; ++variant)
  {
    Hierarchy h = PaperExample();
    if (variant == 0)
    {
      Fill(h, Linear);
    }
    else
    {
      Fill(h,
        [](const glm::dvec3& p) { return std::sin(0.4 * p.x) * std::cos(0.3 * p.y) + 0.05 * p.z; });
    }
    int nearestCrossings = 0, smoothCrossings = 0;
    const double nearest = LargestJump(h, false, nearestCrossings);
    const double smooth = LargestJump(h, true, smoothCrossings);
    std::cout << "variant " << variant << ": largest jump nearest " << nearest << ", smooth "
              << smooth << " over " << nearestCrossings << " crossings\n";
    EXPECT_GT(nearestCrossings, 100);
    EXPECT_EQ(smoothCrossings, nearestCrossings);
    // nearest jumps by the field's change over half a coarse and half a fine cell; the dual-cell
    // reconstruction leaves the change over a fraction of a fine cell
    EXPECT_LT(smooth, 0.5 * nearest)
      << "variant " << variant << ": smooth " << smooth << ", nearest " << nearest;
  }
}

TEST(SmoothCells, KdTreeIntegratorMatchesReferenceAndAtlasPath)
{
  Hierarchy h = PaperExample();
  const KdTree tree = BuildKdTree(h);
  const BrickAtlas atlas = BuildBrickAtlas(h, Packer::Best, glm::ivec3(2048, 2048, 1024));
  const EncodedKdTree plain = EncodeKdTree(h, tree);
  const EncodedKdTree packed = EncodeKdTree(h, tree, &atlas.Layout.Origins);
  RenderSettings s = SmallView(h);
  s.SampleDistanceFactor = 0.25;
  s.ReferenceSampleFactor = 0.25;
  const Image nearest = RenderKdTree(h, plain, s);
  s.SmoothCellData = true;
  const Image smooth = RenderKdTree(h, plain, s);
  const Image reference = RenderReference(h, s);
  std::cout << "smooth vs smooth reference RMSE " << Rmse(smooth, reference)
            << ", smooth vs nearest " << Rmse(smooth, nearest) << "\n";
  EXPECT_LT(Rmse(smooth, reference), 1.0);
  EXPECT_EQ(Rmse(smooth, RenderKdTree(h, packed, s, &atlas)), 0.0);
  EXPECT_GT(Rmse(smooth, nearest), 0.3); // the option changes the image
  s.SmoothCellData = false;
  EXPECT_GT(Rmse(reference, RenderReference(h, s)), 0.3);
}

} // namespace
