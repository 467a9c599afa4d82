// SPDX-License-Identifier: BSD-3-Clause
// Tests of the point lookups behind gradient shading, iso-surfaces and shadow rays: the kD-tree
// descent (amrsp::SampleKdTreeAtPoint, mirrored by the shader's amrspSampleAtPoint) must find
// the same value and level as the reference's tree-free finest-grid lookup everywhere, including
// exactly on grid and level boundaries, so that gradients taken through the tree have no seams
// the reference does not have.
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"
#include "amrsp/Shading.h"
#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace
{
using namespace amrsp;
using namespace amrsp::test;

/// The reference's lookup (as RenderReference builds it).
struct ReferenceLookup
{
  explicit ReferenceLookup(const Hierarchy& h)
    : H(h)
    , Locator(h)
  {
  }
  double operator()(const glm::dvec3& p, glm::dvec3& cellSize) const
  {
    const Box root = H.RootCells();
    glm::i64vec3 cell;
    for (int a = 0; a < 3; ++a)
    {
      if (p[a] < root.Lo[a] || p[a] >= root.Hi[a])
      {
        return std::numeric_limits<double>::quiet_NaN();
      }
    }
    const int32_t g = Locator.Find(p, cell);
    if (g < 0)
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    cellSize = H.CellSize(H.Grids[g].Level);
    return CellValue(H, g, cell);
  }
  const Hierarchy& H;
  FinestCellLocator Locator;
};

/// Points exactly representable in float: random ones and ones on every grid face.
std::vector<glm::dvec3> TestPoints(const Hierarchy& h, std::mt19937_64& rng)
{
  const Box root = h.RootCells();
  const glm::dvec3 lo(root.Lo), hi(root.Hi);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto quantized = [&](int a)
  { return std::floor((lo[a] + u(rng) * (hi[a] - lo[a])) * 64.0) / 64.0; };
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 3000; ++i)
  {
    points.emplace_back(quantized(0), quantized(1), quantized(2));
  }
  for (const Grid& g : h.Grids)
  {
    const glm::dvec3 cs = h.CellSize(g.Level);
    for (int a = 0; a < 3; ++a)
    {
      for (double face : { g.Cells.Lo[a] * cs[a], g.Cells.Hi[a] * cs[a] })
      {
        for (int k = 0; k < 20; ++k)
        {
          glm::dvec3 p(quantized(0), quantized(1), quantized(2));
          p[a] = face;
          points.push_back(p);
        }
      }
    }
  }
  return points;
}

/// Whether p lies within 1e-4 cells of a face of the level whose cells measure cellSize.
bool OnFace(const glm::dvec3& p, const glm::dvec3& cellSize)
{
  const glm::dvec3 c = p / cellSize;
  const glm::dvec3 d = glm::abs(c - glm::round(c));
  return std::min(d.x, std::min(d.y, d.z)) < 1e-4;
}

/// The tree's and the reference's lookups agree, except where a point on a cell face rounds to
/// the other side in float (the tree's split planes are float, as in the shader; under 2%).
void ExpectLookupsAgree(const Hierarchy& h, int& compared, int& onFace)
{
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const ReferenceLookup reference(h);
  std::mt19937_64 rng(11);
  for (const glm::dvec3& p : TestPoints(h, rng))
  {
    glm::dvec3 refSize(0.0);
    glm::vec3 treeSize(0.0f);
    const double expected = reference(p, refSize);
    const double got = SampleKdTreeAtPoint(h, tree, glm::vec3(p), treeSize);
    ++compared;
    if (std::isnan(expected) && std::isnan(got))
    {
      continue;
    }
    if (!std::isnan(expected) && !std::isnan(got) && expected == got &&
      glm::vec3(refSize) == treeSize)
    {
      continue;
    }
    const bool face = (!std::isnan(expected) && OnFace(p, refSize)) ||
      (!std::isnan(got) && OnFace(p, glm::dvec3(treeSize)));
    ASSERT_TRUE(face) << "lookups differ at " << p.x << " " << p.y << " " << p.z << ": tree " << got
                      << ", reference " << expected;
    ++onFace;
  }
}

TEST(Shading, TreeLookupMatchesReferenceOnPaperExample)
{
  int compared = 0, onFace = 0;
  ExpectLookupsAgree(PaperExample(), compared, onFace);
  EXPECT_EQ(onFace, 0); // dyadic cell sizes: float planes are exact
}

TEST(Shading, TreeLookupMatchesReferenceOnRandomHierarchies)
{
  std::mt19937_64 rng(5);
  int compared = 0, onFace = 0;
  for (int i = 0; i < 20; ++i)
  {
    Hierarchy h = RandomHierarchy(rng);
    FillValues(h);
    ExpectLookupsAgree(h, compared, onFace);
  }
  EXPECT_GT(compared, 50000);
  EXPECT_LT(onFace * 50, compared);
}

/// Four abutting level-0 grids holding a linear field: the central differences through the tree
/// reproduce its gradient exactly at every point, also where the neighbours lie in other bricks.
TEST(Shading, GradientHasNoSeamsAtBrickBoundaries)
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1) };
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 8, 8, 16) });
  h.Grids.push_back(Grid{ 0, MakeBox(8, 0, 0, 16, 8, 16) });
  h.Grids.push_back(Grid{ 0, MakeBox(0, 8, 0, 16, 16, 8) });
  h.Grids.push_back(Grid{ 0, MakeBox(0, 8, 8, 16, 16, 16) });
  h.Spacing0 = glm::dvec3(0.5, 0.25, 1.0);
  const glm::dvec3 slope(0.03, -0.02, 0.01); // per level-0 index unit
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    h.Grids[g].SourceId = static_cast<int64_t>(g);
    const Box& b = h.Grids[g].Cells;
    std::vector<float> v;
    for (int64_t k = b.Lo.z; k < b.Hi.z; ++k)
      for (int64_t j = b.Lo.y; j < b.Hi.y; ++j)
        for (int64_t i = b.Lo.x; i < b.Hi.x; ++i)
          v.push_back(static_cast<float>(glm::dot(slope, glm::dvec3(i, j, k) + 0.5)));
    h.Values.push_back(v);
  }
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const PointLookup lookup = [&](const glm::dvec3& q, glm::dvec3& cellSize)
  {
    glm::vec3 size(1.0f);
    const double v = SampleKdTreeAtPoint(h, tree, glm::vec3(q), size);
    cellSize = glm::dvec3(size);
    return v;
  };
  TransferFunction tf = TransferFunction::Preset("grey", 0.0, 1.0, 1.0);
  Lighting light;
  const ShadingContext c = MakeShadingContext(light, tf, h.Origin, h.Spacing0, glm::dvec3(0.0),
    glm::dvec3(16.0), glm::dvec3(0.0, 0.0, 10.0), glm::dvec3(0.0));
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(1.0, 15.0); // one cell away from the root's faces
  for (int i = 0; i < 5000; ++i)
  {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    glm::dvec3 cellSize;
    const double v = lookup(p, cellSize);
    const glm::dvec3 g = Gradient(c, lookup, p, v, cellSize);
    for (int a = 0; a < 3; ++a)
    {
      ASSERT_NEAR(g[a], slope[a] / h.Spacing0[a], 1e-5) << "axis " << a;
    }
  }
}

/// Shadow rays: an opaque slab between the sample and the light blocks it; with the light on the
/// sample's side nothing does.
TEST(Shading, ShadowTransmittanceThroughTree)
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1) };
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 8, 8, 8) });
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 8, 8, 8, 16) });
  h.Grids[0].SourceId = 0;
  h.Grids[1].SourceId = 1;
  h.Values.push_back(GridValues(512, 0.0f)); // transparent
  GridValues slab(512, 0.0f);
  for (int j = 0; j < 64; ++j)
  {
    slab[static_cast<std::size_t>(4 * 64 + j)] = 1.0f; // z = 12: opaque
  }
  h.Values.push_back(slab);
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const PointLookup lookup = [&](const glm::dvec3& q, glm::dvec3& cellSize)
  {
    glm::vec3 size(1.0f);
    const double v = SampleKdTreeAtPoint(h, tree, glm::vec3(q), size);
    cellSize = glm::dvec3(size);
    return v;
  };
  TransferFunction tf;
  tf.Opacity = { { 0.0, 0.0 }, { 1.0, 1.0 } };
  tf.UnitDistance = 1.0;
  Lighting light;
  light.Headlight = false;
  light.Positional = true;
  light.Shadows = true;
  light.ShadowStep = 0.25;
  light.Position = glm::dvec3(4.0, 4.0, 40.0);
  ShadingContext c = MakeShadingContext(light, tf, h.Origin, h.Spacing0, glm::dvec3(0.0),
    glm::dvec3(8.0, 8.0, 16.0), glm::dvec3(0.0), glm::dvec3(0.0));
  EXPECT_LT(ShadowTransmittance(c, lookup, glm::dvec3(4.0, 4.0, 2.0)), ShadowMinTransmittance);
  EXPECT_DOUBLE_EQ(ShadowTransmittance(c, lookup, glm::dvec3(4.0, 4.0, 14.0)), 1.0);
  light.Position = glm::dvec3(4.0, 4.0, -40.0);
  c = MakeShadingContext(light, tf, h.Origin, h.Spacing0, glm::dvec3(0.0),
    glm::dvec3(8.0, 8.0, 16.0), glm::dvec3(0.0), glm::dvec3(0.0));
  EXPECT_DOUBLE_EQ(ShadowTransmittance(c, lookup, glm::dvec3(4.0, 4.0, 2.0)), 1.0);
}

} // namespace
