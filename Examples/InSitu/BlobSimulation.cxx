// SPDX-License-Identifier: BSD-3-Clause
#include "BlobSimulation.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>

namespace insitu
{
namespace
{

/// A blob: amplitude, width (standard deviation), distance from the vertical axis through the
/// cube's centre, height, starting angle and angular speed (radians per unit time).
struct Blob
{
  double Amplitude, Width, Radius, Height, Phase, Speed;
};

constexpr Blob Blobs[] = {
  { 1.0, 0.10, 0.22, 0.50, 0.0, 2.0 },
  { 0.8, 0.07, 0.26, 0.35, 2.1, -3.0 },
  { 0.6, 0.14, 0.12, 0.62, 4.2, 1.0 },
};

using Tile = std::tuple<int, int, int>; // a tile's first cell, in its level's index space

} // namespace

BlobSimulation::BlobSimulation(const SimulationConfig& config, int rank, int ranks)
  : Config(config)
  , Rank(rank)
  , Ranks(ranks)
{
  if (config.BaseCells % config.BaseBlockCells != 0 || config.TileCells % 2 != 0 ||
    config.Levels < 1 || ranks < 1)
  {
    throw std::invalid_argument("the level-0 block edge must divide the level-0 cells, the "
                                "tile edge must be even, and levels and ranks at least 1");
  }
  this->Regrid();
  this->Compute();
}

double BlobSimulation::CellSize(int level) const
{
  return 1.0 / (this->Config.BaseCells * static_cast<double>(1 << level));
}

double BlobSimulation::Field(double x, double y, double z) const
{
  const double t = this->Time();
  double f = 0.0;
  for (const Blob& b : Blobs)
  {
    const double angle = b.Phase + b.Speed * t;
    const double dx = x - (0.5 + b.Radius * std::cos(angle));
    const double dy = y - (0.5 + b.Radius * std::sin(angle));
    const double dz = z - b.Height;
    f += b.Amplitude * std::exp(-(dx * dx + dy * dy + dz * dz) / (2.0 * b.Width * b.Width));
  }
  return f;
}

void BlobSimulation::Step()
{
  ++this->StepCount;
  this->Regridded = this->StepCount % this->Config.RegridInterval == 0;
  if (this->Regridded)
  {
    this->Regrid();
  }
  this->Compute();
}

void BlobSimulation::Regrid()
{
  const SimulationConfig& c = this->Config;
  std::vector<Block> blocks;
  std::set<Tile> below; // the blocks of the level below, by first cell
  for (int k = 0; k < c.BaseCells; k += c.BaseBlockCells)
  {
    for (int j = 0; j < c.BaseCells; j += c.BaseBlockCells)
    {
      for (int i = 0; i < c.BaseCells; i += c.BaseBlockCells)
      {
        Block b;
        b.Lo = { i, j, k };
        b.Cells = { c.BaseBlockCells, c.BaseBlockCells, c.BaseBlockCells };
        blocks.push_back(b);
        below.insert(Tile(i, j, k));
      }
    }
  }
  int belowEdge = c.BaseBlockCells; // edge of the blocks of the level below, in its cells
  for (int level = 1; level < c.Levels; ++level)
  {
    const int cells = c.BaseCells << level;
    const int half = c.TileCells / 2; // a tile's edge in the cells of the level below
    const double h = this->CellSize(level - 1);
    std::set<Tile> kept;
    for (int k = 0; k < cells; k += c.TileCells)
    {
      for (int j = 0; j < cells; j += c.TileCells)
      {
        for (int i = 0; i < cells; i += c.TileCells)
        {
          // properly nested: the cells it refines lie inside one block of the level below
          const int pi = i / 2, pj = j / 2, pk = k / 2;
          if (!below.count(Tile(pi - pi % belowEdge, pj - pj % belowEdge, pk - pk % belowEdge)))
          {
            continue;
          }
          bool steep = false;
          for (int z = pk; z < pk + half && !steep; ++z)
          {
            for (int y = pj; y < pj + half && !steep; ++y)
            {
              for (int x = pi; x < pi + half && !steep; ++x)
              {
                const double cx = (x + 0.5) * h, cy = (y + 0.5) * h, cz = (z + 0.5) * h;
                const double change =
                  std::max({ std::abs(this->Field(cx + h, cy, cz) - this->Field(cx - h, cy, cz)),
                    std::abs(this->Field(cx, cy + h, cz) - this->Field(cx, cy - h, cz)),
                    std::abs(this->Field(cx, cy, cz + h) - this->Field(cx, cy, cz - h)) }) /
                  2.0;
                steep = change > c.RefineThreshold;
              }
            }
          }
          if (steep)
          {
            Block b;
            b.Level = level;
            b.Lo = { i, j, k };
            b.Cells = { c.TileCells, c.TileCells, c.TileCells };
            blocks.push_back(b);
            kept.insert(Tile(i, j, k));
          }
        }
      }
    }
    if (kept.empty())
    {
      break; // nothing steep enough: fewer levels this time
    }
    below = std::move(kept);
    belowEdge = c.TileCells;
  }
  // as AMR codes share out their boxes: along a space-filling curve (Morton order of the blocks'
  // centres, all levels together), in runs of about equal cell counts per rank, so that each
  // rank owns a compact part of the domain
  const int finest = c.BaseCells << (c.Levels - 1);
  std::vector<std::pair<std::uint64_t, std::size_t>> curve;
  for (std::size_t n = 0; n < blocks.size(); ++n)
  {
    const Block& b = blocks[n];
    const int scale = finest / (c.BaseCells << b.Level);
    std::uint64_t key = 0;
    for (int bit = 20; bit >= 0; --bit)
    {
      for (int a = 0; a < 3; ++a) // x most significant: halves split x first, as the
      {                           // representation's regions are cut (longest axis, x first)
        const int centre = (2 * b.Lo[a] + b.Cells[a]) * scale / 2;
        key = (key << 1) | static_cast<std::uint64_t>((centre >> bit) & 1);
      }
    }
    curve.emplace_back(key, n);
  }
  std::sort(curve.begin(), curve.end());
  std::int64_t total = 0;
  for (const Block& b : blocks)
  {
    total += static_cast<std::int64_t>(b.Cells[0]) * b.Cells[1] * b.Cells[2];
  }
  std::int64_t before = 0;
  for (const auto& entry : curve)
  {
    Block& b = blocks[entry.second];
    const std::int64_t n = static_cast<std::int64_t>(b.Cells[0]) * b.Cells[1] * b.Cells[2];
    b.Owner = static_cast<int>(
      std::min<std::int64_t>(this->Ranks - 1, (2 * before + n) * this->Ranks / (2 * total)));
    before += n;
  }
  this->Hierarchy = std::move(blocks);
}

void BlobSimulation::Compute()
{
  for (Block& b : this->Hierarchy)
  {
    if (b.Owner != this->Rank)
    {
      b.Values.clear();
      continue;
    }
    const double h = this->CellSize(b.Level);
    b.Values.resize(static_cast<std::size_t>(b.Cells[0]) * b.Cells[1] * b.Cells[2]);
    std::size_t n = 0;
    for (int k = 0; k < b.Cells[2]; ++k)
    {
      for (int j = 0; j < b.Cells[1]; ++j)
      {
        for (int i = 0; i < b.Cells[0]; ++i)
        {
          b.Values[n++] = static_cast<float>(
            this->Field((b.Lo[0] + i + 0.5) * h, (b.Lo[1] + j + 0.5) * h, (b.Lo[2] + k + 0.5) * h));
        }
      }
    }
  }
}

} // namespace insitu
