// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/BrickPacking.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTreeLayout.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <climits>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>
#include <cstdio>
#include <cstdlib>

namespace amrsp
{
void SetProto(int split, int score);
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

const char* const Advice =
  "Use the bindless path (one texture per brick), a smaller array type, or level-of-detail "
  "(drop the finest levels).";

/// One trial layout: atlas dims (tight bounding box) and the origins in input order.
struct Trial
{
  bool Ok = false;
  glm::ivec3 Dims{ 0 };
  int64_t Texels = 0;
  std::vector<glm::ivec3> Origins;
};

/// Strict weak order of trial results: smaller atlas first, then the more cubic one (smaller
/// largest axis), then lexicographically smaller dims. Total over distinct dims, so the choice
/// does not depend on the order in which trials are evaluated.
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
  if (a.Dims.z != b.Dims.z)
  {
    return a.Dims.z < b.Dims.z;
  }
  if (a.Dims.y != b.Dims.y)
  {
    return a.Dims.y < b.Dims.y;
  }
  return a.Dims.x < b.Dims.x;
}

/// Increasing, distinct base extents in [lo, hi]: a geometric ladder of `steps` values from lo
/// to hi (both included) plus the `extra` values that fall inside the range.
std::vector<int> Ladder(int lo, int hi, int steps, const std::vector<int>& extra)
{
  std::vector<int> v;
  if (lo > hi)
  {
    return v;
  }
  v.push_back(lo);
  v.push_back(hi);
  const double ratio = steps > 1 ? std::pow(double(hi) / double(lo), 1.0 / (steps - 1)) : 2.0;
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
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (e[a].z != e[b].z)
    {
      return e[a].z > e[b].z;
    }
    if (e[a].y != e[b].y)
    {
      return e[a].y > e[b].y;
    }
    if (e[a].x != e[b].x)
    {
      return e[a].x > e[b].x;
    }
    return a < b;
  });
  return order;
}

/// One NFDH pass with container base width x depth (x, y); the height grows as needed. Fails
/// when the height exceeds maxZ. Precondition: width >= every x extent, depth >= every y extent.
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
    { // row full: open a new row above the largest y extent of this one
      rowY += rowD;
      x = 0;
      rowD = 0;
    }
    if (rowY + b.y > depth)
    { // layer full: open a new layer above its largest z extent
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

//--------------------------------------------------------------------------------------------------
// Guillotine best-fit packer

int g_split = 2;
int g_score = 1;

/// The bricks grouped by shape, for best-fit queries. Shapes are ordered by decreasing z extent,
/// then decreasing footprint area (x * y), then decreasing y, then decreasing x. A segment tree
/// over that order keeps, per node, the smallest x and y extents among the shapes that still
/// have unplaced bricks, which prunes the search for the first shape fitting a box.
class ShapeIndex
{
public:
  explicit ShapeIndex(const std::vector<glm::ivec3>& e)
  {
    std::vector<int> order(e.size());
    std::iota(order.begin(), order.end(), 0);
    auto key = [&](int i) {
      return std::make_tuple(e[i].z, int64_t(e[i].x) * e[i].y, e[i].y, e[i].x);
    };
    std::sort(order.begin(), order.end(), [&](int a, int b) {
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
    this->Leaves = 1;
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

  /// The first shape, in shape order, with unplaced bricks that fits into a box of this size;
  /// -1 when none does.
  int Find(const glm::ivec3& box) const
  {
    // shapes with z extent <= box.z form a suffix of the order
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
  std::size_t Leaves = 1;         // segment tree leaves (power of two >= number of shapes)
  std::vector<int> MinX, MinY;    // segment tree, node 1 is the root, leaf s at Leaves + s
};

/// A free box of a trial. Free boxes are pairwise disjoint and disjoint from the placed bricks;
/// they are consumed in bottom-left order (by z, then y, then x of the lower corner, which is
/// unique among disjoint boxes).
struct FreeBox
{
  uint64_t Key;
  glm::ivec3 Size;
  bool operator<(const FreeBox& o) const { return this->Key > o.Key; } // min-heap on Key

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
/// The lowest free box (bottom-left order) receives the first shape, in ShapeIndex order, that
/// fits it, i.e. the tallest brick that fits, widest footprint first; a box nothing fits is
/// given up. The brick sits at the box's lower corner and the rest of the box is cut into
/// three: the slab above the brick (full box footprint), and beside the brick two boxes of the
/// brick's height, where the side with more room left gets the full box extent. The first box
/// is the whole container, so the slab above everything always exists until maxZ is reached.
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
    glm::ivec3 parts[3][2];
    bool yFull = (s.x - b.x) < (s.y - b.y);
    if (g_split == 0) yFull = true;
    if (g_split == 1) yFull = false;
    if (g_split == 3 || g_split == 5)
    {
      const int64_t a1 = std::max(int64_t(s.x) * (s.y - b.y), int64_t(s.x - b.x) * b.y);
      const int64_t a2 = std::max(int64_t(b.x) * (s.y - b.y), int64_t(s.x - b.x) * s.y);
      yFull = a1 >= a2;
    }
    const bool zLast = g_split >= 4;
    const int sideZ = zLast ? s.z : b.z;
    parts[0][0] = glm::ivec3(lo.x, lo.y, lo.z + b.z);
    parts[0][1] = zLast ? glm::ivec3(b.x, b.y, s.z - b.z) : glm::ivec3(s.x, s.y, s.z - b.z);
    parts[1][0] = glm::ivec3(lo.x, lo.y + b.y, lo.z);
    parts[1][1] = glm::ivec3(yFull ? s.x : b.x, s.y - b.y, sideZ);
    parts[2][0] = glm::ivec3(lo.x + b.x, lo.y, lo.z);
    parts[2][1] = glm::ivec3(s.x - b.x, yFull ? b.y : s.y, sideZ);
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
    return; // height limit reached
  }
  t.Ok = true;
  t.Dims = hi;
  t.Texels = Volume(hi);
}

std::string Lower(std::string s)
{
  for (char& c : s)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return s;
}

} // namespace
void SetProto(int split, int score) { g_split = split; g_score = score; }

//--------------------------------------------------------------------------------------------------
AtlasLayout PackBricks(const std::vector<glm::ivec3>& extents, Packer packer,
  const glm::ivec3& maxDims, int64_t maxTexels)
{
  const auto start = std::chrono::steady_clock::now();
  if (maxDims.x < 1 || maxDims.y < 1 || maxDims.z < 1)
  {
    throw std::invalid_argument("PackBricks: maxDims must be >= 1 on every axis, got " +
      DimsString(maxDims));
  }
  if (maxDims.x >= (1 << 21) || maxDims.y >= (1 << 21) || maxDims.z >= (1 << 21))
  {
    throw std::invalid_argument("PackBricks: maxDims must be < 2^21 on every axis, got " +
      DimsString(maxDims));
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
      " texels, the first is brick " + std::to_string(firstTooLarge) + " of " +
      DimsString(extents[firstTooLarge]) + " texels (largest extent over all bricks " +
      DimsString(maxExtent) + "). " + Advice);
  }
  const int64_t axisLimit = Volume(maxDims);
  const int64_t budget = maxTexels > 0 ? std::min(maxTexels, axisLimit) : axisLimit;
  if (layout.UsedTexels > budget)
  {
    std::ostringstream msg;
    msg << "cannot pack the bricks into one 3D texture: " << extents.size() << " bricks hold "
        << layout.UsedTexels << " texels, more than the "
        << (maxTexels > 0 && maxTexels < axisLimit ? "texel budget" : "per-axis texture limit")
        << " allows (" << budget << " texels";
    if (!(maxTexels > 0 && maxTexels < axisLimit))
    {
      msg << ", " << DimsString(maxDims);
    }
    msg << ") by " << layout.UsedTexels - budget << " texels ("
        << 100.0 * double(layout.UsedTexels - budget) / double(budget) << "% over) even at 100% "
        << "packing efficiency. " << Advice;
    throw PackingError(msg.str());
  }
  if (extents.empty())
  {
    layout.Efficiency = 1.0;
    layout.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return layout;
  }

  // Base extents to try: a geometric ladder per axis from the largest brick extent to the limit,
  // refined around the side of a cube holding the bricks, plus multiples of the largest extent.
  const double side = std::cbrt(double(layout.UsedTexels));
  std::vector<int> extraX, extraY;
  for (int k = 1; k <= 16; ++k)
  {
    extraX.push_back(k * maxExtent.x);
    extraY.push_back(k * maxExtent.y);
  }
  Trial best, trial;
  if (packer == Packer::NextFitDecreasingHeight)
  {
    const std::vector<int> order = NfdhOrder(extents);
    const std::vector<int> xs = Ladder(maxExtent.x, maxDims.x, 24, extraX);
    const std::vector<int> ys = Ladder(maxExtent.y, maxDims.y, 24, extraY);
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
  }
  else
  {
    ShapeIndex shapes(extents);
    std::vector<FreeBox> heap;
    std::vector<int> sides;
    for (double f : { 0.9, 1.0, 1.1, 1.2, 1.35 })
    {
      sides.push_back(static_cast<int>(std::lround(side * f)));
    }
    std::vector<int> xs, ys;
    for (int s : sides)
    {
      xs.push_back(std::min(std::max(s, maxExtent.x), maxDims.x));
      ys.push_back(std::min(std::max(s, maxExtent.y), maxDims.y));
    }
    xs.push_back(maxDims.x);
    ys.push_back(maxDims.y);
    if (getenv("BP_WIDE")) { xs = Ladder(maxExtent.x, std::min(maxDims.x, int(side*2)), atoi(getenv("BP_WIDE")), {}); ys = Ladder(maxExtent.y, std::min(maxDims.y, int(side*2)), atoi(getenv("BP_WIDE")), {}); }
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    std::sort(ys.begin(), ys.end());
    ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
    for (int w : xs)
    {
      for (int d : ys)
      {
        BestFitTrial(shapes, extents.size(), w, d, maxDims.z, heap, trial);
        if (getenv("BP_DEBUG")) fprintf(stderr, "T %d %d %d %d %d %.4f\n", w, d, trial.Dims.x, trial.Dims.y, trial.Dims.z, trial.Ok ? double(layout.UsedTexels)/trial.Texels : 0.0);
        if (getenv("BP_DEBUG")) fprintf(stderr, "  trial %d %d ok %d dims %d %d %d eff %.3f\n", w, d, trial.Ok, trial.Dims.x, trial.Dims.y, trial.Dims.z, trial.Ok ? double(layout.UsedTexels)/trial.Texels : 0.0);
        if (Better(trial, best))
        {
          std::swap(best, trial);
        }
      }
    }
  }

  if (!best.Ok || (maxTexels > 0 && best.Texels > maxTexels))
  {
    std::ostringstream msg;
    msg << "cannot pack " << extents.size() << " bricks (" << layout.UsedTexels
        << " texels) into one 3D texture with the " << layout.PackerName << " packer: ";
    if (!best.Ok)
    {
      msg << "no layout found stays within the per-axis texture limit of " << DimsString(maxDims)
          << " texels (the bricks alone fill " << 100.0 * double(layout.UsedTexels) / double(axisLimit)
          << "% of it). ";
    }
    else
    {
      msg << "the smallest layout found, " << DimsString(best.Dims) << " = " << best.Texels
          << " texels, exceeds the texel budget of " << maxTexels << " by "
          << best.Texels - maxTexels << " texels ("
          << 100.0 * double(best.Texels - maxTexels) / double(maxTexels) << "% over). ";
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
  const std::string n = Lower(name);
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
  const int m = std::max(max3DTextureSize, 1);
  return glm::ivec3(std::min<int64_t>(m, int64_t(layout::MaxOffsetX) + 1),
    std::min<int64_t>(m, int64_t(layout::MaxOffsetY) + 1),
    std::min<int64_t>(m, int64_t(layout::MaxOffsetZ) + 1));
}

std::vector<glm::ivec3> BrickExtents(const Hierarchy& h, bool vertexCentred)
{
  std::vector<glm::ivec3> e;
  e.reserve(h.Grids.size());
  const int64_t add = vertexCentred ? 1 : 0;
  for (const Grid& g : h.Grids)
  {
    const glm::i64vec3 c = g.Cells.Extent() + add;
    e.emplace_back(static_cast<int>(std::min<int64_t>(c.x, INT_MAX)),
      static_cast<int>(std::min<int64_t>(c.y, INT_MAX)),
      static_cast<int>(std::min<int64_t>(c.z, INT_MAX)));
  }
  return e;
}

} // namespace amrsp
