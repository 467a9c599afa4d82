// SPDX-License-Identifier: BSD-3-Clause
// amrsp::ListMultiPassNodes, amrsp::OrderFrontToBack and amrsp::PackHierarchy: the multi-pass
// baseline's CPU side (vtkMultiPassAMRVolumeMapper draws what these list, in this order).
#include "amrsp/MultiPassNodes.h"
#include "amrsp/PackedHierarchy.h"

#include "TestHierarchies.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

using namespace amrsp;

namespace
{
PackedHierarchy Packed(const Hierarchy& h)
{
  PackedHierarchy packed;
  bool refreshed = false;
  std::string error;
  EXPECT_TRUE(PackHierarchy(h, 0, 0, false, packed, refreshed, error)) << error;
  return packed;
}

/// The leaf of `tree` that contains `p` (finest cells).
int32_t LeafAt(const KdTree& tree, const glm::dvec3& p)
{
  int32_t n = 0;
  while (!tree.Nodes[static_cast<std::size_t>(n)].IsLeaf())
  {
    const KdNode& node = tree.Nodes[static_cast<std::size_t>(n)];
    const double plane = static_cast<double>(
      tree.Nodes[static_cast<std::size_t>(node.FirstChild)].Region.Hi[node.Axis]);
    n = p[node.Axis] < plane ? node.FirstChild : node.FirstChild + 1;
  }
  return n;
}

/// Rays from `eye` (model units) through points of the root box that meet a draw after one that
/// comes later in `order`: 0 when every ray meets its segments front to back.
int OutOfOrderRays(const Hierarchy& h, const KdTree& tree, const MultiPassNodes& nodes,
  const std::vector<int32_t>& order, const glm::dvec3& eye)
{
  std::vector<int> position(nodes.Draws.size(), -1);
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    position[static_cast<std::size_t>(order[k])] = static_cast<int>(k);
  }
  const glm::dvec3 finest(h.CumulativeRatio(tree.FinestLevel));
  const Box root = tree.Root().Region;
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int out = 0;
  for (int r = 0; r < 400; ++r)
  {
    const glm::dvec3 target = glm::dvec3(root.Lo) +
      glm::dvec3(unit(random), unit(random), unit(random)) * glm::dvec3(root.Extent());
    const glm::dvec3 from = (eye - h.Origin) / h.Spacing0 * finest;
    int last = -1;
    bool ordered = true;
    for (int s = 0; s <= 2000; ++s)
    {
      const glm::dvec3 p = from + (target - from) * (2.0 * s / 2000.0);
      if (glm::any(glm::lessThan(p, glm::dvec3(root.Lo))) ||
        glm::any(glm::greaterThanEqual(p, glm::dvec3(root.Hi))))
      {
        continue;
      }
      const int32_t draw = nodes.DrawOfNode[static_cast<std::size_t>(LeafAt(tree, p))];
      if (draw >= 0)
      {
        const int k = position[static_cast<std::size_t>(draw)];
        ordered = ordered && k >= last;
        last = std::max(last, k);
      }
    }
    out += ordered ? 0 : 1;
  }
  return out;
}
} // namespace

TEST(MultiPassNodes, OneDrawPerLeafWithDataInsideItsGrid)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const PackedHierarchy packed = Packed(h);
  const MultiPassNodes nodes = ListMultiPassNodes(packed.Structure, packed.Tree, packed.Atlas);
  long long leaves = 0, data = 0;
  for (std::size_t n = 0; n < packed.Tree.Nodes.size(); ++n)
  {
    const KdNode& node = packed.Tree.Nodes[n];
    data += node.HasData() ? 1 : 0;
    leaves += node.IsLeaf() && node.HasData() ? 1 : 0;
    EXPECT_EQ(nodes.DrawOfNode[n] >= 0, node.IsLeaf() && node.HasData()) << "node " << n;
    if (nodes.DrawOfNode[n] < 0)
    {
      continue;
    }
    const NodeDraw& d = nodes.Draws[static_cast<std::size_t>(nodes.DrawOfNode[n])];
    const Grid& grid = h.Grids[static_cast<std::size_t>(node.Grid)];
    const glm::ivec3 origin = packed.Atlas.Origins[static_cast<std::size_t>(node.Grid)];
    EXPECT_EQ(d.Level, grid.Level);
    for (int a = 0; a < 3; ++a)
    {
      EXPECT_GE(d.FirstCell[a], grid.Cells.Lo[a]);
      EXPECT_LT(d.LastCell[a], grid.Cells.Hi[a]);
      EXPECT_LE(d.FirstCell[a], d.LastCell[a]);
      EXPECT_EQ(d.AtlasOffset[a], origin[a] + d.FirstCell[a] - grid.Cells.Lo[a]);
      EXPECT_LT(d.Lo[a], d.Hi[a]);
    }
  }
  EXPECT_EQ(static_cast<long long>(nodes.Draws.size()), leaves);
  EXPECT_EQ(nodes.DataNodes, data);
}

TEST(MultiPassNodes, EveryRayMeetsItsSegmentsFrontToBack)
{
  const Hierarchy h = amrsp::test::PaperExample();
  const PackedHierarchy packed = Packed(h);
  const MultiPassNodes nodes = ListMultiPassNodes(packed.Structure, packed.Tree, packed.Atlas);
  const glm::dvec3 centre = 0.5 *
    (glm::dvec3(packed.Bounds[0], packed.Bounds[2], packed.Bounds[4]) +
      glm::dvec3(packed.Bounds[1], packed.Bounds[3], packed.Bounds[5]));
  const double size = packed.Bounds[1] - packed.Bounds[0];
  for (const glm::dvec3 offset : { glm::dvec3(2.0, 0.7, 1.3), glm::dvec3(-1.5, -2.0, 0.4),
         glm::dvec3(0.3, 1.8, -2.2), glm::dvec3(0.1, -0.2, 0.05) })
  {
    const glm::dvec3 eye = centre + offset * size;
    const std::vector<int32_t> order =
      OrderFrontToBack(packed.Structure, packed.Tree, nodes, eye, centre - eye, false);
    std::vector<int32_t> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted.size(), nodes.Draws.size());
    for (std::size_t k = 0; k < sorted.size(); ++k)
    {
      EXPECT_EQ(sorted[k], static_cast<int32_t>(k)); // every draw once
    }
    EXPECT_EQ(OutOfOrderRays(packed.Structure, packed.Tree, nodes, order, eye), 0);
    // the check rejects the order of the far side first (the eye outside the box)
    if (glm::length(offset) > 1.0)
    {
      const std::vector<int32_t> reversed(order.rbegin(), order.rend());
      EXPECT_GT(OutOfOrderRays(packed.Structure, packed.Tree, nodes, reversed, eye), 0);
    }
  }
}

TEST(PackedHierarchy, ANewStepOfTheSameStructureKeepsTheTreeAndLayout)
{
  const Hierarchy h = amrsp::test::PaperExample();
  PackedHierarchy packed = Packed(h);
  const std::size_t nodes = packed.Tree.Nodes.size();
  Hierarchy next = h;
  for (GridValues& values : next.Values)
  {
    for (float& v : values)
    {
      v = 2.0f * v + 1.0f;
    }
  }
  bool refreshed = false;
  std::string error;
  ASSERT_TRUE(PackHierarchy(next, 0, 0, true, packed, refreshed, error)) << error;
  EXPECT_TRUE(refreshed);
  EXPECT_EQ(packed.Tree.Nodes.size(), nodes);
  EXPECT_EQ(packed.Structure.Values, next.Values);
  Hierarchy other = h;
  other.Grids.pop_back();
  other.Values.pop_back();
  ASSERT_TRUE(PackHierarchy(other, 0, 0, true, packed, refreshed, error)) << error;
  EXPECT_FALSE(refreshed); // another structure: built again
}
