// SPDX-License-Identifier: BSD-3-Clause
// Hand-made and random hierarchies, rays and views shared by the core tests.
#pragma once

#include "amrsp/Hierarchy.h"
#include "amrsp/Render.h"
#include "amrsp/SyntheticCosmo.h"

#include <cmath>
#include <cstdint>
#include <random>

namespace amrsp
{
namespace test
{

inline Box MakeBox(int64_t x0, int64_t y0, int64_t z0, int64_t x1, int64_t y1, int64_t z1)
{
  return Box{ glm::i64vec3(x0, y0, z0), glm::i64vec3(x1, y1, z1) };
}

/// Analytic field sampled at cell centres (level-0 index units), so values differ per level.
inline void FillValues(Hierarchy& h)
{
  h.Values.clear();
  for (const Grid& g : h.Grids)
  {
    const glm::dvec3 cs = h.CellSize(g.Level);
    const glm::i64vec3 e = g.Cells.Extent();
    GridValues v(static_cast<std::size_t>(g.Cells.Cells()));
    for (int64_t k = 0; k < e.z; ++k)
      for (int64_t j = 0; j < e.y; ++j)
        for (int64_t i = 0; i < e.x; ++i)
        {
          const glm::dvec3 p = (glm::dvec3(g.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * cs;
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] =
            static_cast<float>(0.5 + 0.5 * std::sin(0.7 * p.x) * std::cos(0.5 * p.y) + 0.05 * p.z);
        }
    h.Values.push_back(std::move(v));
  }
}

/// The unit cube (world units, origin 0) holding field(world point) at the cell centres, with
/// `finest` cells per axis (even) at its finest level. levels = 1: one grid; levels = 2: a level-0
/// grid of finest / 2 cells per axis and a level-1 patch (ratio 2) over the middle of the domain,
/// [1/4, 3/4)^3 (finest must then be a multiple of 8). Every cell, the covered level-0 cells
/// too, holds the field at its own centre. The same field on levels 1 and 2 differs only by the
/// level boundary (and the cell size outside the patch).
template <typename F>
Hierarchy LevelPatch(int levels, int finest, F field)
{
  Hierarchy h;
  const int64_t n0 = levels == 1 ? finest : finest / 2;
  h.Spacing0 = glm::dvec3(1.0 / static_cast<double>(n0));
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, n0, n0, n0) });
  if (levels == 2)
  {
    h.RefinementRatio.push_back(glm::ivec3(2));
    const int64_t lo = n0 / 2, hi = 3 * n0 / 2; // level-1 cells of [n0 / 4, 3 n0 / 4)
    h.Grids.push_back(Grid{ 1, MakeBox(lo, lo, lo, hi, hi, hi) });
  }
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const Grid& grid = h.Grids[g];
    h.Grids[g].SourceId = static_cast<int64_t>(g);
    const glm::dvec3 cs = h.CellSize(grid.Level) * h.Spacing0; // world units
    const glm::i64vec3 e = grid.Cells.Extent();
    GridValues v(static_cast<std::size_t>(grid.Cells.Cells()));
    for (int64_t k = 0; k < e.z; ++k)
      for (int64_t j = 0; j < e.y; ++j)
        for (int64_t i = 0; i < e.x; ++i)
        {
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] = static_cast<float>(
            field((glm::dvec3(grid.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * cs));
        }
    h.Values.push_back(std::move(v));
  }
  h.ArrayName = "field";
  return h;
}

/// The 2D example of the paper's Figure 2, extruded: one root grid, three level-1 grids (one of
/// them overlapping two parents' worth of cells), two level-2 grids abutting level-0 cells.
inline Hierarchy PaperExample()
{
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(2), glm::ivec3(2) };
  h.Grids.push_back(Grid{ 0, MakeBox(0, 0, 0, 16, 16, 4) });
  h.Grids.push_back(Grid{ 1, MakeBox(2, 2, 0, 12, 10, 8) });
  h.Grids.push_back(Grid{ 1, MakeBox(16, 4, 0, 28, 14, 8) });
  h.Grids.push_back(Grid{ 1, MakeBox(6, 20, 2, 24, 30, 6) });
  h.Grids.push_back(Grid{ 2, MakeBox(6, 6, 0, 20, 18, 16) });
  h.Grids.push_back(Grid{ 2, MakeBox(36, 10, 4, 52, 26, 12) });
  h.Spacing0 = glm::dvec3(0.5, 0.25, 1.0); // anisotropic
  h.Origin = glm::dvec3(-3.0, 1.0, 2.0);
  for (std::size_t i = 0; i < h.Grids.size(); ++i)
  {
    h.Grids[i].SourceId = static_cast<int64_t>(i);
  }
  FillValues(h);
  return h;
}

/// A random hierarchy: several root grids with gaps, per-level ratios 2 or 4 (sometimes
/// anisotropic), fine grids that may straddle several parents, stick out of their parents'
/// coverage, or skip a level. Same-level grids never overlap.
inline Hierarchy RandomHierarchy(std::mt19937_64& rng)
{ // structure only: the tree and traversal tests compare grids and cells, not values
  auto uni = [&](int64_t lo, int64_t hi)
  { return lo + static_cast<int64_t>(rng() % static_cast<uint64_t>(hi - lo + 1)); };
  Hierarchy h;
  const int levels = static_cast<int>(uni(1, 5));
  h.RefinementRatio.assign(1, glm::ivec3(1));
  for (int l = 1; l < levels; ++l)
  {
    glm::ivec3 r(uni(0, 3) == 0 ? 4 : 2);
    if (uni(0, 5) == 0)
    {
      r[static_cast<int>(uni(0, 2))] = 1 + static_cast<int>(uni(1, 3)); // anisotropic ratio
    }
    h.RefinementRatio.push_back(r);
  }
  h.Spacing0 = glm::dvec3(0.5 + uni(0, 10) * 0.1, 0.5 + uni(0, 10) * 0.1, 0.5 + uni(0, 10) * 0.1);
  h.Origin = glm::dvec3(uni(-5, 5), uni(-5, 5), uni(-5, 5));

  const glm::i64vec3 domain(uni(6, 20), uni(6, 20), uni(6, 20));
  std::vector<Box> previous;
  for (int l = 0; l < levels; ++l)
  {
    std::vector<Box> boxes;
    const glm::i64vec3 extent = l == 0 ? domain : domain * h.CumulativeRatio(l);
    const int attempts = l == 0 ? 12 : static_cast<int>(uni(0, 30));
    if (l > 0 && uni(0, 6) == 0)
    {
      continue; // a level with no grids: the next level jumps two levels
    }
    for (int a = 0; a < attempts; ++a)
    {
      glm::i64vec3 lo, hi;
      if (l > 0 && !previous.empty() && uni(0, 4) != 0)
      {
        // mostly near a grid of the previous level, possibly straddling its boundary
        const Box& p =
          previous[static_cast<std::size_t>(uni(0, static_cast<int64_t>(previous.size()) - 1))];
        const Box pr = p.Refined(glm::i64vec3(h.RefinementRatio[l]));
        for (int c = 0; c < 3; ++c)
        {
          lo[c] = uni(pr.Lo[c] - 2, pr.Hi[c] - 1);
          hi[c] = std::min(extent[c], lo[c] + uni(1, std::max<int64_t>(1, (pr.Hi[c] - pr.Lo[c]))));
          lo[c] = std::max<int64_t>(0, lo[c]);
          if (hi[c] <= lo[c])
          {
            hi[c] = lo[c] + 1;
          }
        }
      }
      else
      {
        for (int c = 0; c < 3; ++c)
        {
          lo[c] = uni(0, extent[c] - 1);
          hi[c] = std::min(extent[c], lo[c] + uni(1, std::max<int64_t>(1, extent[c] / 2)));
        }
      }
      const Box b{ lo, hi };
      bool free = true;
      for (const Box& o : boxes)
      {
        free = free && !o.Overlaps(b);
      }
      if (free)
      {
        boxes.push_back(b);
      }
    }
    for (const Box& b : boxes)
    {
      h.Grids.push_back(Grid{ l, b, static_cast<int64_t>(h.Grids.size()) });
    }
    if (!boxes.empty())
    {
      previous = boxes;
    }
  }
  return h;
}

/// Rays from outside and inside the root box, axis-parallel rays and rays through cell corners.
inline void RandomRay(std::mt19937_64& rng, const Hierarchy& h, glm::dvec3& o, glm::dvec3& d)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Grid& g : h.Grids)
  {
    if (g.Level == 0)
    {
      lo = glm::min(lo, h.WorldLo(g.Cells, 0));
      hi = glm::max(hi, h.WorldHi(g.Cells, 0));
    }
  }
  const glm::dvec3 size = hi - lo;
  const int kind = static_cast<int>(rng() % 4);
  const glm::dvec3 target = lo + size * glm::dvec3(u(rng), u(rng), u(rng));
  if (kind == 0)
  {
    o = lo + size * glm::dvec3(u(rng), u(rng), u(rng)); // inside
  }
  else
  {
    o = lo - size + 3.0 * size * glm::dvec3(u(rng), u(rng), u(rng));
  }
  d = glm::normalize(target - o + 1e-9);
  if (kind == 2)
  {
    // axis-parallel through a level-0 cell corner-aligned line
    const int a = static_cast<int>(rng() % 3);
    d = glm::dvec3(0.0);
    d[a] = (rng() % 2) ? 1.0 : -1.0;
    o = h.Origin + glm::floor((target - h.Origin) / h.Spacing0) * h.Spacing0;
    o[a] = d[a] > 0 ? lo[a] - 1.0 : hi[a] + 1.0;
  }
}

/// Boxes only (no values) of synthetic:cosmo at the paper's dataset-3 size: 39,061 grids on 13
/// levels, 140M cells; level 12 spans 2^12 root cells per axis.
inline Hierarchy PaperDataset3Boxes()
{
  CosmoParameters p;
  p.Grids = 39061;
  p.Levels = 13;
  p.Cells = 140000000;
  p.GenerateValues = false;
  return GenerateCosmo(p);
}

inline RenderSettings SmallView(const Hierarchy& h)
{
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const Grid& g : h.Grids)
  {
    if (g.Level == 0)
    {
      lo = glm::min(lo, h.WorldLo(g.Cells, 0));
      hi = glm::max(hi, h.WorldHi(g.Cells, 0));
    }
  }
  RenderSettings s;
  s.Width = 64;
  s.Height = 48;
  s.View.FocalPoint = 0.5 * (lo + hi);
  s.View.Position = s.View.FocalPoint + glm::dvec3(0.6, 0.5, 1.0) * 1.2 * glm::length(hi - lo);
  s.Transfer = TransferFunction::Preset("default", 0.0, 1.2, 0.1 * glm::length(hi - lo));
  return s;
}

} // namespace test
} // namespace amrsp
