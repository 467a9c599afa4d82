// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/EmptySpace.h"

#include "amrsp/IntegerMath.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/TransferFunction.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace amrsp
{

std::vector<glm::vec2> ComputeDataNodeRanges(const Hierarchy& h, const EncodedKdTree& tree)
{
  using namespace layout;
  const KdTree decoded = DecodeKdTree(h, tree);
  std::vector<glm::vec2> ranges(
    static_cast<std::size_t>(tree.DataNodeCount + 1), glm::vec2(FLT_MAX, -FLT_MAX));
  if (!h.HasValues())
  {
    return ranges;
  }
  const glm::i64vec3 finest = h.CumulativeRatio(decoded.FinestLevel);
  // one node per item (each writes its own entry); the large nodes dominate, so small chunks
  ParallelFor(
    static_cast<int64_t>(decoded.Nodes.size()),
    [&](int64_t i)
    {
      const KdNode& n = decoded.Nodes[static_cast<std::size_t>(i)];
      const uint data = amrspNodeData(tree.Tree.Texels[static_cast<std::size_t>(i)]);
      if (data == 0 || !n.HasData())
      {
        return;
      }
      const Grid& g = h.Grids[n.Grid];
      const glm::i64vec3 toData = finest / h.CumulativeRatio(g.Level);
      glm::i64vec3 first, last;
      for (int a = 0; a < 3; ++a)
      {
        first[a] = FloorDiv(n.Region.Lo[a], toData[a]);
        last[a] = CeilDiv(n.Region.Hi[a], toData[a]) - 1;
      }
      first = glm::clamp(first, g.Cells.Lo, g.Cells.Hi - glm::i64vec3(1)) - g.Cells.Lo;
      last = glm::clamp(last, g.Cells.Lo, g.Cells.Hi - glm::i64vec3(1)) - g.Cells.Lo;
      glm::i64vec3 extent = g.Cells.Extent();
      if (h.VertexCentred)
      {
        last += glm::i64vec3(1); // the vertices of the node's cells
        extent += glm::i64vec3(1);
      }
      const GridValues& values = h.Values[n.Grid];
      // NaN is skipped: a comparison with NaN is false, so neither bound takes it
      float lo = FLT_MAX, hi = -FLT_MAX;
      for (int64_t z = first.z; z <= last.z; ++z)
      {
        for (int64_t y = first.y; y <= last.y; ++y)
        {
          const float* row =
            values.data() + static_cast<std::size_t>((z * extent.y + y) * extent.x);
          for (int64_t x = first.x; x <= last.x; ++x)
          {
            const float v = row[x];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
          }
        }
      }
      ranges[data] = glm::vec2(lo, hi);
    },
    0, 16);
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
