// SPDX-License-Identifier: BSD-3-Clause
// The reference integrator: no kD-tree, the finest cell found from the grids' boxes.
#include "amrsp/Render.h"

#include "RayIntegration.h"

#include "amrsp/FinestCellLocator.h"
#include "amrsp/SampleStep.h"
#include "amrsp/Shading.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace amrsp
{

using namespace integration;

namespace
{
/// The reference's corner rule (SmoothCornerKdTree's, with the tree-free locator): x, a cell
/// centre of level `level` that is no cell of the sample's grid.
double SmoothCornerReference(const Hierarchy& h, const FinestCellLocator& locator,
  const glm::dvec3& x, int level, double fallback)
{
  glm::i64vec3 xcell;
  const int32_t g = locator.Find(x, xcell);
  if (g < 0)
  {
    return fallback;
  }
  const int m = h.Grids[g].Level;
  const double vx = CellValue(h, g, xcell);
  if (m >= level)
  {
    return vx;
  }
  const glm::dvec3 cellSize = h.CellSize(m);
  return DualCellInterpolate(x, cellSize,
    [&](const glm::dvec3& c)
    {
      const glm::i64vec3 cell = glm::i64vec3(c);
      if (GridHasCell(h, g, cell))
      {
        return static_cast<double>(CellValue(h, g, cell));
      }
      glm::i64vec3 ycell;
      const int32_t yg = locator.Find((c + 0.5) * cellSize, ycell);
      return yg >= 0 ? static_cast<double>(CellValue(h, yg, ycell)) : vx;
    });
}

/// The reference's smooth reconstruction at p (level-0 index units) for a sample of grid g (the
/// finest grid there): SmoothKdTree's rule, corners found by the tree-free locator.
double SmoothReference(const Hierarchy& h, const FinestCellLocator& locator, const glm::dvec3& p,
  int32_t g, double fallback)
{
  const int level = h.Grids[g].Level;
  const glm::dvec3 cellSize = h.CellSize(level);
  return DualCellInterpolate(p, cellSize,
    [&](const glm::dvec3& c)
    {
      const glm::i64vec3 cell = glm::i64vec3(c);
      return GridHasCell(h, g, cell)
        ? static_cast<double>(CellValue(h, g, cell))
        : SmoothCornerReference(h, locator, (c + 0.5) * cellSize, level, fallback);
    });
}
} // namespace

PointLookup ReferencePointLookup(const Hierarchy& h, const FinestCellLocator& locator, bool smooth)
{
  const Box root = h.RootCells();
  const glm::dvec3 lo(root.Lo), hi(root.Hi);
  const bool smoothCells = smooth && !h.VertexCentred;
  return [&h, &locator, lo, hi, smoothCells](const glm::dvec3& q, glm::dvec3& cellSize)
  {
    glm::i64vec3 cell;
    const int32_t g = OutsideBox(q, lo, hi) ? -1 : locator.Find(q, cell);
    if (g < 0)
    {
      return std::numeric_limits<double>::quiet_NaN();
    }
    const int level = h.Grids[g].Level;
    const glm::dvec3 ratio(h.CumulativeRatio(level));
    cellSize = 1.0 / ratio;
    const double v = SampleGrid(h, g, q, ratio);
    return smoothCells ? SmoothReference(h, locator, q, g, v) : v;
  };
}

Image RenderReference(const Hierarchy& h, const RenderSettings& s)
{
  RequireValues(h);
  Image img;
  img.Width = s.Width;
  img.Height = s.Height;
  img.Pixels.resize(static_cast<std::size_t>(s.Width) * s.Height);
  const FinestCellLocator locator(h);

  // the root box: bounding box of the level-0 grids, in level-0 index units
  const Box root = h.RootCells();
  const glm::dvec3 lo(root.Lo), hi(root.Hi);
  std::vector<double> stepOfLevel;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    stepOfLevel.push_back(LevelSampleStep(h, l, s.ReferenceSampleFactor));
  }
  const std::vector<double> isoValues = SortedIsoValues(s);
  const bool shaded = s.Light.Shade || s.Light.Shadows;
  ShadingContext shading = MakeShadingContext(
    s.Light, s.Transfer, h.Origin, h.Spacing0, lo, hi, s.View.Position, s.View.FocalPoint);
  // the reference's point lookup: the finest grid containing the point, from the boxes
  // (nearest or smooth, as the samples), also for iso-surface bisection and shadow rays
  const bool smoothCells = s.SmoothCellData && !h.VertexCentred;
  const PointLookup lookup = ReferencePointLookup(h, locator, smoothCells);
  if (smoothCells)
  {
    shading.Neighbours = lookup;
  }
  shading.CellStencil = !smoothCells && !h.VertexCentred;

  StatsSink sink;
  sink.Target = s.Stats;
  if (s.Stats)
  {
    *s.Stats = RenderStats();
  }

  ForEachRow(
    s.Height, s.Threads,
    [&](int j)
    {
      RenderStats rowStats;
      for (int i = 0; i < s.Width; ++i)
      {
        glm::dvec3 wo, wd;
        s.View.Ray(s.Width, s.Height, i + 0.5, j + 0.5, wo, wd);
        const glm::dvec3 o = (wo - h.Origin) / h.Spacing0;
        const glm::dvec3 d = wd / h.Spacing0;
        double tEnter = -std::numeric_limits<double>::infinity();
        double tExit = std::numeric_limits<double>::infinity();
        bool hit = true;
        for (int a = 0; a < 3 && hit; ++a)
        {
          if (d[a] == 0.0)
          {
            hit = o[a] >= lo[a] && o[a] <= hi[a];
            continue;
          }
          double t0 = (lo[a] - o[a]) / d[a], t1 = (hi[a] - o[a]) / d[a];
          if (t0 > t1)
          {
            std::swap(t0, t1);
          }
          tEnter = std::max(tEnter, t0);
          tExit = std::min(tExit, t1);
        }
        double clip0, clip1;
        hit = hit && ClipInterval(s, wo, wd, clip0, clip1);
        tEnter = std::max(tEnter, clip0);
        tExit = std::min(tExit, clip1);
        Accumulator<double> acc(s.Blend);
        IsoSurfaceTracker iso(shading, lookup, isoValues, -wd);
        glm::dvec3 background = s.Background, opaqueColour;
        double opaqueDistance = 0.0;
        if (s.Opaque && s.Opaque(wo, wd, opaqueDistance, opaqueColour))
        {
          tExit = std::min(tExit, opaqueDistance);
          background = opaqueColour;
        }
        double t = std::max(0.0, tEnter);
        rowStats.Rays += hit && t < tExit ? 1 : 0;
        while (hit && t < tExit)
        {
          if (acc.Done(s.OpacityThreshold))
          {
            break;
          }
          // shrink the step until the level found at its midpoint does not ask for a smaller one
          double dt = std::min(stepOfLevel[0], tExit - t);
          int32_t g = -1;
          glm::i64vec3 cell;
          for (;;)
          {
            g = locator.Find(o + (t + 0.5 * dt) * d, cell);
            const double wanted = g >= 0 ? stepOfLevel[h.Grids[g].Level] : stepOfLevel[0];
            if (wanted >= dt * (1.0 - 1e-12))
            {
              break;
            }
            dt = wanted;
          }
          if (g >= 0)
          {
            const double mid = t + 0.5 * dt;
            const glm::dvec3 ratio(h.CumulativeRatio(h.Grids[g].Level));
            const glm::dvec3 p = o + mid * d;
            double v = SampleGrid(h, g, p, ratio);
            if (s.SmoothCellData && !h.VertexCentred)
            {
              v = SmoothReference(h, locator, p, g, v);
            }
            ++rowStats.Samples;
            if (s.Blend == BlendMode::IsoSurface)
            {
              if (std::isnan(v))
              {
                iso.Break();
              }
              else
              {
                iso.Sample(p, v, acc.Color, acc.Alpha);
              }
            }
            else
            {
              const std::function<glm::dvec3(const glm::dvec3&)> shade = [&](const glm::dvec3& rgb)
              { return ShadeSample(shading, lookup, rgb, p, v, 1.0 / ratio, -wd); };
              acc.Add(s.Transfer, v, dt, shaded ? &shade : nullptr);
            }
          }
          else
          {
            iso.Break();
          }
          t += dt;
        }
        rowStats.TerminatedRays += acc.Done(s.OpacityThreshold) ? 1 : 0;
        img.Pixels[static_cast<std::size_t>(j) * s.Width + i] = acc.Pixel(s.Transfer, background);
      }
      sink.Add(rowStats);
    },
    s.Progress);
  return img;
}
} // namespace amrsp
