// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/RefinedCells.h"

#include "amrsp/IntegerMath.h"

#include <algorithm>
#include <cstddef>

namespace amrsp
{
namespace
{

/// `box` of level l+1 in cells of level l, widened to whole coarse cells.
Box Coarsened(const Box& box, const glm::ivec3& ratio)
{
  Box c;
  for (int a = 0; a < 3; ++a)
  {
    c.Lo[a] = FloorDiv(box.Lo[a], ratio[a]);
    c.Hi[a] = CeilDiv(box.Hi[a], ratio[a]);
  }
  return c;
}

} // namespace

std::vector<std::vector<Box>> RefinedRegions(const Hierarchy& h)
{
  std::vector<std::vector<Box>> regions(h.Grids.size());
  const int levels = h.NumberOfLevels();
  std::vector<std::vector<std::size_t>> byLevel(static_cast<std::size_t>(std::max(levels, 0)));
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const int l = h.Grids[g].Level;
    if (l >= 0 && l < levels)
    {
      byLevel[static_cast<std::size_t>(l)].push_back(g);
    }
  }
  for (int l = 0; l + 1 < levels; ++l)
  {
    // Parents sorted by Lo.x: the candidates for a coarsened child box c are the parents with
    // Lo.x in (c.Lo.x - widest parent, c.Hi.x), found by binary search.
    std::vector<std::size_t> parents = byLevel[static_cast<std::size_t>(l)];
    std::sort(parents.begin(), parents.end(),
      [&h](std::size_t a, std::size_t b) { return h.Grids[a].Cells.Lo.x < h.Grids[b].Cells.Lo.x; });
    int64_t widest = 0;
    for (std::size_t p : parents)
    {
      widest = std::max(widest, h.Grids[p].Cells.Extent().x);
    }
    const glm::ivec3 ratio = h.RefinementRatio[static_cast<std::size_t>(l + 1)];
    for (std::size_t child : byLevel[static_cast<std::size_t>(l + 1)])
    {
      const Box c = Coarsened(h.Grids[child].Cells, ratio);
      auto first = std::lower_bound(parents.begin(), parents.end(), c.Lo.x - widest + 1,
        [&h](std::size_t p, int64_t x) { return h.Grids[p].Cells.Lo.x < x; });
      for (auto it = first; it != parents.end() && h.Grids[*it].Cells.Lo.x < c.Hi.x; ++it)
      {
        const Box& parent = h.Grids[*it].Cells;
        if (parent.Overlaps(c))
        {
          regions[*it].push_back(parent.Intersection(c));
        }
      }
    }
  }
  return regions;
}

std::vector<unsigned char> RefinedCellMask(const Box& grid, const std::vector<Box>& refined)
{
  const glm::i64vec3 e = grid.Extent();
  std::vector<unsigned char> mask(static_cast<std::size_t>(grid.Cells()), 0);
  for (const Box& r : refined)
  {
    const Box b = grid.Intersection(r);
    if (b.Empty())
    {
      continue;
    }
    for (int64_t k = b.Lo.z; k < b.Hi.z; ++k)
    {
      for (int64_t j = b.Lo.y; j < b.Hi.y; ++j)
      {
        const int64_t row = ((k - grid.Lo.z) * e.y + (j - grid.Lo.y)) * e.x - grid.Lo.x;
        std::fill(mask.begin() + row + b.Lo.x, mask.begin() + row + b.Hi.x, 1);
      }
    }
  }
  return mask;
}

} // namespace amrsp
