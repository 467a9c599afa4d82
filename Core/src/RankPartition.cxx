// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/RankPartition.h"

#include "amrsp/IntegerMath.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace amrsp
{
namespace
{

/// Cells of every grid inside `box` (level-0 cells) per level-0 slab along `axis`:
/// weights[s] counts the cells whose level-0 slab is box.Lo[axis] + s.
std::vector<double> SlabWeights(const Hierarchy& h, const Box& box, int axis)
{
  std::vector<double> weights(static_cast<std::size_t>(box.Extent()[axis]), 0.0);
  for (const Grid& g : h.Grids)
  {
    const Box clipped = ClipToRegion(h, g.Cells, g.Level, box);
    if (clipped.Empty())
    {
      continue;
    }
    const glm::i64vec3 e = clipped.Extent();
    const double cross = static_cast<double>(e.x * e.y * e.z / e[axis]);
    const int64_t r = h.CumulativeRatio(g.Level)[axis];
    const int64_t first = FloorDiv(clipped.Lo[axis], r);
    const int64_t last = FloorDiv(clipped.Hi[axis] - 1, r);
    for (int64_t s = first; s <= last; ++s)
    {
      const int64_t cells =
        std::min(clipped.Hi[axis], (s + 1) * r) - std::max(clipped.Lo[axis], s * r);
      weights[static_cast<std::size_t>(s - box.Lo[axis])] += cross * static_cast<double>(cells);
    }
  }
  return weights;
}

void Bisect(const Hierarchy& h, const Box& box, int parts, std::vector<Box>& out)
{
  if (parts == 1)
  {
    out.push_back(box);
    return;
  }
  // the longest axis (world units) that is at least two level-0 cells thick
  int axis = -1;
  double longest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const double length = static_cast<double>(box.Extent()[a]) * h.Spacing0[a];
    if (box.Extent()[a] >= 2 && length > longest)
    {
      axis = a;
      longest = length;
    }
  }
  if (axis < 0)
  {
    out.push_back(box);
    for (int p = 1; p < parts; ++p)
    {
      out.push_back(Box{ box.Lo, box.Lo });
    }
    return;
  }

  const int lowerParts = parts / 2;
  const double fraction = static_cast<double>(lowerParts) / static_cast<double>(parts);
  const std::vector<double> weights = SlabWeights(h, box, axis);
  double total = 0.0;
  for (double w : weights)
  {
    total += w;
  }
  // planes box.Lo + 1 .. box.Hi - 1; the one whose lower share is nearest the target, ties to
  // the one nearest the geometric target (also the rule when the box holds no cells)
  const int64_t extent = box.Extent()[axis];
  const double geometric = fraction * static_cast<double>(extent);
  int64_t best = 1;
  double bestError = INFINITY;
  double bestDistance = INFINITY;
  double lower = 0.0;
  for (int64_t p = 1; p < extent; ++p)
  {
    lower += weights[static_cast<std::size_t>(p - 1)];
    const double error = total > 0.0 ? std::abs(lower / total - fraction) : 0.0;
    const double distance = std::abs(static_cast<double>(p) - geometric);
    if (error < bestError || (error == bestError && distance < bestDistance))
    {
      best = p;
      bestError = error;
      bestDistance = distance;
    }
  }
  Box low = box;
  Box high = box;
  low.Hi[axis] = box.Lo[axis] + best;
  high.Lo[axis] = box.Lo[axis] + best;
  Bisect(h, low, lowerParts, out);
  Bisect(h, high, parts - lowerParts, out);
}

} // namespace

std::vector<Box> PartitionRootBox(const Hierarchy& h, int parts)
{
  if (parts < 1)
  {
    throw std::invalid_argument("PartitionRootBox: the number of parts must be at least 1");
  }
  const Box root = h.RootCells();
  if (root.Empty())
  {
    throw std::invalid_argument("PartitionRootBox: the hierarchy has no level-0 grid");
  }
  std::vector<Box> regions;
  regions.reserve(static_cast<std::size_t>(parts));
  Bisect(h, root, parts, regions);
  return regions;
}

Box ClipToRegion(const Hierarchy& h, const Box& cells, int level, const Box& region)
{
  const Box clipped = h.ToLevel(region, 0, level).Intersection(cells);
  return clipped.Empty() ? Box{ cells.Lo, cells.Lo } : clipped;
}

glm::i64vec3 RegionGhostWidth(const Hierarchy& h, int level)
{
  return level == 0 ? glm::i64vec3(2) : glm::i64vec3(h.RefinementRatio[level]) * int64_t(2);
}

Box GhostedPiece(const Hierarchy& h, const Box& cells, int level, const Box& region)
{
  if (region.Empty())
  {
    return Box{ cells.Lo, cells.Lo };
  }
  Box grown = h.ToLevel(region, 0, level);
  const glm::i64vec3 ghost = RegionGhostWidth(h, level);
  grown.Lo -= ghost;
  grown.Hi += ghost;
  const Box piece = grown.Intersection(cells);
  return piece.Empty() ? Box{ cells.Lo, cells.Lo } : piece;
}

} // namespace amrsp
