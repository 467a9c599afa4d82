// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/KdTraversal.h"

#include "amrsp/KdTreeLayout.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace amrsp
{

bool IntersectBox(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& origin,
  const glm::vec3& direction, float& tEnter, float& tExit)
{
  const float inf = std::numeric_limits<float>::infinity();
  tEnter = -inf;
  tExit = inf;
  for (int a = 0; a < 3; ++a)
  {
    if (direction[a] == 0.0f)
    {
      if (origin[a] < lo[a] || origin[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    float t0 = (lo[a] - origin[a]) / direction[a];
    float t1 = (hi[a] - origin[a]) / direction[a];
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    tEnter = std::max(tEnter, t0);
    tExit = std::min(tExit, t1);
  }
  return tEnter < tExit;
}

namespace
{
/// Where the ray leaves the box [lo, hi]: min over the axes of the far face's distance, as
/// IntersectBox computes it.
float ExitDistance(
  const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& origin, const glm::vec3& direction)
{
  float t = std::numeric_limits<float>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (direction[a] != 0.0f)
    {
      t = std::min(t, ((direction[a] > 0.0f ? hi[a] : lo[a]) - origin[a]) / direction[a]);
    }
  }
  return t;
}

/// The one axis whose far face of [lo, hi] the ray reaches at tLeave; -1 when none or several
/// (an edge or corner: the rope of one face need not hold the next leaf).
int ExitAxis(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& origin,
  const glm::vec3& direction, float tLeave)
{
  int axis = -1;
  for (int a = 0; a < 3; ++a)
  {
    if (direction[a] != 0.0f &&
      ((direction[a] > 0.0f ? hi[a] : lo[a]) - origin[a]) / direction[a] == tLeave)
    {
      if (axis >= 0)
      {
        return -1;
      }
      axis = a;
    }
  }
  return axis;
}
} // namespace

void TraverseKdTree(const EncodedKdTree& tree, const glm::vec3& origin, const glm::vec3& direction,
  float tMin, float tMax, const LevelOfDetail& lod, std::vector<RaySegment>& segments,
  bool restartFromRoot, bool ropes)
{
  using namespace layout;
  float tEnter, tExit;
  if (!IntersectBox(tree.RootLo, tree.RootHi, origin, direction, tEnter, tExit))
  {
    return;
  }
  float t = std::max(tEnter, tMin);
  const float tEnd = std::min(tExit, tMax);
  const float inf = std::numeric_limits<float>::infinity();
  // Every restart ends on a distinct split plane or the exit, so the number of segments is
  // bounded by the number of nodes; the guard only protects against corrupt textures.
  const int64_t guard = 4 * tree.NodeCount + 16;
  // kd-restart with push-down, as the shader: each restart descends from the deepest node
  // reached without a choice between two children (its box holds the rest of the ray), or from
  // the far child of the last split crossed, which visits the same leaves with the same planes
  // as a descent from the root. Perspective level-of-detail cut-offs depend on t, so there every
  // restart is from the root.
  const bool canPushDown =
    !restartFromRoot && (lod.ThresholdPixels <= 0.0f || lod.ParallelPixelSize > 0.0f);
  uint restartNode = 0;
  glm::vec3 restartLo = tree.RootLo;
  glm::vec3 restartHi = tree.RootHi;
  // Far child of the deepest split plane the last descent crossed, and where the ray leaves it.
  // The leaf found by that descent ends on that plane, so the next leaf lies in this child: the
  // next descent starts there (a one-entry short stack, under the same condition as push-down).
  bool haveFar = false;
  uint farNode = 0;
  glm::vec3 farLo(0.0f), farHi(0.0f);
  float farEnd = 0.0f;
  // The rope across the face the last leaf was left through, and its box (level-0 index units,
  // exactly the box a descent from the root computes: amrsp/KdTreeRopes.h).
  const bool useRopes =
    ropes && canPushDown && lod.ThresholdPixels <= 0.0f && !tree.Ropes.Texels.empty();
  bool haveRope = false;
  uint ropeNode = 0;
  glm::vec3 ropeLo(0.0f), ropeHi(0.0f);
  for (int64_t iteration = 0; t < tEnd && iteration < guard; ++iteration)
  {
    const bool fromRope = haveRope;
    haveRope = false;
    // An empty far interval (planes meeting where the leaf ends) is left to the restart.
    const bool fromFar = !fromRope && haveFar && farEnd > t;
    haveFar = false;
    if (fromFar && farEnd >= tEnd)
    {
      restartNode = farNode; // the far child holds the rest of the ray
      restartLo = farLo;
      restartHi = farHi;
    }
    uint node = fromRope ? ropeNode : fromFar ? farNode : restartNode;
    glm::vec3 lo = fromRope ? ropeLo : fromFar ? farLo : restartLo;
    glm::vec3 hi = fromRope ? ropeHi : fromFar ? farHi : restartHi;
    float tLeave = fromRope ? std::min(ExitDistance(ropeLo, ropeHi, origin, direction), tEnd)
      : fromFar             ? farEnd
                            : tEnd;
    uvec2 texel = tree.Tree.Texels[node];
    bool pushDown = canPushDown && !fromRope && (!fromFar || farEnd >= tEnd);
    uint32_t descent = 0;
    uint32_t lodChecks = 0;
    for (;;)
    {
      const uint child = amrspNodeFirstChild(texel);
      if (child == 0u)
      {
        break;
      }
      const uint data = amrspNodeData(texel);
      if (data != 0u && lod.ThresholdPixels > 0.0f)
      {
        ++lodChecks;
        const uint dataLevel = amrspDataLevel(tree.DataNodes.Texels[data]);
        const glm::vec3 cell = tree.LevelCellSize[dataLevel] * lod.Spacing0;
        const float cellWorld = std::max(cell.x, std::max(cell.y, cell.z));
        const float pixel =
          lod.ParallelPixelSize > 0.0f ? lod.ParallelPixelSize : t * lod.PixelSizePerDistance;
        if (cellWorld < lod.ThresholdPixels * pixel)
        {
          break;
        }
      }
      const int axis = static_cast<int>(amrspNodeAxis(texel));
      const uint level = amrspNodeLevel(texel);
      const float plane =
        lo[axis] + static_cast<float>(amrspNodeSplit(texel)) * tree.LevelCellSize[level][axis];
      const float o = origin[axis];
      const float d = direction[axis];
      const bool originBelow = o < plane || (o == plane && d > 0.0f);
      const float tSplit = d != 0.0f ? (plane - o) / d : inf;
      bool lower;
      if (tSplit >= tLeave || tSplit < 0.0f)
      {
        lower = originBelow; // the whole rest of the interval is on the origin's side
      }
      else if (tSplit <= t)
      {
        lower = !originBelow; // already past the plane
      }
      else
      {
        lower = originBelow;
        if (canPushDown)
        {
          haveFar = true;
          farNode = lower ? child + 1u : child;
          farLo = lo;
          farHi = hi;
          (lower ? farLo : farHi)[axis] = plane;
          farEnd = tLeave;
        }
        tLeave = tSplit;
        pushDown = false;
      }
      if (lower)
      {
        hi[axis] = plane;
        node = child;
      }
      else
      {
        lo[axis] = plane;
        node = child + 1u;
      }
      texel = tree.Tree.Texels[node];
      ++descent;
      if (pushDown)
      {
        restartNode = node;
        restartLo = lo;
        restartHi = hi;
      }
    }
    RaySegment s;
    s.T0 = t;
    s.T1 = tLeave;
    s.Node = node;
    s.Data = amrspNodeData(texel);
    s.Level = s.Data != 0u ? static_cast<int>(amrspDataLevel(tree.DataNodes.Texels[s.Data])) : -1;
    s.NodeLo = lo;
    s.NodeHi = hi;
    s.Descent = descent;
    s.FromFar = fromFar;
    s.LodChecks = lodChecks;
    s.FromRope = fromRope;
    segments.push_back(s);
    t = tLeave;
    if (useRopes && t < tEnd)
    {
      const int axis = ExitAxis(lo, hi, origin, direction, tLeave);
      if (axis >= 0)
      {
        const uint k = amrspRopeTexelOfAxis(static_cast<uint>(axis));
        const uint rope = amrspRopeOf(tree.Ropes.Texels[amrspRopeTexelIndex(node, k)],
          static_cast<uint>(axis), direction[axis] > 0.0f);
        if (rope != 0u)
        {
          haveRope = true;
          ropeNode = rope;
          const glm::uvec4 box = tree.Ropes.Texels[amrspRopeTexelIndex(rope, 0u)];
          const glm::uvec4 boxHi = tree.Ropes.Texels[amrspRopeTexelIndex(rope, 1u)];
          ropeLo = glm::vec3(amrspRopeBoxLo(box)) * tree.FinestCellSize;
          ropeHi = glm::vec3(amrspRopeBoxHi(box, boxHi)) * tree.FinestCellSize;
        }
      }
    }
  }
}

} // namespace amrsp
