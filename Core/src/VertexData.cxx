// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/VertexData.h"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>
#include <vector>

namespace amrsp
{
namespace
{

glm::i64vec3 VertexDims(const Grid& g)
{
  return g.Cells.Extent() + glm::i64vec3(1);
}

std::size_t VertexIndex(const glm::i64vec3& dims, const glm::i64vec3& v)
{
  return static_cast<std::size_t>((v.z * dims.y + v.y) * dims.x + v.x);
}

bool CellInBox(const Box& b, const glm::i64vec3& c)
{
  return c.x >= b.Lo.x && c.y >= b.Lo.y && c.z >= b.Lo.z && c.x < b.Hi.x && c.y < b.Hi.y &&
    c.z < b.Hi.z;
}

/// Grids per level, for the few lookups the interface fix needs.
std::vector<std::vector<int32_t>> GridsByLevel(const Hierarchy& h)
{
  std::vector<std::vector<int32_t>> byLevel(static_cast<std::size_t>(h.NumberOfLevels()));
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    byLevel[h.Grids[g].Level].push_back(static_cast<int32_t>(g));
  }
  return byLevel;
}

/// Same-level grids whose boxes touch or overlap grid `g` (the only ones with cells next to it).
std::vector<int32_t> Touching(const Hierarchy& h, const std::vector<int32_t>& sameLevel, int32_t g)
{
  std::vector<int32_t> out;
  const Box& b = h.Grids[g].Cells;
  const Box grown{ b.Lo - glm::i64vec3(1), b.Hi + glm::i64vec3(1) };
  for (int32_t o : sameLevel)
  {
    if (o != g && h.Grids[o].Cells.Overlaps(grown))
    {
      out.push_back(o);
    }
  }
  return out;
}

float CellValueOf(const Hierarchy& h, int32_t g, const glm::i64vec3& cell)
{
  const Box& b = h.Grids[g].Cells;
  const glm::i64vec3 e = b.Extent(), c = cell - b.Lo;
  return h.Values[g][static_cast<std::size_t>((c.z * e.y + c.y) * e.x + c.x)];
}

/// Grid among `candidates` whose box holds `cell`, or -1.
int32_t Holder(const Hierarchy& h, const std::vector<int32_t>& candidates, const glm::i64vec3& cell)
{
  for (int32_t o : candidates)
  {
    if (CellInBox(h.Grids[o].Cells, cell))
    {
      return o;
    }
  }
  return -1;
}

} // namespace

float InterpolateVertices(const Hierarchy& h, int32_t g, glm::dvec3 u)
{
  const Grid& grid = h.Grids[g];
  const glm::i64vec3 dims = VertexDims(grid);
  u = glm::clamp(u, glm::dvec3(0.0), glm::dvec3(dims - glm::i64vec3(1)));
  const glm::i64vec3 base =
    glm::min(glm::i64vec3(glm::floor(u)), glm::max(dims - glm::i64vec3(2), glm::i64vec3(0)));
  const glm::dvec3 w = u - glm::dvec3(base);
  const GridValues& v = h.Values[g];
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::i64vec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const glm::i64vec3 at = glm::min(base + o, dims - glm::i64vec3(1));
    const double weight =
      (o.x ? w.x : 1.0 - w.x) * (o.y ? w.y : 1.0 - w.y) * (o.z ? w.z : 1.0 - w.z);
    if (weight != 0.0)
    {
      sum += weight * static_cast<double>(v[VertexIndex(dims, at)]);
    }
  }
  return static_cast<float>(sum);
}

void ConvertCellsToVertices(Hierarchy& h)
{
  if (h.VertexCentred || !h.HasValues())
  {
    throw std::invalid_argument("cell-to-vertex conversion needs cell-centred values");
  }
  // vertices on a face shared with a same-level grid average the cells of both, so the two
  // bricks hold identical samples there
  const std::vector<std::vector<int32_t>> byLevel = GridsByLevel(h);
  std::vector<GridValues> converted(h.Grids.size());
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const Box& box = h.Grids[g].Cells;
    const glm::i64vec3 e = box.Extent();
    const glm::i64vec3 dims = e + glm::i64vec3(1);
    const std::vector<int32_t> touching =
      Touching(h, byLevel[h.Grids[g].Level], static_cast<int32_t>(g));
    GridValues out(static_cast<std::size_t>(dims.x * dims.y * dims.z));
    for (int64_t k = 0; k < dims.z; ++k)
    {
      for (int64_t j = 0; j < dims.y; ++j)
      {
        for (int64_t i = 0; i < dims.x; ++i)
        {
          double sum = 0.0;
          int count = 0;
          for (int64_t c = 0; c < 8; ++c)
          {
            const glm::i64vec3 cell =
              box.Lo + glm::i64vec3(i - (c & 1), j - ((c >> 1) & 1), k - ((c >> 2) & 1));
            const int32_t holder =
              CellInBox(box, cell) ? static_cast<int32_t>(g) : Holder(h, touching, cell);
            if (holder < 0)
            {
              continue;
            }
            const float x = CellValueOf(h, holder, cell);
            if (!std::isnan(x))
            {
              sum += x;
              ++count;
            }
          }
          out[VertexIndex(dims, glm::i64vec3(i, j, k))] =
            count ? static_cast<float>(sum / count) : std::nanf("");
        }
      }
    }
    converted[g] = std::move(out);
  }
  h.Values = std::move(converted);
  h.VertexCentred = true;
  MakeVertexDataContinuous(h);
}

void MakeVertexDataContinuous(Hierarchy& h)
{
  if (!h.VertexCentred || !h.HasValues())
  {
    throw std::invalid_argument("the interface fix needs vertex-centred values");
  }
  const std::vector<std::vector<int32_t>> byLevel = GridsByLevel(h);
  for (std::size_t gi = 0; gi < h.Grids.size(); ++gi) // grids are sorted by level
  {
    const Grid& grid = h.Grids[gi];
    const int l = grid.Level;
    if (l == 0)
    {
      continue;
    }
    const glm::i64vec3 dims = VertexDims(grid);
    const glm::dvec3 ratio(h.CumulativeRatio(l));
    const std::vector<int32_t> neighbours = Touching(h, byLevel[l], static_cast<int32_t>(gi));
    // the coarse grid found last (usually the parent) is tried first
    std::vector<int32_t> lastFound(static_cast<std::size_t>(l), -1);
    for (int64_t k = 0; k < dims.z; ++k)
    {
      for (int64_t j = 0; j < dims.y; ++j)
      {
        for (int64_t i = 0; i < dims.x; ++i)
        {
          const glm::i64vec3 local(i, j, k);
          const bool boundary =
            i == 0 || j == 0 || k == 0 || i == dims.x - 1 || j == dims.y - 1 || k == dims.z - 1;
          if (!boundary)
          {
            continue;
          }
          const glm::i64vec3 vertex = grid.Cells.Lo + local;
          bool dangling = false;
          for (int c = 0; c < 8 && !dangling; ++c)
          {
            const glm::i64vec3 cell = vertex - glm::i64vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
            if (CellInBox(grid.Cells, cell))
            {
              continue;
            }
            dangling = Holder(h, neighbours, cell) < 0;
          }
          if (!dangling)
          {
            continue;
          }
          // the finest coarser grid whose closed box contains the vertex
          const glm::dvec3 p = glm::dvec3(vertex) / ratio; // level-0 index units
          for (int cl = l - 1; cl >= 0; --cl)
          {
            const glm::dvec3 r(h.CumulativeRatio(cl));
            const glm::dvec3 u = p * r; // vertex coordinates of level cl
            const auto contains = [&](int32_t o)
            {
              const Box& b = h.Grids[o].Cells;
              return u.x >= b.Lo.x && u.y >= b.Lo.y && u.z >= b.Lo.z && u.x <= b.Hi.x &&
                u.y <= b.Hi.y && u.z <= b.Hi.z;
            };
            int32_t found = lastFound[cl] >= 0 && contains(lastFound[cl]) ? lastFound[cl] : -1;
            for (std::size_t q = 0; found < 0 && q < byLevel[cl].size(); ++q)
            {
              found = contains(byLevel[cl][q]) ? byLevel[cl][q] : -1;
            }
            lastFound[cl] = found >= 0 ? found : lastFound[cl];
            if (found >= 0)
            {
              h.Values[gi][VertexIndex(dims, local)] =
                InterpolateVertices(h, found, u - glm::dvec3(h.Grids[found].Cells.Lo));
              break;
            }
          }
        }
      }
    }
  }
}

} // namespace amrsp
