// SPDX-License-Identifier: BSD-3-Clause
// The reference's tree-free lookup of the finest cell containing a point.
#include "amrsp/FinestCellLocator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace amrsp
{

FinestCellLocator::FinestCellLocator(const Hierarchy& h)
  : H(h)
{
  const int levels = h.NumberOfLevels();
  Levels.resize(levels);
  for (int l = 0; l < levels; ++l)
  {
    CumRatio.push_back(glm::dvec3(h.CumulativeRatio(l)));
  }
  std::vector<std::vector<int32_t>> perLevel(levels);
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    perLevel[h.Grids[g].Level].push_back(static_cast<int32_t>(g));
  }
  for (int l = 0; l < levels; ++l)
  {
    LevelBuckets& b = Levels[l];
    if (perLevel[l].empty())
    {
      continue;
    }
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (int32_t g : perLevel[l])
    {
      lo = glm::min(lo, glm::dvec3(h.Grids[g].Cells.Lo) / CumRatio[l]);
      hi = glm::max(hi, glm::dvec3(h.Grids[g].Cells.Hi) / CumRatio[l]);
    }
    const int n = std::max(
      1, std::min(64, static_cast<int>(std::cbrt(static_cast<double>(perLevel[l].size())) * 2.0)));
    b.Lo = lo;
    b.Count = glm::ivec3(n);
    b.BucketSize = (hi - lo) / glm::dvec3(n);
    b.Grids.resize(static_cast<std::size_t>(n) * n * n);
    for (int32_t g : perLevel[l])
    {
      const glm::dvec3 glo = glm::dvec3(h.Grids[g].Cells.Lo) / CumRatio[l];
      const glm::dvec3 ghi = glm::dvec3(h.Grids[g].Cells.Hi) / CumRatio[l];
      const glm::ivec3 a =
        glm::clamp(glm::ivec3(glm::floor((glo - lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
      const glm::ivec3 z =
        glm::clamp(glm::ivec3(glm::floor((ghi - lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
      for (int k = a.z; k <= z.z; ++k)
      {
        for (int j = a.y; j <= z.y; ++j)
        {
          for (int i = a.x; i <= z.x; ++i)
          {
            b.Grids[(static_cast<std::size_t>(k) * n + j) * n + i].push_back(g);
          }
        }
      }
    }
  }
}

int32_t FinestCellLocator::Find(const glm::dvec3& p, glm::i64vec3& cell) const
{
  for (int l = static_cast<int>(Levels.size()) - 1; l >= 0; --l)
  {
    const LevelBuckets& b = Levels[l];
    if (b.Grids.empty())
    {
      continue;
    }
    const glm::ivec3 bucket =
      glm::clamp(glm::ivec3(glm::floor((p - b.Lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
    const glm::i64vec3 c = glm::i64vec3(glm::floor(p * CumRatio[l]));
    for (int32_t g :
      b.Grids[(static_cast<std::size_t>(bucket.z) * b.Count.y + bucket.y) * b.Count.x + bucket.x])
    {
      const Box& box = H.Grids[g].Cells;
      if (c.x >= box.Lo.x && c.y >= box.Lo.y && c.z >= box.Lo.z && c.x < box.Hi.x &&
        c.y < box.Hi.y && c.z < box.Hi.z)
      {
        cell = c;
        return g;
      }
    }
  }
  return -1;
}

float CellValue(const Hierarchy& h, int32_t g, glm::i64vec3 cell)
{
  const Box& box = h.Grids[g].Cells;
  cell = glm::clamp(cell, box.Lo, box.Hi - glm::i64vec3(1)) - box.Lo;
  const glm::i64vec3 e = box.Extent();
  return h.Values[g][static_cast<std::size_t>((cell.z * e.y + cell.y) * e.x + cell.x)];
}
} // namespace amrsp
