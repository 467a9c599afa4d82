// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/EmptySpace.h"

#include "amrsp/IntegerMath.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/MinMaxFold.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/TransferFunction.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace amrsp
{

std::vector<DataNodeBlock> DataNodeBlocks(const Hierarchy& h, const EncodedKdTree& tree)
{
  using namespace layout;
  const KdTree decoded = DecodeKdTree(h, tree);
  const glm::i64vec3 finest = h.CumulativeRatio(decoded.FinestLevel);
  std::vector<DataNodeBlock> found;
  found.reserve(static_cast<std::size_t>(tree.DataNodeCount));
  for (std::size_t i = 0; i < decoded.Nodes.size(); ++i)
  {
    const KdNode& n = decoded.Nodes[i];
    const uint data = amrspNodeData(tree.Tree.Texels[i]);
    if (data == 0 || !n.HasData())
    {
      continue;
    }
    const Grid& g = h.Grids[n.Grid];
    const glm::i64vec3 toData = finest / h.CumulativeRatio(g.Level);
    DataNodeBlock b{ data, static_cast<std::size_t>(n.Grid), glm::i64vec3(0), glm::i64vec3(0),
      g.Cells.Extent() };
    for (int a = 0; a < 3; ++a)
    {
      b.First[a] = FloorDiv(n.Region.Lo[a], toData[a]);
      b.Last[a] = CeilDiv(n.Region.Hi[a], toData[a]) - 1;
    }
    b.First = glm::clamp(b.First, g.Cells.Lo, g.Cells.Hi - glm::i64vec3(1)) - g.Cells.Lo;
    b.Last = glm::clamp(b.Last, g.Cells.Lo, g.Cells.Hi - glm::i64vec3(1)) - g.Cells.Lo;
    if (h.VertexCentred)
    {
      b.Last += glm::i64vec3(1); // the vertices of the node's cells
      b.Extent += glm::i64vec3(1);
    }
    found.push_back(b);
  }
  return found;
}

std::vector<glm::vec2> ComputeDataNodeRanges(const Hierarchy& h, const EncodedKdTree& tree)
{
  if (!h.HasValues())
  {
    return std::vector<glm::vec2>(
      static_cast<std::size_t>(tree.DataNodeCount + 1), glm::vec2(FLT_MAX, -FLT_MAX));
  }
  // the decoded tree (about 80 bytes per node) is freed before the scan, which may run beside
  // the atlas upload (PrepareRayCasting's deferNodeRanges)
  return ComputeDataNodeRanges(h, DataNodeBlocks(h, tree), tree.DataNodeCount);
}

std::vector<glm::vec2> ComputeDataNodeRanges(
  const Hierarchy& h, const std::vector<DataNodeBlock>& blocks, int64_t dataNodeCount)
{
  using Block = DataNodeBlock;
  std::vector<glm::vec2> ranges(
    static_cast<std::size_t>(dataNodeCount + 1), glm::vec2(FLT_MAX, -FLT_MAX));
  if (!h.HasValues())
  {
    return ranges;
  }
  // work items of at most about 2^18 values (slabs of a block's layers), so that the few large
  // blocks of the coarse levels spread over the workers too
  struct Item
  {
    std::size_t Block;
    int64_t Z0, Z1;
  };
  std::vector<Item> items;
  items.reserve(blocks.size());
  for (std::size_t k = 0; k < blocks.size(); ++k)
  {
    const Block& b = blocks[k];
    const int64_t layer = (b.Last.x - b.First.x + 1) * (b.Last.y - b.First.y + 1);
    const int64_t step = std::max<int64_t>(1, (int64_t(1) << 18) / std::max<int64_t>(1, layer));
    for (int64_t z = b.First.z; z <= b.Last.z; z += step)
    {
      items.push_back(Item{ k, z, std::min(b.Last.z, z + step - 1) });
    }
  }
  std::vector<glm::vec2> partial(items.size());
  ParallelFor(
    static_cast<int64_t>(items.size()),
    [&](int64_t i)
    {
      const Item& item = items[static_cast<std::size_t>(i)];
      const Block& b = blocks[item.Block];
      const float* values = h.Values[b.Grid].data();
      // NaN is skipped: a comparison with NaN is false, so neither bound takes it
      float lo = FLT_MAX, hi = -FLT_MAX;
      const int64_t rowLength = b.Last.x - b.First.x + 1;
      if (rowLength == b.Extent.x && b.Last.y - b.First.y + 1 == b.Extent.y)
      {
        // whole layers of the grid: one contiguous run
        FoldMinMax(values + static_cast<std::size_t>(item.Z0 * b.Extent.y * b.Extent.x),
          (item.Z1 - item.Z0 + 1) * b.Extent.y * b.Extent.x, lo, hi);
      }
      else
      {
        for (int64_t z = item.Z0; z <= item.Z1; ++z)
        {
          FoldMinMaxRows(values +
              static_cast<std::size_t>((z * b.Extent.y + b.First.y) * b.Extent.x + b.First.x),
            rowLength, b.Extent.x, b.Last.y - b.First.y + 1, lo, hi);
        }
      }
      partial[static_cast<std::size_t>(i)] = glm::vec2(lo, hi);
    },
    0, 32);
  // min and max are exact in any order
  for (std::size_t i = 0; i < items.size(); ++i)
  {
    glm::vec2& r = ranges[blocks[items[i].Block].Data];
    r.x = std::min(r.x, partial[i].x);
    r.y = std::max(r.y, partial[i].y);
  }
  return ranges;
}

bool TransparentRange(const TransferFunction& tf, double lo, double hi)
{
  if (lo > hi)
  {
    return true;
  }
  // piecewise linear with clamping: the maximum on [lo, hi] is at an end or at a control point
  if (tf.EvaluateOpacity(lo) > 0.0 || tf.EvaluateOpacity(hi) > 0.0)
  {
    return false;
  }
  for (const TransferFunction::OpacityPoint& p : tf.Opacity)
  {
    if (p.X > lo && p.X < hi && p.Opacity > 0.0)
    {
      return false;
    }
  }
  return true;
}

std::vector<float> OpacityPrefixCounts(const std::vector<float>& opacity)
{
  std::vector<float> prefix(opacity.size());
  float count = 0.0f;
  for (std::size_t i = 0; i < opacity.size(); ++i)
  {
    count += opacity[i] > 0.0f ? 1.0f : 0.0f;
    prefix[i] = count;
  }
  return prefix;
}

bool TableRangeTransparent(
  const std::vector<float>& prefix, const float range[2], float lo, float hi)
{
  if (lo > hi)
  {
    return true;
  }
  const int n = static_cast<int>(prefix.size());
  if (n == 0)
  {
    return true;
  }
  // the table positions in the same float expressions as the shader's amrspTransferFunction
  const float last = static_cast<float>(n - 1);
  const float u0 = std::min(1.0f, std::max(0.0f, (lo - range[0]) * range[1])) * last;
  const float u1 = std::min(1.0f, std::max(0.0f, (hi - range[0]) * range[1])) * last;
  const int i0 = std::max(0, static_cast<int>(std::floor(u0)) - 1);
  const int i1 = std::min(n - 1, static_cast<int>(std::ceil(u1)) + 1);
  const float below = i0 > 0 ? prefix[static_cast<std::size_t>(i0 - 1)] : 0.0f;
  return prefix[static_cast<std::size_t>(i1)] - below == 0.0f;
}

} // namespace amrsp
