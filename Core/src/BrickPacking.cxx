// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/BrickPacking.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/TextCase.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace amrsp
{

namespace
{

int64_t Volume(const glm::ivec3& e)
{
  return static_cast<int64_t>(e.x) * e.y * e.z;
}

std::string DimsString(const glm::ivec3& d)
{
  return std::to_string(d.x) + " x " + std::to_string(d.y) + " x " + std::to_string(d.z);
}

const char* const Advice = "Use the bindless path (one texture per brick), a smaller array type, "
                           "or level-of-detail (leave out the finest levels).";

/// One trial layout: the atlas dims (tight bounding box) and the origins, in input order.
struct Trial
{
  bool Ok = false; ///< false: the bricks did not fit under the height limit
  glm::ivec3 Dims{ 0 };
  int64_t Texels = 0;
  std::vector<glm::ivec3> Origins;
};

/// Strict order of trial results: a successful trial first, then the smaller atlas, then the
/// more cubic one (smaller largest axis), then the smaller z, y, x. Two trials compare equal
/// only for equal dims; callers break that tie by the order of their candidates, so the result
/// does not depend on the order in which trials finish.
bool Better(const Trial& a, const Trial& b)
{
  if (a.Ok != b.Ok)
  {
    return a.Ok;
  }
  if (a.Texels != b.Texels)
  {
    return a.Texels < b.Texels;
  }
  const int ma = std::max(a.Dims.x, std::max(a.Dims.y, a.Dims.z));
  const int mb = std::max(b.Dims.x, std::max(b.Dims.y, b.Dims.z));
  if (ma != mb)
  {
    return ma < mb;
  }
  return std::make_tuple(a.Dims.z, a.Dims.y, a.Dims.x) <
    std::make_tuple(b.Dims.z, b.Dims.y, b.Dims.x);
}

/// Increasing, distinct values in [lo, hi]: a geometric ladder of `steps` values from lo to hi
/// (both included) plus the `extra` values that fall inside the range.
std::vector<int> Ladder(int lo, int hi, int steps, const std::vector<int>& extra)
{
  std::vector<int> v{ lo, hi };
  const double ratio = std::pow(double(hi) / double(lo), 1.0 / (steps - 1));
  double x = lo;
  for (int s = 1; s + 1 < steps; ++s)
  {
    x *= ratio;
    v.push_back(static_cast<int>(std::lround(x)));
  }
  for (int e : extra)
  {
    if (e >= lo && e <= hi)
    {
      v.push_back(e);
    }
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

//--------------------------------------------------------------------------------------------------
// NFDH (paper, section 5.1)

/// Bricks sorted by decreasing z extent, then y, then x (input index breaks ties).
std::vector<int> NfdhOrder(const std::vector<glm::ivec3>& e)
{
  std::vector<int> order(e.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](int a, int b)
    {
      const auto ka = std::make_tuple(e[a].z, e[a].y, e[a].x);
      const auto kb = std::make_tuple(e[b].z, e[b].y, e[b].x);
      return ka != kb ? ka > kb : a < b;
    });
  return order;
}

/// One NFDH pass with container base width x depth (along x and y); the height grows as needed
/// and the pass fails when it would exceed maxZ. Precondition: width >= every x extent and
/// depth >= every y extent.
void NfdhTrial(const std::vector<glm::ivec3>& e, const std::vector<int>& order, int width,
  int depth, int maxZ, Trial& t)
{
  t.Ok = false;
  t.Origins.resize(e.size());
  int x = 0;      // next free x in the current row
  int rowY = 0;   // y of the current row
  int rowD = 0;   // largest y extent in the current row
  int layerZ = 0; // z of the current layer
  int layerH = 0; // largest z extent in the current layer
  glm::ivec3 hi(0);
  for (int i : order)
  {
    const glm::ivec3& b = e[i];
    if (x + b.x > width)
    { // the row is full: open a new one at the largest y extent of this row
      rowY += rowD;
      x = 0;
      rowD = 0;
    }
    if (rowY + b.y > depth)
    { // the layer is full: open a new one at the largest z extent of this layer
      layerZ += layerH;
      rowY = 0;
      x = 0;
      rowD = 0;
      layerH = 0;
    }
    if (layerZ + b.z > maxZ)
    {
      return;
    }
    t.Origins[i] = glm::ivec3(x, rowY, layerZ);
    hi = glm::max(hi, t.Origins[i] + b);
    x += b.x;
    rowD = std::max(rowD, b.y);
    layerH = std::max(layerH, b.z);
  }
  t.Ok = true;
  t.Dims = hi;
  t.Texels = Volume(hi);
}

/// The paper's search: NFDH over a ladder of base extents per axis (24 geometric steps from the
/// largest brick extent to the limit, plus the multiples of the largest brick extent).
Trial PackNfdh(
  const std::vector<glm::ivec3>& extents, const glm::ivec3& maxExtent, const glm::ivec3& maxDims)
{
  std::vector<int> extraX, extraY;
  for (int k = 1; k <= 16; ++k)
  {
    extraX.push_back(k * maxExtent.x);
    extraY.push_back(k * maxExtent.y);
  }
  const std::vector<int> order = NfdhOrder(extents);
  const std::vector<int> xs = Ladder(maxExtent.x, maxDims.x, 24, extraX);
  const std::vector<int> ys = Ladder(maxExtent.y, maxDims.y, 24, extraY);
  Trial best, trial;
  for (int w : xs)
  {
    for (int d : ys)
    {
      NfdhTrial(extents, order, w, d, maxDims.z, trial);
      if (Better(trial, best))
      {
        std::swap(best, trial);
      }
    }
  }
  return best;
}

//--------------------------------------------------------------------------------------------------
// Guillotine best-fit packer

/// The bricks grouped by shape, for best-fit queries. Shapes are ordered by decreasing z extent,
/// then decreasing footprint area (x * y), then decreasing y, then decreasing x. A segment tree
/// over that order holds, per node, the smallest x and the smallest y extent among the shapes
/// that still have unplaced bricks; it prunes the search for the first shape that fits a box.
class ShapeIndex
{
public:
  explicit ShapeIndex(const std::vector<glm::ivec3>& e)
  {
    std::vector<int> order(e.size());
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int i)
    { return std::make_tuple(e[i].z, int64_t(e[i].x) * e[i].y, e[i].y, e[i].x); };
    std::sort(order.begin(), order.end(),
      [&](int a, int b)
      {
        const auto ka = key(a), kb = key(b);
        return ka != kb ? ka > kb : a < b;
      });
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      const int i = order[k];
      if (k == 0 || e[i] != this->Extent.back())
      {
        this->Extent.push_back(e[i]);
        this->First.push_back(static_cast<int>(k));
      }
      this->Bricks.push_back(i);
    }
    this->First.push_back(static_cast<int>(order.size()));
    while (this->Leaves < this->Extent.size())
    {
      this->Leaves *= 2;
    }
    this->Reset();
  }

  /// Makes every brick unplaced again.
  void Reset()
  {
    this->Next.assign(this->First.begin(), this->First.end() - 1);
    this->MinX.assign(2 * this->Leaves, INT_MAX);
    this->MinY.assign(2 * this->Leaves, INT_MAX);
    for (std::size_t s = 0; s < this->Extent.size(); ++s)
    {
      this->MinX[this->Leaves + s] = this->Extent[s].x;
      this->MinY[this->Leaves + s] = this->Extent[s].y;
    }
    for (std::size_t n = this->Leaves - 1; n >= 1; --n)
    {
      this->Pull(n);
    }
  }

  /// The first shape, in shape order, with unplaced bricks that fits into a box of this size
  /// (the tallest that fits, then the largest footprint); -1 when none does.
  int Find(const glm::ivec3& box) const
  {
    // the shapes with z extent <= box.z form a suffix of the order
    const auto it = std::lower_bound(this->Extent.begin(), this->Extent.end(), box.z,
      [](const glm::ivec3& s, int z) { return s.z > z; });
    const std::size_t start = static_cast<std::size_t>(it - this->Extent.begin());
    if (start >= this->Extent.size())
    {
      return -1;
    }
    return this->Find(1, 0, this->Leaves, start, box.x, box.y);
  }

  const glm::ivec3& ShapeExtent(int shape) const { return this->Extent[shape]; }

  /// Takes the unplaced brick of smallest input index of a shape that has one.
  int Take(int shape)
  {
    const int brick = this->Bricks[this->Next[shape]++];
    if (this->Next[shape] == this->First[shape + 1])
    {
      std::size_t n = this->Leaves + shape;
      this->MinX[n] = INT_MAX;
      this->MinY[n] = INT_MAX;
      for (n /= 2; n >= 1; n /= 2)
      {
        this->Pull(n);
      }
    }
    return brick;
  }

private:
  void Pull(std::size_t n)
  {
    this->MinX[n] = std::min(this->MinX[2 * n], this->MinX[2 * n + 1]);
    this->MinY[n] = std::min(this->MinY[2 * n], this->MinY[2 * n + 1]);
  }

  /// Leftmost leaf in [max(lo, start), hi) under `node` whose shape fits x by y.
  int Find(std::size_t node, std::size_t lo, std::size_t hi, std::size_t start, int x, int y) const
  {
    if (hi <= start || this->MinX[node] > x || this->MinY[node] > y)
    {
      return -1;
    }
    if (hi - lo == 1)
    {
      return static_cast<int>(lo); // a leaf: its own extents passed the test above
    }
    const std::size_t mid = (lo + hi) / 2;
    const int left = this->Find(2 * node, lo, mid, start, x, y);
    return left >= 0 ? left : this->Find(2 * node + 1, mid, hi, start, x, y);
  }

  std::vector<glm::ivec3> Extent; // per shape
  std::vector<int> First;         // per shape: its first entry in Bricks; one extra at the end
  std::vector<int> Next;          // per shape: its next unplaced entry in Bricks
  std::vector<int> Bricks;        // brick indices grouped by shape, increasing within a shape
  std::size_t Leaves = 1;         // segment tree leaves: a power of two >= number of shapes
  std::vector<int> MinX, MinY;    // segment tree; node 1 is the root, shape s is leaf Leaves + s
};

/// A free box of a trial. The free boxes of a trial are pairwise disjoint and disjoint from the
/// placed bricks. They are consumed in bottom-left order: by z, then y, then x of the lower
/// corner (disjoint boxes have distinct lower corners, so the corner alone is the key).
struct FreeBox
{
  uint64_t Key;
  glm::ivec3 Size;
  bool operator<(const FreeBox& o) const { return this->Key > o.Key; } // std heap: min Key on top

  static uint64_t MakeKey(const glm::ivec3& lo)
  {
    return (static_cast<uint64_t>(lo.z) << 42) | (static_cast<uint64_t>(lo.y) << 21) |
      static_cast<uint64_t>(lo.x);
  }
  glm::ivec3 Corner() const
  {
    const uint64_t mask = (uint64_t(1) << 21) - 1;
    return glm::ivec3(static_cast<int>(this->Key & mask),
      static_cast<int>((this->Key >> 21) & mask), static_cast<int>(this->Key >> 42));
  }
};

/// One guillotine best-fit trial with container base width x depth and height limit maxZ.
/// The lowest free box (bottom-left order) receives the first shape in ShapeIndex order that
/// fits it: the tallest brick that fits, largest footprint first. A box that nothing fits is
/// given up. The brick sits at the box's lower corner and the rest of the box is cut into
/// three: the slab above the brick (the full footprint of the box), and beside the brick two
/// boxes of the brick's height, where the side with more room left gets the full box extent.
/// The first box is the whole container, so until maxZ is reached a slab above everything
/// placed so far exists and every brick finds a place.
void BestFitTrial(ShapeIndex& shapes, std::size_t count, int width, int depth, int maxZ,
  std::vector<FreeBox>& heap, Trial& t)
{
  t.Ok = false;
  t.Origins.resize(count);
  shapes.Reset();
  heap.clear();
  heap.push_back(FreeBox{ FreeBox::MakeKey(glm::ivec3(0)), glm::ivec3(width, depth, maxZ) });
  glm::ivec3 hi(0);
  std::size_t remaining = count;
  while (remaining > 0 && !heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end());
    const FreeBox box = heap.back();
    heap.pop_back();
    const int shape = shapes.Find(box.Size);
    if (shape < 0)
    {
      continue;
    }
    const glm::ivec3 b = shapes.ShapeExtent(shape);
    const glm::ivec3 lo = box.Corner();
    const glm::ivec3& s = box.Size;
    t.Origins[shapes.Take(shape)] = lo;
    --remaining;
    hi = glm::max(hi, lo + b);
    const bool yFull = (s.x - b.x) < (s.y - b.y);
    const glm::ivec3 parts[3][2] = {
      { glm::ivec3(lo.x, lo.y, lo.z + b.z), glm::ivec3(s.x, s.y, s.z - b.z) },
      { glm::ivec3(lo.x, lo.y + b.y, lo.z), glm::ivec3(yFull ? s.x : b.x, s.y - b.y, b.z) },
      { glm::ivec3(lo.x + b.x, lo.y, lo.z), glm::ivec3(s.x - b.x, yFull ? b.y : s.y, b.z) },
    };
    for (const auto& p : parts)
    {
      if (p[1].x > 0 && p[1].y > 0 && p[1].z > 0)
      {
        heap.push_back(FreeBox{ FreeBox::MakeKey(p[0]), p[1] });
        std::push_heap(heap.begin(), heap.end());
      }
    }
  }
  if (remaining > 0)
  {
    return; // the height limit was reached
  }
  t.Ok = true;
  t.Dims = hi;
  t.Texels = Volume(hi);
}

/// Evaluates candidate base extents (x: width, y: depth) with guillotine best-fit trials, on up
/// to 8 threads, and returns the best layout by Better(), ties going to the earlier candidate.
Trial RunBestFitTrials(const ShapeIndex& prototype, std::size_t count,
  const std::vector<glm::ivec2>& candidates, int maxZ)
{
  struct Worker
  {
    ShapeIndex Shapes;
    std::vector<FreeBox> Heap;
    Trial Best, Current;
    std::size_t BestIndex = 0;
  };
  const std::size_t n = candidates.size();
  if (n == 0)
  {
    return Trial{};
  }
  // a thread is worth starting for about 20,000 brick placements
  const std::size_t threads = std::min<std::size_t>(
    { static_cast<std::size_t>(WorkerCount()), 8, (n + 3) / 4, count * n / 20000 + 1 });
  std::vector<Worker> workers(threads, Worker{ prototype, {}, {}, {}, 0 });
  // worker w tries the candidates w, w + threads, ... in order (its ties go to the earlier one)
  RunWorkers(static_cast<int>(threads),
    [&](int w)
    {
      Worker& k = workers[static_cast<std::size_t>(w)];
      for (std::size_t c = static_cast<std::size_t>(w); c < n; c += threads)
      {
        BestFitTrial(k.Shapes, count, candidates[c].x, candidates[c].y, maxZ, k.Heap, k.Current);
        if (Better(k.Current, k.Best))
        {
          std::swap(k.Best, k.Current);
          k.BestIndex = c;
        }
      }
    });
  std::size_t best = 0;
  for (std::size_t w = 1; w < threads; ++w)
  {
    const Trial& a = workers[w].Best;
    const Trial& b = workers[best].Best;
    if (Better(a, b) || (!Better(b, a) && workers[w].BestIndex < workers[best].BestIndex))
    {
      best = w;
    }
  }
  return std::move(workers[best].Best);
}

/// (v[perm[0]], v[perm[1]], v[perm[2]]).
glm::ivec3 Permute(const glm::ivec3& v, const int perm[3])
{
  return glm::ivec3(v[perm[0]], v[perm[1]], v[perm[2]]);
}

/// Work limits of the extra search for small sets, in brick placements (about 10 ns each):
/// a dense grid of footprints when it costs at most DenseSearchPlacements per stacking axis, and
/// all three stacking axes when a search costs at most ThreeAxesPlacements.
constexpr int64_t DenseSearchPlacements = 300000;
constexpr int64_t ThreeAxesPlacements = 300000;
/// The two refinement stages (16 trials) run while they cost at most this many placements: at
/// the paper's dataset-3 size (39,061 bricks) they took 43 % of the packing (0.15 of 0.34 s,
/// two threads) for an atlas 0.10 % smaller (0.56 MiB of 562), and the packing runs beside the
/// kD-tree on the build's critical path.
constexpr int64_t RefinePlacements = 400000;

/// The guillotine best-fit search with atlas axis `stack` (0, 1, 2) as the stacking axis: the
/// search runs in a frame whose z is that axis; the result is in atlas coordinates.
///
/// Footprints tried (search frame): stage 1 takes areas from the smallest one that could hold
/// the bricks under the height limit upwards by factors of sqrt(2) (8 steps) at aspect ratios
/// 1/2, 1 and 2, plus the full footprint allowed by the limits (and, for small sets, every
/// footprint up to twice the side of the cube holding the bricks); stages 2 and 3 try the eight
/// neighbours of the best footprint so far, at factors of 2^(1/8), then 2^(1/32), per axis, for
/// sets small enough (RefinePlacements).
Trial SearchBestFit(const std::vector<glm::ivec3>& extents, int64_t used,
  const glm::ivec3& maxExtent, const glm::ivec3& maxDims, int stack)
{
  const int perm[3] = { stack == 0 ? 1 : 0, stack == 2 ? 1 : 2, stack };
  std::vector<glm::ivec3> permuted(extents.size());
  std::transform(extents.begin(), extents.end(), permuted.begin(),
    [&](const glm::ivec3& v) { return Permute(v, perm); });
  const glm::ivec3 lim = Permute(maxDims, perm);
  const glm::ivec3 big = Permute(maxExtent, perm);
  const ShapeIndex shapes(permuted);
  const int64_t count = static_cast<int64_t>(extents.size());

  std::vector<glm::ivec2> candidates;
  std::set<std::pair<int, int>> tried; // footprints of all stages, each tried once
  auto add = [&](double w, double d)
  {
    const glm::ivec2 c(std::min(std::max(static_cast<int>(std::lround(w)), big.x), lim.x),
      std::min(std::max(static_cast<int>(std::lround(d)), big.y), lim.y));
    if (tried.emplace(c.x, c.y).second)
    {
      candidates.push_back(c);
    }
  };
  const double minArea = std::max(double(used) / lim.z, double(big.x) * big.y);
  const double maxArea = double(lim.x) * lim.y;
  for (int k = 0; k < 8; ++k)
  {
    const double area = std::min(minArea * std::pow(2.0, 0.5 * k), maxArea);
    for (double aspect : { 0.5, 1.0, 2.0 })
    {
      const double w = std::max(1.0, std::round(std::sqrt(area / aspect)));
      add(w, std::ceil(area / w));
    }
  }
  add(lim.x, lim.y);
  const int cap = static_cast<int>(std::ceil(2.0 * std::cbrt(double(used))));
  const int64_t dense = int64_t(std::max(0, std::min(lim.x, big.x + cap) - big.x + 1)) *
    std::max(0, std::min(lim.y, big.y + cap) - big.y + 1);
  if (dense * count <= DenseSearchPlacements)
  {
    for (int w = big.x; w <= std::min(lim.x, big.x + cap); ++w)
    {
      for (int d = big.y; d <= std::min(lim.y, big.y + cap); ++d)
      {
        add(w, d);
      }
    }
  }
  Trial best = RunBestFitTrials(shapes, extents.size(), candidates, lim.z);
  const bool refine = count * 16 <= RefinePlacements;
  for (double step : { 0.125, 0.03125 })
  {
    if (!best.Ok || !refine)
    {
      break;
    }
    const glm::dvec2 center(best.Dims.x, best.Dims.y);
    candidates.clear();
    for (int i = -1; i <= 1; ++i)
    {
      for (int j = -1; j <= 1; ++j)
      {
        if (i != 0 || j != 0)
        {
          add(center.x * std::pow(2.0, step * i), center.y * std::pow(2.0, step * j));
        }
      }
    }
    Trial refined = RunBestFitTrials(shapes, extents.size(), candidates, lim.z);
    if (Better(refined, best))
    {
      best = std::move(refined);
    }
  }
  if (best.Ok)
  { // back to atlas coordinates
    glm::ivec3 dims;
    for (int k = 0; k < 3; ++k)
    {
      dims[perm[k]] = best.Dims[k];
    }
    best.Dims = dims;
    for (glm::ivec3& o : best.Origins)
    {
      const glm::ivec3 p = o;
      for (int k = 0; k < 3; ++k)
      {
        o[perm[k]] = p[k];
      }
    }
  }
  return best;
}

/// The guillotine best-fit packer. The stacking axis is the axis with the largest limit (z on a
/// tie, then x): the taller the atlas may grow, the smaller its footprint and the less space the
/// last, partly filled layer wastes. Small sets also try the other two axes.
Trial PackBestFit(const std::vector<glm::ivec3>& extents, int64_t used, const glm::ivec3& maxExtent,
  const glm::ivec3& maxDims)
{
  int first = 2;
  if (maxDims.x > maxDims.z || maxDims.y > maxDims.z)
  {
    first = maxDims.x >= maxDims.y ? 0 : 1;
  }
  Trial best = SearchBestFit(extents, used, maxExtent, maxDims, first);
  // a search without the dense grid runs about 60 trials
  if (static_cast<int64_t>(extents.size()) * 60 <= ThreeAxesPlacements)
  {
    for (int axis : { 2, 0, 1 })
    {
      if (axis != first)
      {
        Trial t = SearchBestFit(extents, used, maxExtent, maxDims, axis);
        if (Better(t, best))
        {
          best = std::move(t);
        }
      }
    }
  }
  return best;
}

} // namespace

//--------------------------------------------------------------------------------------------------
AtlasLayout PackBricks(const std::vector<glm::ivec3>& extents, Packer packer,
  const glm::ivec3& maxDims, int64_t maxTexels)
{
  const auto start = std::chrono::steady_clock::now();
  if (maxDims.x < 1 || maxDims.y < 1 || maxDims.z < 1 || maxDims.x >= (1 << 21) ||
    maxDims.y >= (1 << 21) || maxDims.z >= (1 << 21))
  {
    throw std::invalid_argument(
      "PackBricks: maxDims must lie in [1, 2^21) on every axis, got " + DimsString(maxDims));
  }
  if (maxTexels < 0)
  {
    throw std::invalid_argument("PackBricks: maxTexels must be >= 0 (0 = no budget)");
  }

  AtlasLayout layout;
  layout.PackerName = packer == Packer::Best ? "guillotine-bestfit" : "nfdh";
  glm::ivec3 maxExtent(0);
  std::size_t tooLarge = 0, firstTooLarge = 0;
  for (std::size_t i = 0; i < extents.size(); ++i)
  {
    const glm::ivec3& b = extents[i];
    if (b.x < 1 || b.y < 1 || b.z < 1)
    {
      throw std::invalid_argument("PackBricks: brick " + std::to_string(i) + " has extent " +
        DimsString(b) + "; every extent must be >= 1");
    }
    if (b.x > maxDims.x || b.y > maxDims.y || b.z > maxDims.z)
    {
      firstTooLarge = tooLarge == 0 ? i : firstTooLarge;
      ++tooLarge;
    }
    maxExtent = glm::max(maxExtent, b);
    layout.UsedTexels += Volume(b);
  }
  if (tooLarge > 0)
  {
    throw PackingError("cannot pack the bricks into one 3D texture: " + std::to_string(tooLarge) +
      " brick(s) exceed the per-axis texture limit of " + DimsString(maxDims) +
      " texels; the first is brick " + std::to_string(firstTooLarge) + " of " +
      DimsString(extents[firstTooLarge]) +
      " texels (largest extents over all bricks: " + DimsString(maxExtent) + "). " + Advice);
  }
  const int64_t axisLimit = Volume(maxDims);
  const bool budgetBinds = maxTexels > 0 && maxTexels < axisLimit;
  const int64_t budget = budgetBinds ? maxTexels : axisLimit;
  if (layout.UsedTexels > budget)
  {
    std::ostringstream msg;
    msg << "cannot pack the bricks into one 3D texture: " << extents.size() << " bricks hold "
        << layout.UsedTexels << " texels, " << layout.UsedTexels - budget << " texels ("
        << 100.0 * double(layout.UsedTexels - budget) / double(budget) << "%) more than the "
        << (budgetBinds ? "texel budget of " : "per-axis texture limit allows, ") << budget
        << " texels";
    if (!budgetBinds)
    {
      msg << " (" << DimsString(maxDims) << ")";
    }
    msg << ", even at 100% packing efficiency. " << Advice;
    throw PackingError(msg.str());
  }
  if (extents.empty())
  {
    layout.Efficiency = 1.0;
    layout.Seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return layout;
  }

  Trial best = packer == Packer::Best ? PackBestFit(extents, layout.UsedTexels, maxExtent, maxDims)
                                      : PackNfdh(extents, maxExtent, maxDims);

  if (!best.Ok || (maxTexels > 0 && best.Texels > maxTexels))
  {
    std::ostringstream msg;
    msg << "cannot pack " << extents.size() << " bricks (" << layout.UsedTexels
        << " texels) into one 3D texture with the " << layout.PackerName << " packer: ";
    if (!best.Ok)
    {
      msg << "no layout found stays within the per-axis texture limit of " << DimsString(maxDims)
          << " texels (the bricks alone would fill "
          << 100.0 * double(layout.UsedTexels) / double(axisLimit) << "% of it). ";
    }
    else
    {
      msg << "the smallest layout found, " << DimsString(best.Dims) << " = " << best.Texels
          << " texels (" << 100.0 * double(layout.UsedTexels) / double(best.Texels)
          << "% efficient), exceeds the texel budget of " << maxTexels << " by "
          << best.Texels - maxTexels << " texels ("
          << 100.0 * double(best.Texels - maxTexels) / double(maxTexels) << "%). ";
    }
    msg << Advice;
    throw PackingError(msg.str());
  }

  layout.Dims = best.Dims;
  layout.Origins = std::move(best.Origins);
  layout.TotalTexels = best.Texels;
  layout.Efficiency = double(layout.UsedTexels) / double(layout.TotalTexels);
  layout.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return layout;
}

Packer ParsePacker(const std::string& name)
{
  const std::string n = LowerAscii(name);
  if (n == "nfdh")
  {
    return Packer::NextFitDecreasingHeight;
  }
  if (n == "best" || n == "guillotine-bestfit")
  {
    return Packer::Best;
  }
  throw std::invalid_argument(
    "unknown packer '" + name + "'; expected 'nfdh', 'best' or 'guillotine-bestfit'");
}

std::string PackerName(Packer packer)
{
  return packer == Packer::Best ? "best" : "nfdh";
}

glm::ivec3 AtlasLimits(int max3DTextureSize)
{
  const int64_t m = std::max(max3DTextureSize, 1);
  return glm::ivec3(static_cast<int>(std::min<int64_t>(m, int64_t(layout::MaxOffsetX) + 1)),
    static_cast<int>(std::min<int64_t>(m, int64_t(layout::MaxOffsetY) + 1)),
    static_cast<int>(std::min<int64_t>(m, int64_t(layout::MaxOffsetZ) + 1)));
}

std::vector<glm::ivec3> BrickExtents(const Hierarchy& h, bool vertexCentred)
{
  std::vector<glm::ivec3> e;
  e.reserve(h.Grids.size());
  const int64_t add = vertexCentred ? 1 : 0;
  for (const Grid& g : h.Grids)
  {
    // saturate: an extent beyond INT_MAX is reported by PackBricks as too large
    const glm::i64vec3 c = glm::min(g.Cells.Extent() + add, glm::i64vec3(INT_MAX));
    e.emplace_back(static_cast<int>(c.x), static_cast<int>(c.y), static_cast<int>(c.z));
  }
  return e;
}

} // namespace amrsp
