// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/KdTreeRopes.h"

#include "amrsp/IntegerMath.h"
#include "amrsp/KdTreeLayout.h"

#include <cstddef>
#include <string>

namespace amrsp
{

glm::ivec3 TextureDimsFor(std::size_t texels)
{
  const std::size_t row = AMRSP_TEXTURE_ROW;
  const std::size_t n = texels == 0 ? 1 : texels;
  const std::size_t rows = (n + row - 1) / row;
  return glm::ivec3(static_cast<int>(n < row ? n : row), static_cast<int>(rows < row ? rows : row),
    static_cast<int>((rows + row - 1) / row));
}

std::size_t KdTreeTextureBytes(const UIntTexture3D& tree, const UIntTexture3D& dataNodes)
{
  return tree.Bytes() + dataNodes.Bytes() + dataNodes.Texels.size();
}

namespace
{
void Require(bool ok, const std::string& what)
{
  if (!ok)
  {
    throw EncodingError(what);
  }
}

void Resize(UIntTexture3D& t, std::size_t texels)
{
  t.Dims = TextureDimsFor(texels);
  t.Texels.assign(static_cast<std::size_t>(t.Dims.x) * t.Dims.y * t.Dims.z, glm::uvec2(0u));
}
} // namespace

EncodedKdTree EncodeKdTree(const Hierarchy& h, const KdTree& tree,
  const std::vector<glm::ivec3>* brickOrigins, const std::vector<int>* brickPages, bool ropes)
{
  using namespace layout;
  EncodedKdTree e;
  const std::size_t nodes = tree.Nodes.size();
  Require(h.NumberOfLevels() <= static_cast<int>(MaxLevel) + 1,
    "the hierarchy has " + std::to_string(h.NumberOfLevels()) +
      " levels; the tree texture encodes at most " + std::to_string(MaxLevel + 1));
  Require(nodes <= MaxNodes,
    "the kD-tree has " + std::to_string(nodes) + " nodes; the tree texture addresses at most " +
      std::to_string(MaxNodes) + " (2^24)");
  Require(h.Grids.size() <= MaxBricks,
    "the hierarchy has " + std::to_string(h.Grids.size()) + " grids; at most 2^24 are supported");
  Require(brickOrigins == nullptr || brickOrigins->size() == h.Grids.size(),
    "one brick origin per grid is required");
  Require(brickPages == nullptr || brickPages->size() == h.Grids.size(),
    "one atlas page per grid is required");

  std::size_t dataNodes = 0;
  for (const KdNode& n : tree.Nodes)
  {
    dataNodes += n.HasData() ? 1 : 0;
  }
  Require(dataNodes <= MaxDataNodes,
    "the kD-tree has " + std::to_string(dataNodes) +
      " data nodes; the tree texture's 21-bit data index addresses at most " +
      std::to_string(MaxDataNodes));

  Resize(e.Tree, nodes);
  Resize(e.DataNodes, dataNodes + 1);
  e.NodeCount = static_cast<int64_t>(nodes);
  e.DataNodeCount = static_cast<int64_t>(dataNodes);

  const glm::i64vec3 finestRatio = h.CumulativeRatio(tree.FinestLevel);
  uint nextData = 1;
  for (std::size_t i = 0; i < nodes; ++i)
  {
    const KdNode& n = tree.Nodes[i];
    uint data = 0;
    if (n.HasData())
    {
      data = nextData++;
      const Grid& g = h.Grids[n.Grid];
      glm::ivec3 offset(0);
      if (brickOrigins)
      {
        // the data-level cell holding the node's lower corner, relative to the grid's first cell
        const glm::i64vec3 toData = finestRatio / h.CumulativeRatio(g.Level);
        const glm::i64vec3 corner =
          glm::i64vec3(FloorDiv(n.Region.Lo.x, toData.x), FloorDiv(n.Region.Lo.y, toData.y),
            FloorDiv(n.Region.Lo.z, toData.z)) -
          g.Cells.Lo;
        const glm::i64vec3 texel = glm::i64vec3((*brickOrigins)[n.Grid]) + corner;
        Require(texel.x >= 0 && texel.y >= 0 && texel.z >= 0 && texel.x <= MaxOffsetX &&
            texel.y <= MaxOffsetY && texel.z <= MaxOffsetZ,
          "a data node's atlas offset exceeds the 2048 x 2048 x 1024 texels the data-nodes "
          "texture can address");
        offset = glm::ivec3(texel);
      }
      const int page = brickPages ? (*brickPages)[n.Grid] : 0;
      if (page < 0 || page >= static_cast<int>(MaxAtlasPages))
      {
        Require(false,
          "a brick's atlas page " + std::to_string(page) + " is beyond the " +
            std::to_string(MaxAtlasPages) + " pages the data-nodes texture can address");
      }
      e.DataNodes.Texels[data] = amrspPackDataNode(static_cast<uint>(g.Level),
        static_cast<uint>(n.Grid), static_cast<uint>(offset.x), static_cast<uint>(offset.y),
        static_cast<uint>(offset.z), static_cast<uint>(page));
    }
    uint axis = AMRSP_AXIS_NONE, child = 0, split = 0;
    if (!n.IsLeaf())
    {
      Require(n.Split >= 1 && n.Split <= static_cast<int64_t>(MaxSplit),
        "a kD node of level " + std::to_string(n.Level) + " is split " + std::to_string(n.Split) +
          " cells from its corner; the layout's 11 bits allow " + std::to_string(MaxSplit) +
          " (node extents up to 2048 cells)");
      axis = static_cast<uint>(n.Axis);
      child = static_cast<uint>(n.FirstChild);
      split = static_cast<uint>(n.Split);
    }
    e.Tree.Texels[i] = amrspPackNode(axis, static_cast<uint>(n.Level), child, split, data);
  }

  e.RootLo = glm::vec3(RegionLoIndex(h, tree, tree.Root().Region));
  e.RootHi = glm::vec3(RegionHiIndex(h, tree, tree.Root().Region));
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    e.LevelCellSize.push_back(glm::vec3(h.CellSize(l)));
  }
  e.FinestCellSize = glm::vec3(h.CellSize(tree.FinestLevel));
  if (ropes)
  {
    e.Ropes = EncodeKdTreeRopes(tree, e);
  }
  return e;
}

KdTree DecodeKdTree(const Hierarchy& h, const EncodedKdTree& e)
{
  using namespace layout;
  KdTree tree;
  tree.FinestLevel = h.NumberOfLevels() - 1;
  tree.Nodes.resize(static_cast<std::size_t>(e.NodeCount));
  const glm::i64vec3 finestRatio = h.CumulativeRatio(tree.FinestLevel);
  tree.Nodes[0].Region.Lo = glm::i64vec3(glm::dvec3(e.RootLo) * glm::dvec3(finestRatio));
  tree.Nodes[0].Region.Hi = glm::i64vec3(glm::dvec3(e.RootHi) * glm::dvec3(finestRatio));
  // parents precede children in breadth-first order, so regions propagate in one sweep
  for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
  {
    const uvec2 t = e.Tree.Texels[i];
    KdNode& n = tree.Nodes[i];
    n.Level = static_cast<int>(amrspNodeLevel(t));
    const uint data = amrspNodeData(t);
    if (data != 0)
    {
      n.Grid = static_cast<int32_t>(amrspDataBrick(e.DataNodes.Texels[data]));
    }
    const uint child = amrspNodeFirstChild(t);
    if (child == 0)
    {
      n.Type = data != 0 ? NodeType::Leaf : NodeType::Empty;
      continue;
    }
    n.Type = data != 0 ? NodeType::Refined : NodeType::Mixed;
    n.Axis = static_cast<int>(amrspNodeAxis(t));
    n.Split = static_cast<int64_t>(amrspNodeSplit(t));
    n.FirstChild = static_cast<int32_t>(child);
    const int64_t toFinest = finestRatio[n.Axis] / h.CumulativeRatio(n.Level)[n.Axis];
    const int64_t plane = n.Region.Lo[n.Axis] + n.Split * toFinest;
    KdNode& lower = tree.Nodes[child];
    KdNode& upper = tree.Nodes[child + 1];
    lower.Region = upper.Region = n.Region;
    lower.Region.Hi[n.Axis] = plane;
    upper.Region.Lo[n.Axis] = plane;
  }
  return tree;
}

} // namespace amrsp
