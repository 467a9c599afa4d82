// SPDX-License-Identifier: BSD-3-Clause
// The synthetic cosmology's hierarchy: levels of grids refined where the density peaks.
#include "amrsp/SyntheticCosmo.h"

#include "CosmoLevels.h"
#include "amrsp/ParallelFor.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace amrsp
{

using namespace cosmo;

namespace
{

/// The hierarchy of `p` refined on the field at `boxesTime`, its values from the field at
/// `valuesTime`.
Hierarchy Generate(
  const CosmoParameters& p, double boxesTime, double valuesTime, const ProgressCallback& progress)
{
  const std::string what = "cosmo generator (" + FormatCosmoParameters(p) + "): ";
  if (p.Levels < 1 || p.Levels > 30)
  {
    throw std::invalid_argument(what + "levels must be between 1 and 30");
  }
  if (p.Grids < 1)
  {
    throw std::invalid_argument(what + "grids must be >= 1");
  }
  if (p.RootGrids < 0)
  {
    throw std::invalid_argument(what + "roots must be >= 0");
  }
  const int64_t roots = p.RootGrids > 0 ? p.RootGrids : (p.Levels == 1 ? p.Grids : 8);
  if (p.Levels == 1 && roots != p.Grids)
  {
    throw std::invalid_argument(
      what + "with levels=1 every grid is a root grid, so roots must equal grids");
  }
  if (p.Grids < roots + (p.Levels - 1))
  {
    throw std::invalid_argument(what + "grids must be at least the " + std::to_string(roots) +
      " root grids plus one grid per refined level (" + std::to_string(roots + p.Levels - 1) + ")");
  }
  constexpr int64_t minCellsPerGrid = 64;
  if (p.Cells / minCellsPerGrid < p.Grids)
  {
    throw std::invalid_argument(what + "cells too small for the grids: need at least " +
      std::to_string(minCellsPerGrid) +
      " cells per grid on average (cells >= " + std::to_string(minCellsPerGrid * p.Grids) + ")");
  }

  const std::vector<int64_t> refinedGrids = GridsPerRefinedLevel(p.Grids - roots, p.Levels);

  // Root edge N0: the cell budget model gives level 1 a tenth of the domain (8 * 0.1 * N0^3
  // cells) and every finer level the same mean cells per grid, so
  // Cells = N0^3 * (1 + 8 * 0.1 * sum_l G_l / G_1).
  double share = 1.0;
  for (std::size_t l = 0; l < refinedGrids.size(); ++l)
  {
    share += 8.0 * Level1VolumeFraction * static_cast<double>(refinedGrids[l]) /
      static_cast<double>(refinedGrids[0]);
  }
  const int64_t rootCellsWanted =
    std::max<int64_t>(1, static_cast<int64_t>(static_cast<double>(p.Cells) / share + 0.5));
  const int64_t n0 = NearestIntegerCubeRoot(rootCellsWanted);
  if (n0 * n0 * n0 < roots || (p.Levels > 1 && n0 < 2))
  {
    throw std::invalid_argument(what + "cells too small for " + std::to_string(roots) +
      " root grids (root domain would be " + std::to_string(n0) + "^3 cells)");
  }

  const CosmoField field(p.Seed, boxesTime);
  const CosmoField valuesField = valuesTime == boxesTime ? field : CosmoField(p.Seed, valuesTime);
  Hierarchy h;
  h.Origin = glm::dvec3(0.0);
  h.Spacing0 = glm::dvec3(1.0 / static_cast<double>(n0));
  h.RefinementRatio.assign(static_cast<std::size_t>(p.Levels), glm::ivec3(2));
  h.RefinementRatio[0] = glm::ivec3(1);
  h.ArrayName = "Density";
  h.VertexCentred = false;

  std::vector<Box> level;
  SplitDomain(Box{ glm::i64vec3(0), glm::i64vec3(n0) }, roots, level);
  int64_t levelCells = n0 * n0 * n0;
  int64_t remaining = p.Cells - levelCells;
  for (const Box& b : level)
  {
    h.Grids.push_back(Grid{ 0, b, static_cast<int64_t>(h.Grids.size()) });
  }

  RefinedLevelBuilder builder(field);
  double scale = static_cast<double>(n0); // cells of the current level per unit length
  for (int l = 1; l < p.Levels; ++l)
  {
    scale *= 2.0;
    const int64_t grids = refinedGrids[static_cast<std::size_t>(l - 1)];
    int64_t gridsLeft = 0;
    for (std::size_t j = static_cast<std::size_t>(l - 1); j < refinedGrids.size(); ++j)
    {
      gridsLeft += refinedGrids[j];
    }
    // This level's share of the remaining cell budget, capped by the room in the parents and
    // at least 8 cells per grid.
    double target =
      static_cast<double>(remaining) * static_cast<double>(grids) / static_cast<double>(gridsLeft);
    target = std::min(target, MaxVolumeFraction * 8.0 * static_cast<double>(levelCells));
    target = std::max(target, 8.0 * static_cast<double>(grids));
    level = builder.Build(level, 1.0 / scale, grids, static_cast<int64_t>(target + 0.5));
    if (level.empty())
    {
      throw std::invalid_argument(what + "no room for level " + std::to_string(l));
    }
    levelCells = 0;
    for (const Box& b : level)
    {
      h.Grids.push_back(Grid{ l, b, static_cast<int64_t>(h.Grids.size()) });
      levelCells += b.Cells();
    }
    remaining -= levelCells;
  }

  if (p.GenerateValues)
  {
    h.Values.resize(h.Grids.size());
    // Largest grids first for load balance; each grid is written by exactly one thread.
    std::vector<std::size_t> order(h.Grids.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      order[i] = i;
    }
    std::stable_sort(order.begin(), order.end(),
      [&h](std::size_t a, std::size_t b)
      { return h.Grids[a].Cells.Cells() > h.Grids[b].Cells.Cells(); });
    ProgressTicker ticker(progress, h.TotalCells());
    ParallelFor(
      static_cast<int64_t>(order.size()),
      [&](int64_t i)
      {
        const std::size_t g = order[static_cast<std::size_t>(i)];
        const Grid& grid = h.Grids[g];
        // Cell size of the grid's level in world units: Spacing0 / 2^level (exact scaling).
        const double cs = std::ldexp(h.Spacing0.x, -grid.Level);
        std::vector<float> values;
        valuesField.Sample(grid.Cells, cs, values);
        h.Values[g] = GridValues(std::move(values));
        ticker.Done(grid.Cells.Cells());
      },
      CosmoWorkers());
    ticker.Finish();
  }
  return h;
}

} // namespace

Hierarchy GenerateCosmo(const CosmoParameters& p, const ProgressCallback& progress)
{
  return GenerateCosmoStep(p, p.Step, progress);
}

int CosmoRegridStep(const CosmoParameters& p, int step)
{
  return p.RegridEvery > 0 ? step - step % p.RegridEvery : 0;
}

Hierarchy GenerateCosmoStep(const CosmoParameters& p, int step, const ProgressCallback& progress)
{
  if (step < 0 || step >= p.Steps)
  {
    throw std::invalid_argument("cosmo series: step " + std::to_string(step) +
      " is outside the series' " + std::to_string(p.Steps) + " steps");
  }
  return Generate(
    p, static_cast<double>(CosmoRegridStep(p, step)), static_cast<double>(step), progress);
}

CosmoStatistics ComputeCosmoStatistics(const Hierarchy& h)
{
  CosmoStatistics s;
  s.GridsPerLevel.assign(static_cast<std::size_t>(h.NumberOfLevels()), 0);
  s.CellsPerLevel.assign(static_cast<std::size_t>(h.NumberOfLevels()), 0);
  s.MinGridCells = h.Grids.empty() ? 0 : std::numeric_limits<int64_t>::max();
  for (const Grid& g : h.Grids)
  {
    const std::size_t l = static_cast<std::size_t>(g.Level);
    if (l >= s.GridsPerLevel.size())
    {
      s.GridsPerLevel.resize(l + 1, 0);
      s.CellsPerLevel.resize(l + 1, 0);
    }
    const int64_t c = g.Cells.Cells();
    ++s.GridsPerLevel[l];
    s.CellsPerLevel[l] += c;
    ++s.Grids;
    s.Cells += c;
    s.MinGridCells = std::min(s.MinGridCells, c);
    s.MaxGridCells = std::max(s.MaxGridCells, c);
  }
  return s;
}
} // namespace amrsp
