// SPDX-License-Identifier: BSD-3-Clause
// The synthetic cosmology's refined levels: candidate tiles of the parents, their selection
// where the density peaks, and the adjustment to the requested grid and cell counts.
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
namespace cosmo
{

// ------------------------------------------------------------------------------------------------
// Portable arithmetic: everything that decides the structure or the values goes through these
// (or through +, -, *, /, sqrt, floor, which IEEE 754 rounds identically everywhere).

/// Cube root of x > 0 by a fixed number of Newton steps from a power-of-two start (frexp and
/// ldexp are exact), so the result does not depend on the C library's cbrt.
double CubeRoot(double x)
{
  if (!(x > 0.0))
  {
    return 0.0;
  }
  int e = 0;
  std::frexp(x, &e);
  double y = std::ldexp(1.0, e / 3);
  for (int i = 0; i < 16; ++i)
  {
    y = (2.0 * y + x / (y * y)) / 3.0;
  }
  return y;
}

/// The integer n >= 1 whose cube is nearest to x (x >= 1), by integer bisection.
int64_t NearestIntegerCubeRoot(int64_t x)
{
  int64_t lo = 1;
  int64_t hi = 2097151; // 2097151^3 < 2^63
  while (hi - lo > 1)
  {
    const int64_t mid = (lo + hi) / 2;
    if (mid * mid * mid <= x)
    {
      lo = mid;
    }
    else
    {
      hi = mid;
    }
  }
  // lo^3 <= x < hi^3: pick the nearer one.
  return (x - lo * lo * lo <= hi * hi * hi - x) ? lo : hi;
}
// ------------------------------------------------------------------------------------------------
// Threads. Every parallel loop writes disjoint outputs computed from read-only inputs, so results
// do not depend on the number of threads.

/// One per core, at most 64.
int CosmoWorkers()
{
  return std::min(WorkerCount(), 64);
}

/// Workers for `n` items of which each should get at least `minPerWorker` (1 for small n).
int SliceWorkers(int64_t n, int64_t minPerWorker)
{
  return static_cast<int>(std::min<int64_t>(
    CosmoWorkers(), std::max<int64_t>(1, n / std::max<int64_t>(1, minPerWorker))));
}

/// Splits `box` into `count` boxes by recursive bisection of the longest axis, cutting in
/// proportion to the counts on either side. Appends in a deterministic order.
void SplitDomain(const Box& box, int64_t count, std::vector<Box>& out)
{
  if (count <= 1)
  {
    out.push_back(box);
    return;
  }
  const glm::i64vec3 e = box.Extent();
  int axis = 0;
  for (int a = 1; a < 3; ++a)
  {
    if (e[a] > e[axis])
    {
      axis = a;
    }
  }
  const int64_t c1 = count / 2;
  const int64_t c2 = count - c1;
  int64_t cut = box.Lo[axis] + (e[axis] * c1 + count / 2) / count;
  cut = std::max(box.Lo[axis] + 1, std::min(box.Hi[axis] - 1, cut));
  Box a = box;
  Box b = box;
  a.Hi[axis] = cut;
  b.Lo[axis] = cut;
  SplitDomain(a, c1, out);
  SplitDomain(b, c2, out);
}

/// Grid counts of levels 1..levels-1: at least one each, the rest geometric with ratio
/// GridCountRatio, rounded so that they sum to `total` exactly.
std::vector<int64_t> GridsPerRefinedLevel(int64_t total, int levels)
{
  const int n = levels - 1;
  std::vector<int64_t> g(static_cast<std::size_t>(n), 1);
  if (n == 0)
  {
    return g;
  }
  std::vector<double> w(static_cast<std::size_t>(n));
  double sum = 0.0;
  double q = 1.0;
  for (int l = 0; l < n; ++l)
  {
    w[static_cast<std::size_t>(l)] = q;
    sum += q;
    q *= GridCountRatio;
  }
  const int64_t extra = total - n;
  double cumulative = 0.0;
  int64_t assigned = 0;
  for (int l = 0; l < n; ++l)
  {
    cumulative += w[static_cast<std::size_t>(l)];
    const int64_t upTo = (l == n - 1)
      ? extra
      : static_cast<int64_t>(static_cast<double>(extra) * cumulative / sum + 0.5);
    g[static_cast<std::size_t>(l)] += upTo - assigned;
    assigned = upTo;
  }
  return g;
}

namespace
{

/// Joining boxes pairwise (JoinToCount) is tried only up to this many boxes on a level.
constexpr int64_t MaxJoinBoxes = 64;
/// Smallest tile edge (cells) considered when tiling a parent.
constexpr double MinTile = 2.0;
/// A level's merged tiles are accepted when they form at least this fraction of the requested
/// grids (and not more than the requested grids); splitting makes up the rest.
constexpr double MinMergedFraction = 0.6;

/// One candidate set for a level: each parent (a level-(l-1) grid, refined to level l) cut into
/// a lattice of near-equal tiles of edge about T cells. Tile (i,j,k) of parent p spans cells
/// [Bound(p,a,i), Bound(p,a,i+1)) on axis a, so tiles of one parent partition it and never cross
/// its boundary; hence any union of tiles of one parent is properly nested.
struct Tiling
{
  struct Parent
  {
    int64_t Offset = 0;  ///< first tile's index in the flat tile arrays
    glm::i64vec3 N{ 1 }; ///< tiles per axis (>= 1, <= extent)
    glm::i64vec3 Lo{ 0 };
    glm::i64vec3 Ext{ 1 };
    int64_t Bound(int a, int64_t i) const { return this->Lo[a] + (i * this->Ext[a]) / this->N[a]; }
  };
  std::vector<Parent> Parents;
  std::vector<int32_t> ParentOf; ///< per tile
  std::vector<double> Density;   ///< per tile: the field at the tile centre
  int64_t TotalCells = 0;        ///< cells of all parents (refined)
  int64_t MaxTileCells = 0;      ///< cells of the biggest tile

  int64_t NumberOfTiles() const { return static_cast<int64_t>(this->ParentOf.size()); }

  glm::i64vec3 Local(int64_t tile, const Parent& p) const
  {
    const int64_t l = tile - p.Offset;
    return glm::i64vec3(l % p.N.x, (l / p.N.x) % p.N.y, l / (p.N.x * p.N.y));
  }

  Box TileBox(int64_t tile) const
  {
    const Parent& p = this->Parents[static_cast<std::size_t>(this->ParentOf[tile])];
    const glm::i64vec3 ijk = this->Local(tile, p);
    Box b;
    for (int a = 0; a < 3; ++a)
    {
      b.Lo[a] = p.Bound(a, ijk[a]);
      b.Hi[a] = p.Bound(a, ijk[a] + 1);
    }
    return b;
  }
};

/// A box of a refined level and the index of its parent in the parent level's box list.
struct LevelBox
{
  Box Cells;
  int32_t Parent = 0;
};

/// Candidate tiles and their selection for one level at a time. One builder serves all levels
/// so that its large scratch arrays are allocated (and touched) once.
class LevelBuilder
{
public:
  explicit LevelBuilder(const CosmoField& field)
    : Field(field)
  {
  }

  /// Starts a level: `parents` are the level-(l-1) boxes, `cellSize` the world size of a
  /// level-l cell.
  void SetParents(const std::vector<Box>& parents, double cellSize)
  {
    this->ParentsRefined.clear();
    this->MaxExtent = 1;
    for (const Box& b : parents)
    {
      const Box r = b.Refined(glm::i64vec3(2));
      this->ParentsRefined.push_back(r);
      const glm::i64vec3 e = r.Extent();
      this->MaxExtent = std::max(this->MaxExtent, std::max(e.x, std::max(e.y, e.z)));
    }
    this->CellSize = cellSize;
  }

  const CosmoField& GetField() const { return this->Field; }
  /// Longest parent edge in cells of the level being built.
  int64_t GetMaxExtent() const { return this->MaxExtent; }

  /// Tiles the parents with tiles of edge about `tile`, samples the field at the tile centres,
  /// selects the densest tiles worth `targetCells` cells and merges each parent's selected tiles
  /// into boxes (greedy: runs along x, then whole rows along y, then whole slabs along z).
  std::vector<LevelBox> Evaluate(double tile, int64_t targetCells)
  {
    this->BuildTiling(tile);
    const int64_t nt = this->T.NumberOfTiles();
    const double meanTileCells = static_cast<double>(this->T.TotalCells) / static_cast<double>(nt);
    int64_t k = static_cast<int64_t>(static_cast<double>(targetCells) / meanTileCells + 0.5);
    k = std::max<int64_t>(1, std::min(k, nt));

    // The k densest tiles; ties broken by tile index, so the set is unique.
    std::vector<int64_t>& order = this->Order;
    order.resize(static_cast<std::size_t>(nt));
    for (int64_t i = 0; i < nt; ++i)
    {
      order[static_cast<std::size_t>(i)] = i;
    }
    const std::vector<double>& dens = this->T.Density;
    auto denser = [&dens](int64_t a, int64_t b)
    { return dens[a] > dens[b] || (dens[a] == dens[b] && a < b); };
    if (k < nt)
    {
      std::nth_element(order.begin(), order.begin() + k, order.end(), denser);
    }
    // Tiles differ in size (a parent's edge is rarely a multiple of T), so correct k until the
    // selected cells match the budget to within half a mean tile: add the next-densest tiles or
    // drop the least dense of the selection, never more than the deficit or excess allows.
    // order[0, k) stays the k densest tiles throughout.
    auto cellsOf = [this, &order](int64_t begin, int64_t end)
    {
      int64_t n = 0;
      for (int64_t i = begin; i < end; ++i)
      {
        n += this->T.TileBox(order[static_cast<std::size_t>(i)]).Cells();
      }
      return n;
    };
    int64_t cells = cellsOf(0, k);
    const int64_t tolerance = std::max<int64_t>(1, static_cast<int64_t>(0.5 * meanTileCells));
    const int64_t maxTile = std::max<int64_t>(1, this->T.MaxTileCells);
    int lastStep = 0;
    for (int round = 0; round < 64; ++round)
    {
      const int64_t excess = cells - targetCells;
      if (excess > -tolerance && excess < tolerance)
      {
        break;
      }
      if (excess < 0)
      {
        const int64_t extra = std::min(nt - k, std::max<int64_t>(1, -excess / maxTile));
        if (extra == 0 || lastStep == -1)
        {
          break;
        }
        std::nth_element(order.begin() + k, order.begin() + k + extra, order.end(), denser);
        cells += cellsOf(k, k + extra);
        k += extra;
        lastStep = extra == 1 ? 1 : 0;
      }
      else
      {
        const int64_t drop = std::min(k - 1, std::max<int64_t>(1, excess / maxTile));
        if (drop == 0 || lastStep == 1)
        {
          break;
        }
        std::nth_element(order.begin(), order.begin() + (k - drop), order.begin() + k, denser);
        cells -= cellsOf(k - drop, k);
        k -= drop;
        lastStep = drop == 1 ? -1 : 0;
      }
    }
    std::vector<uint8_t>& selected = this->Selected;
    selected.assign(static_cast<std::size_t>(nt), 0);
    std::vector<int32_t> touched;
    std::vector<uint8_t> parentTouched(this->T.Parents.size(), 0);
    for (int64_t i = 0; i < k; ++i)
    {
      const int64_t t = order[static_cast<std::size_t>(i)];
      selected[static_cast<std::size_t>(t)] = 1;
      const int32_t p = this->T.ParentOf[static_cast<std::size_t>(t)];
      if (!parentTouched[static_cast<std::size_t>(p)])
      {
        parentTouched[static_cast<std::size_t>(p)] = 1;
        touched.push_back(p);
      }
    }
    std::sort(touched.begin(), touched.end());

    std::vector<LevelBox> boxes;
    for (int32_t pi : touched)
    {
      this->MergeParent(pi, selected, boxes);
    }
    return boxes;
  }

private:
  const CosmoField& Field;
  std::vector<Box> ParentsRefined;
  double CellSize = 1.0;
  int64_t MaxExtent = 1;
  Tiling T;
  // Scratch buffers reused between evaluations.
  std::vector<int64_t> Order;
  std::vector<uint8_t> Selected;
  std::vector<uint8_t> Used;

  void BuildTiling(double tile)
  {
    Tiling& t = this->T;
    t.Parents.clear();
    t.TotalCells = 0;
    t.MaxTileCells = 0;
    int64_t offset = 0;
    for (const Box& b : this->ParentsRefined)
    {
      Tiling::Parent p;
      p.Offset = offset;
      p.Lo = b.Lo;
      p.Ext = b.Extent();
      for (int a = 0; a < 3; ++a)
      {
        const int64_t n = static_cast<int64_t>(static_cast<double>(p.Ext[a]) / tile + 0.5);
        p.N[a] = std::max<int64_t>(1, std::min(n, p.Ext[a]));
      }
      offset += p.N.x * p.N.y * p.N.z;
      t.TotalCells += b.Cells();
      // Tile edges are floor or ceil of Ext / N.
      const glm::i64vec3 edge = (p.Ext + p.N - int64_t(1)) / p.N;
      t.MaxTileCells = std::max(t.MaxTileCells, edge.x * edge.y * edge.z);
      t.Parents.push_back(p);
    }
    t.ParentOf.resize(static_cast<std::size_t>(offset));
    t.Density.resize(static_cast<std::size_t>(offset));
    for (std::size_t pi = 0; pi < t.Parents.size(); ++pi)
    {
      const Tiling::Parent& p = t.Parents[pi];
      std::fill(t.ParentOf.begin() + p.Offset,
        t.ParentOf.begin() + p.Offset + p.N.x * p.N.y * p.N.z, static_cast<int32_t>(pi));
    }
    const double cs = this->CellSize;
    const CosmoField& field = this->Field;
    ParallelForSlices(offset, SliceWorkers(offset, 8192),
      [&t, cs, &field](int64_t begin, int64_t end)
      {
        for (int64_t i = begin; i < end; ++i)
        {
          const Box b = t.TileBox(i);
          // Centre in cells of this level: (Lo + Hi) / 2, exact in double.
          const glm::dvec3 c = glm::dvec3(b.Lo + b.Hi) * 0.5;
          t.Density[static_cast<std::size_t>(i)] = field(c * cs);
        }
      });
  }

  void MergeParent(int32_t pi, const std::vector<uint8_t>& selected, std::vector<LevelBox>& out)
  {
    const Tiling::Parent& p = this->T.Parents[static_cast<std::size_t>(pi)];
    const int64_t nx = p.N.x, ny = p.N.y, nz = p.N.z;
    std::vector<uint8_t>& used = this->Used;
    used.assign(static_cast<std::size_t>(nx * ny * nz), 0);
    auto free = [&](int64_t x, int64_t y, int64_t z)
    {
      const int64_t l = x + nx * (y + ny * z);
      return selected[static_cast<std::size_t>(p.Offset + l)] && !used[static_cast<std::size_t>(l)];
    };
    for (int64_t z = 0; z < nz; ++z)
    {
      for (int64_t y = 0; y < ny; ++y)
      {
        for (int64_t x = 0; x < nx; ++x)
        {
          if (!free(x, y, z))
          {
            continue;
          }
          int64_t x1 = x + 1;
          while (x1 < nx && free(x1, y, z))
          {
            ++x1;
          }
          int64_t y1 = y + 1;
          for (;; ++y1)
          {
            bool ok = y1 < ny;
            for (int64_t i = x; ok && i < x1; ++i)
            {
              ok = free(i, y1, z);
            }
            if (!ok)
            {
              break;
            }
          }
          int64_t z1 = z + 1;
          for (;; ++z1)
          {
            bool ok = z1 < nz;
            for (int64_t j = y; ok && j < y1; ++j)
            {
              for (int64_t i = x; ok && i < x1; ++i)
              {
                ok = free(i, j, z1);
              }
            }
            if (!ok)
            {
              break;
            }
          }
          for (int64_t k = z; k < z1; ++k)
          {
            for (int64_t j = y; j < y1; ++j)
            {
              for (int64_t i = x; i < x1; ++i)
              {
                used[static_cast<std::size_t>(i + nx * (j + ny * k))] = 1;
              }
            }
          }
          LevelBox lb;
          lb.Parent = pi;
          lb.Cells.Lo = glm::i64vec3(p.Bound(0, x), p.Bound(1, y), p.Bound(2, z));
          lb.Cells.Hi = glm::i64vec3(p.Bound(0, x1), p.Bound(1, y1), p.Bound(2, z1));
          out.push_back(lb);
        }
      }
    }
  }
};

int64_t CellsOf(const std::vector<LevelBox>& boxes)
{
  int64_t n = 0;
  for (const LevelBox& b : boxes)
  {
    n += b.Cells.Cells();
  }
  return n;
}

/// Splits the boxes with the most cells in halves (longest axis, middle cell) until there are
/// `count` boxes or no box has more than one cell. Halves stay inside the parent.
void SplitToCount(std::vector<LevelBox>& boxes, int64_t count)
{
  // Max-heap on (cells, -index): the largest box first, the lowest index among equals.
  auto less = [&boxes](std::size_t a, std::size_t b)
  {
    const int64_t ca = boxes[a].Cells.Cells(), cb = boxes[b].Cells.Cells();
    return ca < cb || (ca == cb && a > b);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(less)> heap(less);
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    heap.push(i);
  }
  while (static_cast<int64_t>(boxes.size()) < count && !heap.empty())
  {
    const std::size_t i = heap.top();
    heap.pop();
    const glm::i64vec3 e = boxes[i].Cells.Extent();
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (e[a] > e[axis])
      {
        axis = a;
      }
    }
    if (e[axis] < 2)
    {
      break; // the largest box is a single cell: nothing can be split
    }
    LevelBox second = boxes[i];
    const int64_t cut = boxes[i].Cells.Lo[axis] + e[axis] / 2;
    boxes[i].Cells.Hi[axis] = cut;
    second.Cells.Lo[axis] = cut;
    boxes.push_back(second);
    heap.push(i);
    heap.push(boxes.size() - 1);
  }
}

/// Reduces the boxes to `count`: while there are at most MaxJoinBoxes, replaces the two boxes
/// of one parent whose bounding box adds the fewest cells (and meets no other box) by that
/// bounding box; otherwise, or when no pair can be joined, drops the box with the fewest cells.
/// Joined boxes stay inside their common parent and disjoint from the others.
void JoinToCount(std::vector<LevelBox>& boxes, int64_t count)
{
  while (static_cast<int64_t>(boxes.size()) > count)
  {
    const std::size_t n = boxes.size();
    std::size_t bi = n, bj = n;
    int64_t bestCost = std::numeric_limits<int64_t>::max();
    Box bestUnion;
    if (static_cast<int64_t>(n) <= MaxJoinBoxes)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        for (std::size_t j = i + 1; j < n; ++j)
        {
          if (boxes[i].Parent != boxes[j].Parent)
          {
            continue;
          }
          const Box u{ glm::min(boxes[i].Cells.Lo, boxes[j].Cells.Lo),
            glm::max(boxes[i].Cells.Hi, boxes[j].Cells.Hi) };
          const int64_t cost = u.Cells() - boxes[i].Cells.Cells() - boxes[j].Cells.Cells();
          if (cost >= bestCost)
          {
            continue;
          }
          bool clear = true;
          for (std::size_t o = 0; clear && o < n; ++o)
          {
            clear = o == i || o == j || !u.Overlaps(boxes[o].Cells);
          }
          if (clear)
          {
            bestCost = cost;
            bi = i;
            bj = j;
            bestUnion = u;
          }
        }
      }
    }
    if (bi < n)
    {
      boxes[bi].Cells = bestUnion;
      boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(bj));
      continue;
    }
    std::size_t smallest = 0;
    for (std::size_t i = 1; i < n; ++i)
    {
      if (boxes[i].Cells.Cells() < boxes[smallest].Cells.Cells())
      {
        smallest = i;
      }
    }
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(smallest));
  }
}

/// Shaves slabs off the biggest boxes, on the side where the field is lower, until the boxes
/// hold at most `targetCells` cells (within 2%) or every box is a single cell. Only needed when a
/// level has very few, coarse tiles (e.g. one grid on a level). Boxes only shrink, so they stay
/// inside their parents and disjoint.
void TrimToCells(
  std::vector<LevelBox>& boxes, int64_t targetCells, const CosmoField& field, double cellSize)
{
  int64_t total = CellsOf(boxes);
  const int64_t limit = targetCells + targetCells / 50;
  auto less = [&boxes](std::size_t a, std::size_t b)
  {
    const int64_t ca = boxes[a].Cells.Cells(), cb = boxes[b].Cells.Cells();
    return ca < cb || (ca == cb && a > b);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(less)> heap(less);
  for (std::size_t i = 0; i < boxes.size(); ++i)
  {
    heap.push(i);
  }
  while (total > limit && !heap.empty())
  {
    const std::size_t i = heap.top();
    heap.pop();
    Box& b = boxes[i].Cells;
    const glm::i64vec3 e = b.Extent();
    int axis = 0;
    for (int a = 1; a < 3; ++a)
    {
      if (e[a] > e[axis])
      {
        axis = a;
      }
    }
    if (e[axis] < 2)
    {
      break; // the largest box is a single cell
    }
    const int64_t face = b.Cells() / e[axis];
    const int64_t excess = total - targetCells;
    const int64_t thickness =
      std::max<int64_t>(1, std::min<int64_t>(std::max<int64_t>(1, e[axis] / 4), excess / face));
    // Field at the centres of the two candidate slabs (in cells of this level, exact halves).
    glm::dvec3 lowSide = glm::dvec3(b.Lo + b.Hi) * 0.5;
    glm::dvec3 highSide = lowSide;
    lowSide[axis] = static_cast<double>(b.Lo[axis]) + 0.5 * static_cast<double>(thickness);
    highSide[axis] = static_cast<double>(b.Hi[axis]) - 0.5 * static_cast<double>(thickness);
    if (field(lowSide * cellSize) < field(highSide * cellSize))
    {
      b.Lo[axis] += thickness;
    }
    else
    {
      b.Hi[axis] -= thickness;
    }
    total -= thickness * face;
    heap.push(i);
  }
}

/// Builds one refined level with exactly `grids` boxes (when the parents have room) holding about
/// `targetCells` cells. `tileGuess` carries the tile edge, relative to the cube root of the mean
/// grid size, from level to level.
std::vector<LevelBox> BuildLevel(LevelBuilder& builder, const std::vector<Box>& parents,
  double cellSize, int64_t grids, int64_t targetCells, double& tileGuess)
{
  builder.SetParents(parents, cellSize);
  const CosmoField& field = builder.GetField();

  // Search the tile edge T. With the cell budget fixed, bigger tiles give fewer boxes (about
  // B ~ T^-2: a blob of volume V tiled by T^3 tiles merges into ~ (V^(1/3)/T)^2 runs). Aim for a
  // box count between MinMergedFraction and 1 times `grids`; the remainder comes from splitting
  // the biggest boxes. (Smaller tiles would need fewer splits but cost time: the field is
  // sampled at every candidate tile for every T tried.)
  const double meanGrid = static_cast<double>(targetCells) / static_cast<double>(grids);
  const double tmax = static_cast<double>(builder.GetMaxExtent()) + 1.0;
  double t = std::max(MinTile, std::min(tmax, tileGuess * CubeRoot(meanGrid)));
  double tBelow = 0.0;                                // largest T known to give too many boxes
  double tAbove = std::numeric_limits<double>::max(); // smallest T known to give few enough
  std::vector<LevelBox> best;
  double bestTile = t;
  std::vector<LevelBox> over; // the fewest boxes among the tilings with too many
  const double aim = 0.5 * (1.0 + MinMergedFraction) * static_cast<double>(grids);
  for (int iteration = 0; iteration < 10; ++iteration)
  {
    std::vector<LevelBox> boxes = builder.Evaluate(t, targetCells);
    const int64_t b = static_cast<int64_t>(boxes.size());
    if (b > grids && (over.empty() || b < static_cast<int64_t>(over.size())))
    {
      over = boxes;
    }
    if (b <= grids)
    {
      tAbove = std::min(tAbove, t);
      if (best.empty() || b > static_cast<int64_t>(best.size()))
      {
        best = std::move(boxes);
        bestTile = t;
      }
      if (static_cast<double>(b) >= MinMergedFraction * static_cast<double>(grids) || t <= MinTile)
      {
        break;
      }
    }
    else
    {
      tBelow = std::max(tBelow, t);
      if (t >= tmax)
      {
        break;
      }
    }
    double next = t * std::sqrt(static_cast<double>(b) / aim);
    next = std::max(0.5 * t, std::min(2.0 * t, next));
    if (next <= tBelow || next >= tAbove)
    {
      next =
        (tAbove < std::numeric_limits<double>::max()) ? std::sqrt(tBelow * tAbove) : 2.0 * tBelow;
    }
    next = std::max(MinTile, std::min(tmax, next));
    // B(T) jumps where the tile counts per parent change; once the bracket is this narrow,
    // further bisection only hops between the same few tilings.
    const bool bracketed = tAbove < std::numeric_limits<double>::max() && tBelow > 0.0;
    if (std::fabs(next - t) < 1e-3 * t || (bracketed && tAbove < 1.03 * tBelow))
    {
      break;
    }
    t = next;
  }
  if (!best.empty())
  {
    tileGuess = bestTile / CubeRoot(meanGrid);
  }

  // Bring the count to `grids` exactly and the cells to at most the target: split the tiling
  // with few enough boxes, or join (or, failing that, drop) boxes of the tiling with too many.
  // With only a handful of grids on a level B(T) jumps by more than the grid count, and either
  // can be the closer one in cells: keep the result nearer the cell target.
  auto finish = [&](std::vector<LevelBox> boxes)
  {
    if (static_cast<int64_t>(boxes.size()) < grids)
    {
      SplitToCount(boxes, grids);
    }
    else
    {
      JoinToCount(boxes, grids);
    }
    TrimToCells(boxes, targetCells, field, cellSize);
    return boxes;
  };
  auto miss = [targetCells](const std::vector<LevelBox>& boxes)
  {
    const int64_t d = CellsOf(boxes) - targetCells;
    return d < 0 ? -d : d;
  };
  if (best.empty())
  {
    best = finish(std::move(over));
  }
  else
  {
    best = finish(std::move(best));
    if (!over.empty() && static_cast<int64_t>(over.size()) <= MaxJoinBoxes &&
      miss(best) > targetCells / 20)
    {
      std::vector<LevelBox> joined = finish(std::move(over));
      if (static_cast<int64_t>(joined.size()) == grids && miss(joined) < miss(best))
      {
        best = std::move(joined);
      }
    }
  }
  std::sort(best.begin(), best.end(),
    [](const LevelBox& a, const LevelBox& b)
    {
      if (a.Parent != b.Parent)
      {
        return a.Parent < b.Parent;
      }
      for (int ax = 2; ax >= 0; --ax)
      {
        if (a.Cells.Lo[ax] != b.Cells.Lo[ax])
        {
          return a.Cells.Lo[ax] < b.Cells.Lo[ax];
        }
      }
      return false;
    });
  return best;
}
} // namespace

struct RefinedLevelBuilder::Internals
{
  explicit Internals(const CosmoField& field)
    : Builder(field)
  {
  }
  LevelBuilder Builder;
  double TileGuess = 0.6; // tile edge relative to the cube root of the mean grid size
};

RefinedLevelBuilder::RefinedLevelBuilder(const CosmoField& field)
  : I(new Internals(field))
{
}

RefinedLevelBuilder::~RefinedLevelBuilder() = default;

std::vector<Box> RefinedLevelBuilder::Build(
  const std::vector<Box>& parents, double cellSize, int64_t grids, int64_t targetCells)
{
  std::vector<Box> boxes;
  for (const LevelBox& b :
    BuildLevel(this->I->Builder, parents, cellSize, grids, targetCells, this->I->TileGuess))
  {
    boxes.push_back(b.Cells);
  }
  return boxes;
}

} // namespace cosmo
} // namespace amrsp
