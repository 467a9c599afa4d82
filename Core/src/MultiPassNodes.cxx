// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/MultiPassNodes.h"

#include "amrsp/IntegerMath.h"

namespace amrsp
{

MultiPassNodes ListMultiPassNodes(const Hierarchy& h, const KdTree& tree, const AtlasPages& atlas)
{
  MultiPassNodes out;
  const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
  std::vector<glm::vec3> levelCellSize;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    levelCellSize.push_back(glm::vec3(h.CellSize(l)));
  }

  // Walk the tree from the root with the float boxes the single-pass traversal computes, and
  // record every leaf with data.
  struct Pending
  {
    int32_t Node;
    glm::vec3 Lo;
    glm::vec3 Hi;
  };
  std::vector<Pending> stack;
  stack.push_back(Pending{ 0, glm::vec3(RegionLoIndex(h, tree, tree.Root().Region)),
    glm::vec3(RegionHiIndex(h, tree, tree.Root().Region)) });
  out.DrawOfNode.assign(tree.Nodes.size(), -1);
  while (!stack.empty())
  {
    const Pending p = stack.back();
    stack.pop_back();
    const KdNode& node = tree.Nodes[static_cast<std::size_t>(p.Node)];
    out.DataNodes += node.HasData() ? 1 : 0;
    if (!node.IsLeaf())
    {
      const int a = node.Axis;
      const float plane = p.Lo[a] +
        static_cast<float>(node.Split) * levelCellSize[static_cast<std::size_t>(node.Level)][a];
      Pending lower{ node.FirstChild, p.Lo, p.Hi };
      Pending upper{ node.FirstChild + 1, p.Lo, p.Hi };
      lower.Hi[a] = plane;
      upper.Lo[a] = plane;
      stack.push_back(upper);
      stack.push_back(lower);
      continue;
    }
    if (!node.HasData())
    {
      continue; // empty space: nothing to draw
    }
    const Grid& grid = h.Grids[static_cast<std::size_t>(node.Grid)];
    const glm::i64vec3 toData = finest / h.CumulativeRatio(grid.Level);
    const glm::ivec3 origin = atlas.Origins[static_cast<std::size_t>(node.Grid)];
    NodeDraw d;
    d.Level = grid.Level;
    d.Page = atlas.PageOfGrid[static_cast<std::size_t>(node.Grid)];
    for (int a = 0; a < 3; ++a)
    {
      d.Lo[a] = p.Lo[a];
      d.Hi[a] = p.Hi[a];
      d.CellSize[a] = levelCellSize[static_cast<std::size_t>(grid.Level)][a];
      const int64_t first = FloorDiv(node.Region.Lo[a], toData[a]);
      const int64_t last = CeilDiv(node.Region.Hi[a], toData[a]) - 1;
      d.FirstCell[a] = static_cast<int>(first);
      d.LastCell[a] = static_cast<int>(last);
      d.AtlasOffset[a] = origin[a] + static_cast<int>(first - grid.Cells.Lo[a]);
    }
    out.DrawOfNode[static_cast<std::size_t>(p.Node)] = static_cast<int32_t>(out.Draws.size());
    out.Draws.push_back(d);
  }
  return out;
}

std::vector<int32_t> OrderFrontToBack(const Hierarchy& h, const KdTree& tree,
  const MultiPassNodes& nodes, const glm::dvec3& eye, const glm::dvec3& direction, bool parallel)
{
  // the eye in finest cells (the unit of the nodes' exact regions), and the viewing direction in
  // index space (only its signs matter)
  const glm::dvec3 finest(h.CumulativeRatio(tree.FinestLevel));
  const glm::dvec3 eyeFinest = (eye - h.Origin) / h.Spacing0 * finest;
  const glm::dvec3 directionIndex = direction / h.Spacing0;

  std::vector<int32_t> order;
  std::vector<int32_t> stack{ 0 };
  while (!stack.empty())
  {
    const int32_t n = stack.back();
    stack.pop_back();
    const KdNode& node = tree.Nodes[static_cast<std::size_t>(n)];
    if (node.IsLeaf())
    {
      const int32_t draw = nodes.DrawOfNode[static_cast<std::size_t>(n)];
      if (draw >= 0)
      {
        order.push_back(draw);
      }
      continue;
    }
    const int a = node.Axis;
    const double plane =
      static_cast<double>(tree.Nodes[static_cast<std::size_t>(node.FirstChild)].Region.Hi[a]);
    const bool lowerFirst = parallel ? directionIndex[a] >= 0.0 : eyeFinest[a] < plane;
    stack.push_back(lowerFirst ? node.FirstChild + 1 : node.FirstChild); // visited second
    stack.push_back(lowerFirst ? node.FirstChild : node.FirstChild + 1);
  }
  return order;
}

} // namespace amrsp
