// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/KdTreeRopes.h"

#include "amrsp/KdTreeLayout.h"

#include <cstddef>

namespace amrsp
{

namespace
{
/// Moves `rope`, the neighbour across face (axis, upper) of the node with box `region`, down to
/// the deepest node that still holds the whole face: through splits on that axis to the child
/// touching the face, and through other splits to the side the face lies on.
uint32_t Descend(const KdTree& tree, uint32_t rope, const Box& region, int axis, bool upper)
{
  while (rope != 0 && !tree.Nodes[rope].IsLeaf())
  {
    const KdNode& n = tree.Nodes[rope];
    const uint32_t lower = static_cast<uint32_t>(n.FirstChild);
    // the children's common face, in finest cells
    const int64_t plane = tree.Nodes[lower].Region.Hi[n.Axis];
    if (n.Axis == axis)
    {
      rope = upper ? lower : lower + 1; // the face is on the node's far side from its own
    }
    else if (region.Hi[n.Axis] <= plane)
    {
      rope = lower;
    }
    else if (region.Lo[n.Axis] >= plane)
    {
      rope = lower + 1;
    }
    else
    {
      break; // the face spans both children
    }
  }
  return rope;
}
} // namespace

std::vector<uint32_t> ComputeKdTreeRopes(const KdTree& tree)
{
  const std::size_t n = tree.Nodes.size();
  std::vector<uint32_t> ropes(6 * n, 0u);
  // children follow their parents (breadth-first order): parents' ropes are final first
  for (std::size_t i = 0; i < n; ++i)
  {
    const KdNode& node = tree.Nodes[i];
    if (node.IsLeaf())
    {
      continue;
    }
    const std::size_t c = static_cast<std::size_t>(node.FirstChild);
    for (std::size_t k = 0; k < 2; ++k)
    {
      const std::size_t child = c + k;
      for (int f = 0; f < 6; ++f)
      {
        ropes[6 * child + f] = ropes[6 * i + f];
      }
      // the lower child's upper face on the split axis borders the upper child, and vice versa
      ropes[6 * child + 2 * node.Axis + (k == 0 ? 1 : 0)] = static_cast<uint32_t>(c + 1 - k);
      for (int f = 0; f < 6; ++f)
      {
        ropes[6 * child + f] =
          Descend(tree, ropes[6 * child + f], tree.Nodes[child].Region, f / 2, f % 2 == 1);
      }
    }
  }
  return ropes;
}

UInt4Texture3D EncodeKdTreeRopes(const KdTree& tree, const EncodedKdTree& e)
{
  using namespace layout;
  const std::size_t n = tree.Nodes.size();
  // the float boxes of a descent from the root, computed as the traversal computes them
  std::vector<glm::vec3> lo(n), hi(n);
  lo[0] = e.RootLo;
  hi[0] = e.RootHi;
  for (std::size_t i = 0; i < n; ++i)
  {
    const uvec2 texel = e.Tree.Texels[i];
    const KdNode& node = tree.Nodes[i];
    const glm::vec3 fromCells = glm::vec3(node.Region.Lo) * e.FinestCellSize;
    const glm::vec3 toCells = glm::vec3(node.Region.Hi) * e.FinestCellSize;
    if (lo[i] != fromCells || hi[i] != toCells)
    {
      return UInt4Texture3D(); // not exact: no ropes
    }
    const uint child = amrspNodeFirstChild(texel);
    if (child == 0u)
    {
      continue;
    }
    const int axis = static_cast<int>(amrspNodeAxis(texel));
    const float plane = lo[i][axis] +
      static_cast<float>(amrspNodeSplit(texel)) * e.LevelCellSize[amrspNodeLevel(texel)][axis];
    lo[child] = lo[i];
    hi[child] = hi[i];
    hi[child][axis] = plane;
    lo[child + 1] = lo[i];
    hi[child + 1] = hi[i];
    lo[child + 1][axis] = plane;
  }

  const std::vector<uint32_t> ropes = ComputeKdTreeRopes(tree);
  UInt4Texture3D t;
  t.Dims = TextureDimsFor(3 * n);
  t.Texels.assign(static_cast<std::size_t>(t.Dims.x) * t.Dims.y * t.Dims.z, glm::uvec4(0u));
  const auto bits = [](int64_t v) { return static_cast<uint32_t>(static_cast<int32_t>(v)); };
  for (std::size_t i = 0; i < n; ++i)
  {
    const Box& r = tree.Nodes[i].Region;
    const uint32_t* q = &ropes[6 * i];
    t.Texels[amrspRopeTexelIndex(static_cast<uint>(i), 0u)] =
      glm::uvec4(bits(r.Lo.x), bits(r.Lo.y), bits(r.Lo.z), bits(r.Hi.x));
    t.Texels[amrspRopeTexelIndex(static_cast<uint>(i), 1u)] =
      glm::uvec4(bits(r.Hi.y), bits(r.Hi.z), q[0], q[1]);
    t.Texels[amrspRopeTexelIndex(static_cast<uint>(i), 2u)] = glm::uvec4(q[2], q[3], q[4], q[5]);
  }
  return t;
}

} // namespace amrsp
