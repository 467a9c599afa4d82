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
// Layer-guillotine packer

/// Free boxes of one guillotine trial. Free boxes are pairwise disjoint and disjoint from the
/// placed bricks; they are kept in bottom-left order: by z, then y, then x of their lower corner
/// (distinct for disjoint boxes, so the corner is the key).
class FreeBoxes
{
public:
  static uint64_t Key(const glm::ivec3& lo)
  {
    return (static_cast<uint64_t>(lo.z) << 42) | (static_cast<uint64_t>(lo.y) << 21) |
      static_cast<uint64_t>(lo.x);
  }
  static glm::ivec3 Corner(uint64_t key)
  {
    const uint64_t mask = (uint64_t(1) << 21) - 1;
    return glm::ivec3(static_cast<int>(key & mask), static_cast<int>((key >> 21) & mask),
      static_cast<int>(key >> 42));
  }
  std::map<uint64_t, glm::ivec3> Boxes; // corner key -> size
};

/// Answers "can any brick (of the whole set) fit into a box of this size?" exactly: the minimum z
/// extent over the bricks whose x and y extents fit, from a prefix-minimum table over the
/// distinct x and y extents. A box no brick fits is dead for good and is dropped.
class FitTable
{
public:
  explicit FitTable(const std::vector<glm::ivec3>& e)
  {
    for (const glm::ivec3& b : e)
    {
      this->Xs.push_back(b.x);
      this->Ys.push_back(b.y);
    }
    std::sort(this->Xs.begin(), this->Xs.end());
    this->Xs.erase(std::unique(this->Xs.begin(), this->Xs.end()), this->Xs.end());
    std::sort(this->Ys.begin(), this->Ys.end());
    this->Ys.erase(std::unique(this->Ys.begin(), this->Ys.end()), this->Ys.end());
    const std::size_t nx = this->Xs.size(), ny = this->Ys.size();
    this->MinZ.assign(nx * ny, INT_MAX);
    for (const glm::ivec3& b : e)
    {
      const std::size_t i = std::lower_bound(this->Xs.begin(), this->Xs.end(), b.x) - this->Xs.begin();
      const std::size_t j = std::lower_bound(this->Ys.begin(), this->Ys.end(), b.y) - this->Ys.begin();
      int& m = this->MinZ[i * ny + j];
      m = std::min(m, b.z);
    }
    for (std::size_t i = 0; i < nx; ++i)
    {
      for (std::size_t j = 0; j < ny; ++j)
      {
        int m = this->MinZ[i * ny + j];
        if (i > 0)
        {
          m = std::min(m, this->MinZ[(i - 1) * ny + j]);
        }
        if (j > 0)
        {
          m = std::min(m, this->MinZ[i * ny + j - 1]);
        }
        this->MinZ[i * ny + j] = m;
      }
    }
  }

  bool Useful(const glm::ivec3& size) const
  {
    const auto ix = std::upper_bound(this->Xs.begin(), this->Xs.end(), size.x) - this->Xs.begin();
    const auto iy = std::upper_bound(this->Ys.begin(), this->Ys.end(), size.y) - this->Ys.begin();
    if (ix == 0 || iy == 0)
    {
      return false;
    }
    return this->MinZ[static_cast<std::size_t>(ix - 1) * this->Ys.size() +
             static_cast<std::size_t>(iy - 1)] <= size.z;
  }

private:
  std::vector<int> Xs, Ys;
  std::vector<int> MinZ; // [i * Ys.size() + j]: min z extent over bricks with x <= Xs[i], y <= Ys[j]
};

/// Bricks sorted by decreasing z extent, then decreasing footprint area, then y, then x.
std::vector<int> GuillotineOrder(const std::vector<glm::ivec3>& e)
{
  std::vector<int> order(e.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (e[a].z != e[b].z)
    {
      return e[a].z > e[b].z;
    }
    const int64_t aa = int64_t(e[a].x) * e[a].y, ab = int64_t(e[b].x) * e[b].y;
    if (aa != ab)
    {
      return aa > ab;
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

/// How many free boxes a placement inspects, in bottom-left order, before it falls back to the
/// top slab (the free box above everything placed so far, which every brick fits unless the
/// height limit is reached). Bounds the work per brick; does not affect correctness.
constexpr int ScanLimit = 1 << 30;

/// One guillotine trial with container base width x depth and height limit maxZ.
/// Each brick goes to the first free box, in bottom-left order, that holds it, at that box's
/// lower corner. The rest of the box is cut into three boxes: the slab above the brick (the full
/// footprint of the box), the part behind the brick in y (full box width, brick height) and the
/// part right of the brick in x (brick depth and height). Cutting the slab above first makes the
/// first brick of every slab set its layer height, rows open along y, bricks line up along x, and
/// the space above shorter bricks stays available for later ones.
void GuillotineTrial(const std::vector<glm::ivec3>& e, const std::vector<int>& order,
  const FitTable& fit, int width, int depth, int maxZ, Trial& t)
{
  t.Ok = false;
  t.Origins.resize(e.size());
  FreeBoxes free;
  free.Boxes.emplace(FreeBoxes::Key(glm::ivec3(0)), glm::ivec3(width, depth, maxZ));
  glm::ivec3 hi(0);
  for (int i : order)
  {
    const glm::ivec3& b = e[i];
    auto chosen = free.Boxes.end();
    int scanned = 0;
    for (auto it = free.Boxes.begin(); it != free.Boxes.end() && scanned < ScanLimit;)
    {
      const glm::ivec3& s = it->second;
      if (s.x >= b.x && s.y >= b.y && s.z >= b.z)
      {
        chosen = it;
        break;
      }
      if (!fit.Useful(s))
      {
        it = free.Boxes.erase(it);
        continue;
      }
      ++it;
      ++scanned;
    }
    if (chosen == free.Boxes.end())
    {
      chosen = std::prev(free.Boxes.end()); // the top slab
      const glm::ivec3& s = chosen->second;
      if (s.x < b.x || s.y < b.y || s.z < b.z)
      {
        if (getenv("BP_DEBUG")) fprintf(stderr, "fail brick %d ext %d %d %d top %d %d %d size %d %d %d nboxes %zu\n", i, b.x,b.y,b.z, FreeBoxes::Corner(chosen->first).x, FreeBoxes::Corner(chosen->first).y, FreeBoxes::Corner(chosen->first).z, s.x,s.y,s.z, free.Boxes.size());
        return; // height limit reached
      }
    }
    const glm::ivec3 lo = FreeBoxes::Corner(chosen->first);
    const glm::ivec3 s = chosen->second;
    free.Boxes.erase(chosen);
    t.Origins[i] = lo;
    hi = glm::max(hi, lo + b);
    const glm::ivec3 parts[3][2] = {
      { glm::ivec3(lo.x, lo.y, lo.z + b.z), glm::ivec3(s.x, s.y, s.z - b.z) },
      { glm::ivec3(lo.x, lo.y + b.y, lo.z), glm::ivec3(s.x, s.y - b.y, b.z) },
      { glm::ivec3(lo.x + b.x, lo.y, lo.z), glm::ivec3(s.x - b.x, b.y, b.z) },
    };
    for (const auto& p : parts)
    {
      if (p[1].x > 0 && p[1].y > 0 && p[1].z > 0 && fit.Useful(p[1]))
      {
        free.Boxes.emplace(FreeBoxes::Key(p[0]), p[1]);
      }
    }
  }
  t.Ok = true;
  t.Dims = hi;
  t.Texels = Volume(hi);
}

int g_split = 0;
int g_score = 0;
/// Box-driven best fit (prototype).
void BestFitTrial(const std::vector<glm::ivec3>& e, int width, int depth, int maxZ, Trial& t)
{
  t.Ok = false;
  t.Origins.resize(e.size());
  // distinct shapes sorted by score desc
  std::map<std::tuple<int,int,int>, std::vector<int>> shapeMap;
  for (int i = static_cast<int>(e.size()) - 1; i >= 0; --i)
    shapeMap[std::make_tuple(e[i].x, e[i].y, e[i].z)].push_back(i);
  struct Shape { glm::ivec3 s; std::vector<int> bricks; };
  std::vector<Shape> shapes;
  for (auto& kv : shapeMap)
    shapes.push_back(Shape{ glm::ivec3(std::get<0>(kv.first), std::get<1>(kv.first), std::get<2>(kv.first)), kv.second });
  std::sort(shapes.begin(), shapes.end(), [](const Shape& a, const Shape& b) {
    int64_t va, vb;
    if (g_score == 0) { va = Volume(a.s); vb = Volume(b.s); }
    else { va = int64_t(a.s.z) << 32 | (int64_t(a.s.x) * a.s.y); vb = int64_t(b.s.z) << 32 | (int64_t(b.s.x) * b.s.y); }
    if (va != vb) return va > vb;
    return std::make_tuple(a.s.z, a.s.y, a.s.x) > std::make_tuple(b.s.z, b.s.y, b.s.x);
  });
  std::size_t remaining = e.size();
  std::map<uint64_t, glm::ivec3> boxes;
  boxes.emplace(FreeBoxes::Key(glm::ivec3(0)), glm::ivec3(width, depth, maxZ));
  glm::ivec3 hi(0);
  std::size_t firstLive = 0;
  while (remaining > 0 && !boxes.empty())
  {
    auto it = boxes.begin();
    const glm::ivec3 lo = FreeBoxes::Corner(it->first);
    const glm::ivec3 s = it->second;
    boxes.erase(it);
    while (firstLive < shapes.size() && shapes[firstLive].bricks.empty()) ++firstLive;
    int found = -1;
    for (std::size_t k = firstLive; k < shapes.size(); ++k)
    {
      const Shape& sh = shapes[k];
      if (!sh.bricks.empty() && sh.s.x <= s.x && sh.s.y <= s.y && sh.s.z <= s.z) { found = static_cast<int>(k); break; }
    }
    if (found < 0) continue;
    Shape& sh = shapes[found];
    const int i = sh.bricks.back();
    sh.bricks.pop_back();
    --remaining;
    const glm::ivec3 b = sh.s;
    t.Origins[i] = lo;
    hi = glm::max(hi, lo + b);
    glm::ivec3 parts[3][2];
    parts[0][0] = glm::ivec3(lo.x, lo.y, lo.z + b.z); parts[0][1] = glm::ivec3(s.x, s.y, s.z - b.z);
    bool yFull = g_split == 0 || (g_split == 2 && (s.x - b.x) < (s.y - b.y));
    if (yFull)
    {
      parts[1][0] = glm::ivec3(lo.x, lo.y + b.y, lo.z); parts[1][1] = glm::ivec3(s.x, s.y - b.y, b.z);
      parts[2][0] = glm::ivec3(lo.x + b.x, lo.y, lo.z); parts[2][1] = glm::ivec3(s.x - b.x, b.y, b.z);
    }
    else
    {
      parts[1][0] = glm::ivec3(lo.x, lo.y + b.y, lo.z); parts[1][1] = glm::ivec3(b.x, s.y - b.y, b.z);
      parts[2][0] = glm::ivec3(lo.x + b.x, lo.y, lo.z); parts[2][1] = glm::ivec3(s.x - b.x, s.y, b.z);
    }
    for (const auto& p : parts)
      if (p[1].x > 0 && p[1].y > 0 && p[1].z > 0)
        boxes.emplace(FreeBoxes::Key(p[0]), p[1]);
  }
  if (remaining > 0) return;
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
  layout.PackerName = packer == Packer::Best ? "layer-guillotine" : "nfdh";
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
    const std::vector<int> order = GuillotineOrder(extents);
    const FitTable fit(extents);
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
        if (getenv("BP_BF")) BestFitTrial(extents, w, d, maxDims.z, trial); else
        GuillotineTrial(extents, order, fit, w, d, maxDims.z, trial);
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
  if (n == "best" || n == "layer-guillotine")
  {
    return Packer::Best;
  }
  throw std::invalid_argument(
    "unknown packer '" + name + "'; expected 'nfdh', 'best' or 'layer-guillotine'");
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
