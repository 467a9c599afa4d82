// SPDX-License-Identifier: BSD-3-Clause
// The reference's sampling of the hierarchy: the finest grid at a point, nearest cell, vertex
// trilinear and the smooth reconstruction of cell data (amrsp/RenderSettings.h, SmoothCellData).
#include "ReferenceRules.h"

#include <cmath>
#include <cstddef>
#include <limits>

namespace amrsp
{
namespace reference
{
namespace
{
constexpr double Absent = std::numeric_limits<double>::quiet_NaN();

double Lerp(double a, double b, double w)
{
  return a + w * (b - a);
}

/// Trilinear interpolation of the 8 values c[x + 2y + 4z] at weights w, as three lerps.
double Trilinear(const double c[8], const glm::dvec3& w)
{
  const double x00 = Lerp(c[0], c[1], w.x), x10 = Lerp(c[2], c[3], w.x);
  const double x01 = Lerp(c[4], c[5], w.x), x11 = Lerp(c[6], c[7], w.x);
  return Lerp(Lerp(x00, x10, w.y), Lerp(x01, x11, w.y), w.z);
}

bool Contains(const Box& box, const glm::i64vec3& cell)
{
  return cell.x >= box.Lo.x && cell.y >= box.Lo.y && cell.z >= box.Lo.z && cell.x < box.Hi.x &&
    cell.y < box.Hi.y && cell.z < box.Hi.z;
}
} // namespace

Field::Field(const Hierarchy& h, const FinestCellLocator& locator, bool smooth)
  : H(h)
  , Locator(locator)
  , SmoothCells(smooth && !h.VertexCentred)
{
  const Box root = h.RootCells();
  this->Lo = glm::dvec3(root.Lo);
  this->Hi = glm::dvec3(root.Hi);
}

glm::dvec3 Field::CellSizeOf(int level) const
{
  return glm::dvec3(1.0) / glm::dvec3(this->H.CumulativeRatio(level));
}

int32_t Field::FindGrid(const glm::dvec3& p, glm::i64vec3& cell) const
{
  for (int a = 0; a < 3; ++a)
  {
    if (!(p[a] >= this->Lo[a] && p[a] < this->Hi[a]))
    {
      return -1;
    }
  }
  return this->Locator.Find(p, cell);
}

int Field::LevelAt(const glm::dvec3& p) const
{
  glm::i64vec3 cell;
  const int32_t g = this->FindGrid(p, cell);
  return g < 0 ? -1 : this->H.Grids[g].Level;
}

double Field::VertexValue(int32_t g, const glm::dvec3& p) const
{
  const Grid& grid = this->H.Grids[g];
  const glm::i64vec3 vertices = grid.Cells.Extent() + glm::i64vec3(1);
  // u: p in the grid's vertex index space (vertex i at cell corner Lo + i)
  const glm::dvec3 u =
    p * glm::dvec3(this->H.CumulativeRatio(grid.Level)) - glm::dvec3(grid.Cells.Lo);
  glm::i64vec3 i0;
  glm::dvec3 w;
  for (int a = 0; a < 3; ++a)
  {
    const double top = static_cast<double>(vertices[a] - 1);
    const double x = std::min(std::max(u[a], 0.0), top);
    const int64_t base = vertices[a] >= 2
      ? std::min(static_cast<int64_t>(std::floor(x)), vertices[a] - 2)
      : int64_t(0);
    i0[a] = base;
    w[a] = x - static_cast<double>(base);
  }
  const GridValues& values = this->H.Values[g];
  double c[8];
  for (int k = 0; k < 8; ++k)
  {
    glm::i64vec3 v = i0 + glm::i64vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    v = glm::min(v, vertices - glm::i64vec3(1));
    c[k] = values[static_cast<std::size_t>((v.z * vertices.y + v.y) * vertices.x + v.x)];
  }
  return Trilinear(c, w);
}

double Field::Plain(const glm::dvec3& p, int* level) const
{
  glm::i64vec3 cell;
  const int32_t g = this->FindGrid(p, cell);
  if (level)
  {
    *level = g < 0 ? -1 : this->H.Grids[g].Level;
  }
  if (g < 0)
  {
    return Absent;
  }
  return this->H.VertexCentred ? this->VertexValue(g, p) : CellValue(this->H, g, cell);
}

double Field::CornerValue(int32_t g, const glm::i64vec3& corner, int level, double nearest) const
{
  // a cell of the sample's own grid, covered by finer grids or not: that cell
  if (Contains(this->H.Grids[g].Cells, corner))
  {
    return CellValue(this->H, g, corner);
  }
  // else the finest data at the corner's centre x
  const glm::dvec3 x = (glm::dvec3(corner) + 0.5) * this->CellSizeOf(level);
  glm::i64vec3 xCell;
  const int32_t xg = this->FindGrid(x, xCell);
  if (xg < 0)
  {
    return nearest;
  }
  const double xNearest = CellValue(this->H, xg, xCell);
  const int m = this->H.Grids[xg].Level;
  if (m >= level)
  {
    return xNearest;
  }
  // a coarser leaf: the trilinear value of level m at x from that grid's cells; a corner the
  // grid does not have takes the nearest cell of the finest data at its centre
  const glm::dvec3 h = this->CellSizeOf(m);
  const glm::dvec3 q = x / h - 0.5;
  const glm::dvec3 base = glm::floor(q);
  double c[8];
  for (int k = 0; k < 8; ++k)
  {
    const glm::i64vec3 cm = glm::i64vec3(base) + glm::i64vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    if (Contains(this->H.Grids[xg].Cells, cm))
    {
      c[k] = CellValue(this->H, xg, cm);
      continue;
    }
    glm::i64vec3 yCell;
    const int32_t yg = this->FindGrid((glm::dvec3(cm) + 0.5) * h, yCell);
    c[k] = yg >= 0 ? static_cast<double>(CellValue(this->H, yg, yCell)) : xNearest;
  }
  return Trilinear(c, q - base);
}

double Field::SmoothValue(int32_t g, const glm::dvec3& p, double nearest) const
{
  const int level = this->H.Grids[g].Level;
  const glm::dvec3 q = p / this->CellSizeOf(level) - 0.5;
  const glm::dvec3 base = glm::floor(q);
  double c[8];
  for (int k = 0; k < 8; ++k)
  {
    const glm::i64vec3 corner =
      glm::i64vec3(base) + glm::i64vec3(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    c[k] = this->CornerValue(g, corner, level, nearest);
  }
  return Trilinear(c, q - base);
}

double Field::At(const glm::dvec3& p, int* level) const
{
  glm::i64vec3 cell;
  const int32_t g = this->FindGrid(p, cell);
  if (level)
  {
    *level = g < 0 ? -1 : this->H.Grids[g].Level;
  }
  if (g < 0)
  {
    return Absent;
  }
  if (this->H.VertexCentred)
  {
    return this->VertexValue(g, p);
  }
  const double nearest = CellValue(this->H, g, cell);
  return this->SmoothCells ? this->SmoothValue(g, p, nearest) : nearest;
}

} // namespace reference
} // namespace amrsp
