// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Render.h"

#include "amrsp/EmptySpace.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/VertexData.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace amrsp
{

void Camera::Ray(int width, int height, double px, double py, glm::dvec3& origin,
  glm::dvec3& direction) const
{
  const glm::dvec3 forward = glm::normalize(FocalPoint - Position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, ViewUp));
  const glm::dvec3 up = glm::cross(right, forward);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const double x = 2.0 * px / width - 1.0;
  const double y = 2.0 * py / height - 1.0;
  if (Parallel)
  {
    origin = Position + x * ParallelScale * aspect * right + y * ParallelScale * up;
    direction = forward;
    return;
  }
  const double h = std::tan(glm::radians(ViewAngle) * 0.5);
  origin = Position;
  direction = glm::normalize(forward + x * h * aspect * right + y * h * up);
}

Camera Camera::ResetTo(const glm::dvec3& lo, const glm::dvec3& hi)
{
  Camera c;
  c.FocalPoint = 0.5 * (lo + hi);
  double radius = 0.5 * glm::length(hi - lo);
  radius = radius > 0.0 ? radius : 1.0;
  const double distance = radius / std::sin(glm::radians(c.ViewAngle) * 0.5);
  c.Position = c.FocalPoint + glm::dvec3(0.0, 0.0, distance);
  c.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  c.ParallelScale = radius;
  return c;
}

namespace
{
/// Rotation of `v` by `degrees` about the unit `axis` (right-handed, as vtkTransform::RotateWXYZ).
glm::dvec3 Rotate(const glm::dvec3& v, const glm::dvec3& axis, double degrees)
{
  const double a = glm::radians(degrees);
  const glm::dvec3 k = glm::normalize(axis);
  return v * std::cos(a) + glm::cross(k, v) * std::sin(a) + k * glm::dot(k, v) * (1.0 - std::cos(a));
}
} // namespace

void Camera::Azimuth(double degrees)
{
  Position = FocalPoint + Rotate(Position - FocalPoint, ViewUp, degrees);
}

void Camera::Elevation(double degrees)
{
  const glm::dvec3 right = glm::normalize(glm::cross(FocalPoint - Position, ViewUp));
  Position = FocalPoint + Rotate(Position - FocalPoint, -right, degrees);
}

void Camera::OrthogonalizeViewUp()
{
  const glm::dvec3 forward = glm::normalize(FocalPoint - Position);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, ViewUp));
  ViewUp = glm::cross(right, forward);
}

void Camera::Zoom(double factor)
{
  if (factor <= 0.0)
  {
    return;
  }
  if (Parallel)
  {
    ParallelScale /= factor;
  }
  else
  {
    ViewAngle /= factor;
  }
}

namespace
{
template <typename Point, typename Value, typename Get>
Value Interpolate(const std::vector<Point>& points, double s, Value fallback, Get get)
{
  if (points.empty())
  {
    return fallback;
  }
  if (s <= points.front().X)
  {
    return get(points.front());
  }
  if (s >= points.back().X)
  {
    return get(points.back());
  }
  const auto upper = std::upper_bound(points.begin(), points.end(), s,
    [](double v, const Point& p) { return v < p.X; });
  const Point& b = *upper;
  const Point& a = *(upper - 1);
  const double w = b.X > a.X ? (s - a.X) / (b.X - a.X) : 0.0;
  return get(a) * (1.0 - w) + get(b) * w;
}
} // namespace

glm::dvec3 TransferFunction::EvaluateColor(double s) const
{
  return Interpolate(
    Color, s, glm::dvec3(1.0), [](const ColorPoint& p) { return p.Rgb; });
}

double TransferFunction::EvaluateOpacity(double s) const
{
  return Interpolate(Opacity, s, 0.0, [](const OpacityPoint& p) { return p.Opacity; });
}

std::vector<std::string> TransferFunction::PresetNames()
{
  return { "default", "grey", "hot", "grey-opaque", "sparse" };
}

TransferFunction TransferFunction::Preset(const std::string& name, double lo, double hi,
  double unitDistance)
{
  if (!(hi > lo))
  {
    hi = lo + 1.0;
  }
  const auto at = [&](double f) { return lo + f * (hi - lo); };
  TransferFunction tf;
  tf.UnitDistance = unitDistance;
  if (name == "default")
  {
    // cool-to-warm colours; opacity rising with the value so that peaks stand out
    tf.Color = { { at(0.0), { 0.23, 0.30, 0.75 } }, { at(0.5), { 0.87, 0.87, 0.87 } },
      { at(1.0), { 0.71, 0.02, 0.15 } } };
    tf.Opacity = { { at(0.0), 0.0 }, { at(0.3), 0.05 }, { at(0.7), 0.4 }, { at(1.0), 0.9 } };
  }
  else if (name == "grey")
  {
    tf.Color = { { at(0.0), { 0.0, 0.0, 0.0 } }, { at(1.0), { 1.0, 1.0, 1.0 } } };
    tf.Opacity = { { at(0.0), 0.0 }, { at(1.0), 0.5 } };
  }
  else if (name == "hot")
  {
    tf.Color = { { at(0.0), { 0.0, 0.0, 0.0 } }, { at(0.4), { 0.9, 0.0, 0.0 } },
      { at(0.8), { 1.0, 0.9, 0.0 } }, { at(1.0), { 1.0, 1.0, 1.0 } } };
    tf.Opacity = { { at(0.0), 0.0 }, { at(0.3), 0.05 }, { at(1.0), 0.8 } };
  }
  else if (name == "grey-opaque")
  {
    // for maximum/minimum/average intensity: the kept scalar as a grey level
    tf.Color = { { at(0.0), { 0.0, 0.0, 0.0 } }, { at(1.0), { 1.0, 1.0, 1.0 } } };
    tf.Opacity = { { at(0.0), 1.0 }, { at(1.0), 1.0 } };
  }
  else if (name == "sparse")
  {
    // the "hot" colours, transparent below 60 % of the range: most of the data is empty space
    tf.Color = { { at(0.0), { 0.0, 0.0, 0.0 } }, { at(0.6), { 0.9, 0.0, 0.0 } },
      { at(0.85), { 1.0, 0.9, 0.0 } }, { at(1.0), { 1.0, 1.0, 1.0 } } };
    tf.Opacity = { { at(0.0), 0.0 }, { at(0.6), 0.0 }, { at(0.7), 0.1 }, { at(1.0), 0.9 } };
  }
  else
  {
    throw std::invalid_argument("unknown transfer-function preset '" + name +
      "' (known: default, grey, hot, grey-opaque, sparse)");
  }
  return tf;
}

std::vector<std::uint8_t> Image::Rgb8() const
{
  std::vector<std::uint8_t> out(Pixels.size() * 3);
  for (std::size_t i = 0; i < Pixels.size(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const float v = std::min(1.0f, std::max(0.0f, Pixels[i][c]));
      out[3 * i + c] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  }
  return out;
}

double Rmse8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    throw std::invalid_argument("images of different sizes cannot be compared");
  }
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
    sum += d * d;
  }
  return std::sqrt(sum / static_cast<double>(a.size()));
}

double Rmse(const Image& a, const Image& b)
{
  return Rmse8(a.Rgb8(), b.Rgb8());
}

FinestCellLocator::FinestCellLocator(const Hierarchy& h)
  : H(h)
{
  const int levels = h.NumberOfLevels();
  Levels.resize(levels);
  for (int l = 0; l < levels; ++l)
  {
    CumRatio.push_back(glm::dvec3(h.CumulativeRatio(l)));
  }
  std::vector<std::vector<int32_t>> perLevel(levels);
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    perLevel[h.Grids[g].Level].push_back(static_cast<int32_t>(g));
  }
  for (int l = 0; l < levels; ++l)
  {
    LevelBuckets& b = Levels[l];
    if (perLevel[l].empty())
    {
      continue;
    }
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (int32_t g : perLevel[l])
    {
      lo = glm::min(lo, glm::dvec3(h.Grids[g].Cells.Lo) / CumRatio[l]);
      hi = glm::max(hi, glm::dvec3(h.Grids[g].Cells.Hi) / CumRatio[l]);
    }
    const int n = std::max(1,
      std::min(64, static_cast<int>(std::cbrt(static_cast<double>(perLevel[l].size())) * 2.0)));
    b.Lo = lo;
    b.Count = glm::ivec3(n);
    b.BucketSize = (hi - lo) / glm::dvec3(n);
    b.Grids.resize(static_cast<std::size_t>(n) * n * n);
    for (int32_t g : perLevel[l])
    {
      const glm::dvec3 glo = glm::dvec3(h.Grids[g].Cells.Lo) / CumRatio[l];
      const glm::dvec3 ghi = glm::dvec3(h.Grids[g].Cells.Hi) / CumRatio[l];
      const glm::ivec3 a =
        glm::clamp(glm::ivec3(glm::floor((glo - lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
      const glm::ivec3 z =
        glm::clamp(glm::ivec3(glm::floor((ghi - lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
      for (int k = a.z; k <= z.z; ++k)
      {
        for (int j = a.y; j <= z.y; ++j)
        {
          for (int i = a.x; i <= z.x; ++i)
          {
            b.Grids[(static_cast<std::size_t>(k) * n + j) * n + i].push_back(g);
          }
        }
      }
    }
  }
}

int32_t FinestCellLocator::Find(const glm::dvec3& p, glm::i64vec3& cell) const
{
  for (int l = static_cast<int>(Levels.size()) - 1; l >= 0; --l)
  {
    const LevelBuckets& b = Levels[l];
    if (b.Grids.empty())
    {
      continue;
    }
    const glm::ivec3 bucket =
      glm::clamp(glm::ivec3(glm::floor((p - b.Lo) / b.BucketSize)), glm::ivec3(0), b.Count - 1);
    const glm::i64vec3 c = glm::i64vec3(glm::floor(p * CumRatio[l]));
    for (int32_t g : b.Grids[(static_cast<std::size_t>(bucket.z) * b.Count.y + bucket.y) *
             b.Count.x +
           bucket.x])
    {
      const Box& box = H.Grids[g].Cells;
      if (c.x >= box.Lo.x && c.y >= box.Lo.y && c.z >= box.Lo.z && c.x < box.Hi.x &&
        c.y < box.Hi.y && c.z < box.Hi.z)
      {
        cell = c;
        return g;
      }
    }
  }
  return -1;
}

float CellValue(const Hierarchy& h, int32_t g, glm::i64vec3 cell)
{
  const Box& box = h.Grids[g].Cells;
  cell = glm::clamp(cell, box.Lo, box.Hi - glm::i64vec3(1)) - box.Lo;
  const glm::i64vec3 e = box.Extent();
  return h.Values[g][static_cast<std::size_t>((cell.z * e.y + cell.y) * e.x + cell.x)];
}

namespace
{

void ForEachRow(int height, int threads, const std::function<void(int)>& row)
{
  int n = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  n = std::max(1, std::min(n, height));
  std::vector<std::thread> pool;
  for (int t = 0; t < n; ++t)
  {
    pool.emplace_back([&, t]() {
      for (int j = t; j < height; j += n)
      {
        row(j);
      }
    });
  }
  for (std::thread& th : pool)
  {
    th.join();
  }
}

/// Front-to-back accumulation of one ray, in the precision `T` of the integrator.
template <typename T>
struct Accumulator
{
  explicit Accumulator(BlendMode mode)
    : Mode(mode)
  {
  }

  BlendMode Mode;
  glm::tvec3<T, glm::defaultp> Color{ 0 };
  T Alpha = 0;
  // maximum/minimum/average intensity: the scalar kept, or the length-weighted sum and length
  double Extremum = std::numeric_limits<double>::quiet_NaN();
  double Sum = 0.0;
  double Length = 0.0;

  /// Early ray termination: composite rays stop once their opacity reaches `threshold` (< 1).
  bool Done(double threshold) const
  {
    return Mode == BlendMode::Composite && threshold < 1.0 &&
      static_cast<double>(Alpha) >= threshold;
  }

  /// `shade`, when given, turns the transfer function's colour into the lit colour.
  void Add(const TransferFunction& tf, double scalar, double dt,
    const std::function<glm::dvec3(const glm::dvec3&)>* shade = nullptr)
  {
    if (std::isnan(scalar))
    {
      return; // missing data is transparent
    }
    switch (Mode)
    {
      case BlendMode::Maximum:
        Extremum = std::isnan(Extremum) ? scalar : std::max(Extremum, scalar);
        return;
      case BlendMode::Minimum:
        Extremum = std::isnan(Extremum) ? scalar : std::min(Extremum, scalar);
        return;
      case BlendMode::Average:
        Sum += scalar * dt;
        Length += dt;
        return;
      case BlendMode::Composite:
        break;
      case BlendMode::IsoSurface:
        return; // IsoSurfaceTracker composites the crossings
    }
    const T opacity = static_cast<T>(tf.EvaluateOpacity(scalar));
    if (opacity <= T(0))
    {
      return;
    }
    const T a = T(1) -
      std::pow(T(1) - std::min(opacity, T(1)), static_cast<T>(dt / tf.UnitDistance));
    const glm::tvec3<T, glm::defaultp> c(
      shade ? (*shade)(tf.EvaluateColor(scalar)) : tf.EvaluateColor(scalar));
    Color += (T(1) - Alpha) * a * c;
    Alpha += (T(1) - Alpha) * a;
  }

  glm::vec4 Pixel(const TransferFunction& tf, const glm::dvec3& background)
  {
    if (Mode != BlendMode::Composite && Mode != BlendMode::IsoSurface)
    {
      // the kept scalar through the transfer function, without opacity correction
      const double s = Mode == BlendMode::Average ? (Length > 0.0 ? Sum / Length : NAN) : Extremum;
      if (!std::isnan(s))
      {
        Alpha = static_cast<T>(std::min(1.0, tf.EvaluateOpacity(s)));
        Color = glm::tvec3<T, glm::defaultp>(tf.EvaluateColor(s)) * Alpha;
      }
    }
    const glm::dvec3 rgb = glm::dvec3(Color) + (1.0 - static_cast<double>(Alpha)) * background;
    return glm::vec4(glm::vec3(rgb), static_cast<float>(Alpha));
  }
};

void RequireValues(const Hierarchy& h)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("the hierarchy has no scalar values to render");
  }
}

/// Value of grid `g` at `p` (level-0 index units): nearest cell for cell-centred data,
/// trilinear between vertices for vertex-centred data.
float SampleGrid(const Hierarchy& h, int32_t g, const glm::dvec3& p, const glm::dvec3& ratio)
{
  if (h.VertexCentred)
  {
    return InterpolateVertices(h, g, p * ratio - glm::dvec3(h.Grids[g].Cells.Lo));
  }
  return CellValue(h, g, glm::i64vec3(glm::floor(p * ratio)));
}

/// Trilinear lookup in the atlas at texel coordinate `u` (texel i at u = i), with the eight
/// texels clamped into [lo, hi]: the vertex texels of one kD node.
float AtlasTrilinear(const BrickAtlas& atlas, const glm::vec3& u, const glm::ivec3& lo,
  const glm::ivec3& hi)
{
  const glm::vec3 c = glm::clamp(u, glm::vec3(lo), glm::vec3(hi));
  const glm::ivec3 base = glm::min(glm::ivec3(glm::floor(c)), glm::max(hi - 1, lo));
  const glm::vec3 w = c - glm::vec3(base);
  float sum = 0.0f;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float weight =
      (o.x ? w.x : 1.0f - w.x) * (o.y ? w.y : 1.0f - w.y) * (o.z ? w.z : 1.0f - w.z);
    if (weight != 0.0f)
    {
      sum += weight * atlas.At(glm::min(base + o, hi));
    }
  }
  return sum;
}

/// Point location in the encoded tree, as the shader's amrspLocateDataNode: from the root to the
/// leaf containing p (level-0 index units); a point on a split plane goes to the upper side (the
/// cell it starts). Returns the data index (0: empty leaf or outside the root box) and the
/// node's box, computed as the traversal computes node boxes.
uint32_t LocateDataNode(const EncodedKdTree& tree, const glm::vec3& p, glm::vec3& lo, glm::vec3& hi)
{
  using namespace layout;
  lo = tree.RootLo;
  hi = tree.RootHi;
  for (int a = 0; a < 3; ++a)
  {
    if (!(p[a] >= lo[a] && p[a] < hi[a]))
    {
      return 0;
    }
  }
  uvec2 texel = tree.Tree.Texels[0];
  for (;;)
  {
    const uint child = amrspNodeFirstChild(texel);
    if (child == 0)
    {
      break;
    }
    const int axis = static_cast<int>(amrspNodeAxis(texel));
    const uint level = amrspNodeLevel(texel);
    const float plane =
      lo[axis] + static_cast<float>(amrspNodeSplit(texel)) * tree.LevelCellSize[level][axis];
    if (p[axis] < plane)
    {
      hi[axis] = plane;
      texel = tree.Tree.Texels[child];
    }
    else
    {
      lo[axis] = plane;
      texel = tree.Tree.Texels[child + 1];
    }
  }
  return amrspNodeData(texel);
}

/// The nearest cell value of the data node `data` (box lo, hi) at p: from the grid, or from the
/// atlas through the node's offset as the packing shader reads it.
float NodeCellValue(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  uint32_t data, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& p)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  const glm::vec3 cellSize = tree.LevelCellSize[amrspDataLevel(dn)];
  if (atlas)
  {
    const glm::ivec3 first = glm::ivec3(glm::floor(lo / cellSize));
    const glm::ivec3 last = glm::ivec3(glm::ceil(hi / cellSize)) - 1;
    const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(p / cellSize)), first, last);
    return atlas->At(amrspDataOffset(dn) + cell - first);
  }
  return CellValue(
    h, static_cast<int32_t>(amrspDataBrick(dn)), glm::i64vec3(glm::floor(p / cellSize)));
}

/// Whether `cell` (cells of the grid's level) is one of grid g's cells, covered or not.
bool GridHasCell(const Hierarchy& h, int32_t g, const glm::i64vec3& cell)
{
  const Box& box = h.Grids[g].Cells;
  return glm::all(glm::greaterThanEqual(cell, box.Lo)) && glm::all(glm::lessThan(cell, box.Hi));
}

/// Cell `cell` (any cell of the data node's grid, cells of its level) read through the data node
/// (box lo, hi): from the grid, or from the atlas at the node's offset + (cell - first cell), as
/// the shader's amrspFetchGridCell reads it.
float NodeGridCell(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  uint32_t data, const glm::vec3& lo, const glm::ivec3& cell)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  if (atlas)
  {
    const glm::ivec3 first =
      glm::ivec3(glm::floor(lo / tree.LevelCellSize[amrspDataLevel(dn)]));
    return atlas->At(amrspDataOffset(dn) + cell - first);
  }
  return CellValue(h, static_cast<int32_t>(amrspDataBrick(dn)), glm::i64vec3(cell));
}

/// The trilinear weight of dual-cell corner o at fractional position w.
template <typename V>
typename V::value_type CornerWeight(const V& o, const V& w)
{
  using T = typename V::value_type;
  return (o.x > T(0) ? w.x : T(1) - w.x) * (o.y > T(0) ? w.y : T(1) - w.y) *
    (o.z > T(0) ? w.z : T(1) - w.z);
}

/// Trilinear interpolation at p in the dual cell of cells of size `cellSize` (cell c centred at
/// (c + 0.5) * cellSize): the sum over its 8 corners o of CornerWeight(o, w) * value(base + o),
/// base the corner cell with the lowest index (as floating-point integers).
template <typename V, typename F>
typename V::value_type DualCellInterpolate(const V& p, const V& cellSize, F value)
{
  using T = typename V::value_type;
  const V q = p / cellSize - T(0.5);
  const V base = glm::floor(q);
  const V w = q - base;
  T sum = T(0);
  for (int corner = 0; corner < 8; ++corner)
  {
    const V o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    sum += CornerWeight(o, w) * value(base + o);
  }
  return sum;
}

/// A corner of the smooth reconstruction's dual cell that is no cell of the sample's grid: x, a
/// cell centre of level `level`. The leaf containing x, of level m: for m >= level its nearest
/// cell at x; for a coarser leaf (x lies outside the sample's level) the trilinear value of
/// level m at x, its corners the cells of the leaf's grid (covered or not) or, where that grid
/// has no such cell, the nearest cell of the leaf there. `fallback` outside every leaf.
float SmoothCornerKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& x, int level, float fallback)
{
  using namespace layout;
  glm::vec3 lo, hi;
  const uint32_t data = LocateDataNode(tree, x, lo, hi);
  if (data == 0)
  {
    return fallback;
  }
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int m = static_cast<int>(amrspDataLevel(dn));
  const float vx = NodeCellValue(h, tree, atlas, data, lo, hi, x);
  if (m >= level)
  {
    return vx;
  }
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  const glm::vec3 cellSize = tree.LevelCellSize[m];
  return DualCellInterpolate(x, cellSize, [&](const glm::vec3& c) {
    const glm::ivec3 cell = glm::ivec3(c);
    if (GridHasCell(h, g, glm::i64vec3(cell)))
    {
      return NodeGridCell(h, tree, atlas, data, lo, cell);
    }
    const glm::vec3 y = (c + 0.5f) * cellSize;
    glm::vec3 ylo, yhi;
    const uint32_t ydata = LocateDataNode(tree, y, ylo, yhi);
    return ydata != 0 ? NodeCellValue(h, tree, atlas, ydata, ylo, yhi, y) : vx;
  });
}

/// Smooth reconstruction (RenderSettings::SmoothCellData) at p for a sample of the data node
/// `data` (box lo, hi): trilinear in the dual cell of the node's level around p; a corner that is
/// a cell of the node's grid (covered by finer grids or not) takes that cell's value, any other
/// corner SmoothCornerKdTree's. Linear-exact across level boundaries where every grid's cells,
/// covered ones included, hold the field at their centres (see README, "Smooth cells").
float SmoothKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& p, uint32_t data, const glm::vec3& lo, float fallback)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int level = static_cast<int>(amrspDataLevel(dn));
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  const glm::vec3 cellSize = tree.LevelCellSize[level];
  return DualCellInterpolate(p, cellSize, [&](const glm::vec3& c) {
    const glm::ivec3 cell = glm::ivec3(c);
    return GridHasCell(h, g, glm::i64vec3(cell))
      ? NodeGridCell(h, tree, atlas, data, lo, cell)
      : SmoothCornerKdTree(h, tree, atlas, (c + 0.5f) * cellSize, level, fallback);
  });
}

/// The cell-centred value the kD-tree integrator samples at p: point location, then the leaf's
/// nearest cell or, with `smooth`, the smooth reconstruction at the leaf's data level (the rule of
/// the sample loop). NaN outside every leaf with data; cellSize: the leaf's data-level cell size.
float SampleCellsKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& p, bool smooth, glm::vec3& cellSize)
{
  using namespace layout;
  glm::vec3 lo, hi;
  const uint32_t data = LocateDataNode(tree, p, lo, hi);
  if (data == 0)
  {
    return std::numeric_limits<float>::quiet_NaN();
  }
  const int level = static_cast<int>(amrspDataLevel(tree.DataNodes.Texels[data]));
  cellSize = tree.LevelCellSize[level];
  const float v = NodeCellValue(h, tree, atlas, data, lo, hi, p);
  return smooth ? SmoothKdTree(h, tree, atlas, p, data, lo, v) : v;
}

/// Per-row counters added to RenderSettings::Stats under a lock.
struct StatsSink
{
  RenderStats* Target = nullptr;
  std::mutex Lock;

  void Add(const RenderStats& r)
  {
    if (!Target)
    {
      return;
    }
    std::lock_guard<std::mutex> guard(Lock);
    Target->Rays += r.Rays;
    Target->Samples += r.Samples;
    Target->DataSegments += r.DataSegments;
    Target->SkippedSegments += r.SkippedSegments;
    Target->SkippedSamples += r.SkippedSamples;
    Target->TerminatedRays += r.TerminatedRays;
    Target->Segments += r.Segments;
    Target->DescentLevels += r.DescentLevels;
  }
};

double MinEdge(const glm::dvec3& v)
{
  return std::min(v.x, std::min(v.y, v.z));
}

/// The iso-values sorted ascending; throws for too many.
std::vector<double> SortedIsoValues(const RenderSettings& s)
{
  if (s.Blend == BlendMode::IsoSurface &&
    (s.IsoValues.empty() || s.IsoValues.size() > static_cast<std::size_t>(MaxIsoValues)))
  {
    throw std::invalid_argument("iso-surface blending needs 1 to " +
      std::to_string(MaxIsoValues) + " iso-values");
  }
  if (s.Light.Shadows && !(s.Light.ShadowStep > 0.0))
  {
    throw std::invalid_argument("shadow rays need a positive step (Lighting::ShadowStep)");
  }
  std::vector<double> v = s.IsoValues;
  std::sort(v.begin(), v.end());
  return v;
}

bool OutsideBox(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
  return p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x >= hi.x || p.y >= hi.y || p.z >= hi.z;
}

} // namespace

double SampleKdTreeAtPoint(const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p,
  glm::vec3& cellSize)
{
  using namespace layout;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (OutsideBox(glm::dvec3(p), glm::dvec3(tree.RootLo), glm::dvec3(tree.RootHi)))
  {
    return nan;
  }
  glm::vec3 lo = tree.RootLo;
  uvec2 texel = tree.Tree.Texels[0];
  for (;;)
  {
    const uint child = amrspNodeFirstChild(texel);
    if (child == 0u)
    {
      break;
    }
    const int axis = static_cast<int>(amrspNodeAxis(texel));
    const uint level = amrspNodeLevel(texel);
    const float plane =
      lo[axis] + static_cast<float>(amrspNodeSplit(texel)) * tree.LevelCellSize[level][axis];
    uint node = child;
    if (!(p[axis] < plane))
    {
      lo[axis] = plane;
      node = child + 1u;
    }
    texel = tree.Tree.Texels[node];
  }
  const uint data = amrspNodeData(texel);
  if (data == 0u)
  {
    return nan;
  }
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  cellSize = tree.LevelCellSize[amrspDataLevel(dn)];
  if (h.VertexCentred)
  {
    return InterpolateVertices(h, g, glm::dvec3(p / cellSize) - glm::dvec3(h.Grids[g].Cells.Lo));
  }
  return CellValue(h, g, glm::i64vec3(glm::floor(p / cellSize)));
}

void SampleRayKdTree(const Hierarchy& h, const EncodedKdTree& tree, const glm::dvec3& origin,
  const glm::dvec3& direction, double sampleDistanceFactor, std::vector<TreeSample>& samples)
{
  using namespace layout;
  const glm::dvec3 o = (origin - h.Origin) / h.Spacing0;
  const glm::dvec3 d = direction / h.Spacing0;
  std::vector<RaySegment> segments;
  TraverseKdTree(tree, glm::vec3(o), glm::vec3(d), 0.0f, std::numeric_limits<float>::infinity(),
    LevelOfDetail(), segments);
  for (const RaySegment& s : segments)
  {
    if (s.Data == 0)
    {
      continue;
    }
    const int32_t g = static_cast<int32_t>(amrspDataBrick(tree.DataNodes.Texels[s.Data]));
    const glm::dvec3 ratio(h.CumulativeRatio(s.Level));
    const double step = sampleDistanceFactor * MinEdge(h.Spacing0 / ratio);
    const double length = static_cast<double>(s.T1) - static_cast<double>(s.T0);
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    const double dt = length / n;
    for (int k = 0; k < n; ++k)
    {
      const double t = static_cast<double>(s.T0) + (k + 0.5) * dt;
      const glm::dvec3 p = o + t * d;
      samples.push_back(TreeSample{ p, g, glm::i64vec3(glm::floor(p * ratio)) });
    }
  }
}

bool ClipInterval(const RenderSettings& s, const glm::dvec3& wo, const glm::dvec3& wd, double& t0,
  double& t1)
{
  t0 = -std::numeric_limits<double>::infinity();
  t1 = std::numeric_limits<double>::infinity();
  if (!s.Clip)
  {
    return true;
  }
  for (int a = 0; a < 3; ++a)
  {
    if (wd[a] == 0.0)
    {
      if (wo[a] < s.ClipLo[a] || wo[a] > s.ClipHi[a])
      {
        return false;
      }
      continue;
    }
    double a0 = (s.ClipLo[a] - wo[a]) / wd[a], a1 = (s.ClipHi[a] - wo[a]) / wd[a];
    if (a0 > a1)
    {
      std::swap(a0, a1);
    }
    t0 = std::max(t0, a0);
    t1 = std::min(t1, a1);
  }
  return t0 < t1;
}

Image RenderKdTree(const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s,
  const BrickAtlas* atlas)
{
  using namespace layout;
  RequireValues(h);
  Image img;
  img.Width = s.Width;
  img.Height = s.Height;
  img.Pixels.resize(static_cast<std::size_t>(s.Width) * s.Height);
  LevelOfDetail lod;
  lod.ThresholdPixels = s.LodThresholdPixels;
  lod.Spacing0 = glm::vec3(h.Spacing0);
  if (s.View.Parallel)
  {
    lod.ParallelPixelSize = static_cast<float>(2.0 * s.View.ParallelScale / s.Height);
  }
  else
  {
    lod.PixelSizePerDistance =
      static_cast<float>(2.0 * std::tan(glm::radians(s.View.ViewAngle) * 0.5) / s.Height);
  }
  std::vector<float> stepOfLevel;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    stepOfLevel.push_back(
      static_cast<float>(s.SampleDistanceFactor * MinEdge(h.Spacing0 * h.CellSize(l))));
  }
  const glm::vec3 spacing(h.Spacing0), worldOrigin(h.Origin);
  // empty-space skipping: per data node, whether its value range is transparent under this
  // transfer function (the ranges depend on the data only)
  const bool skip = s.SkipEmptySpace && s.Blend == BlendMode::Composite;
  std::vector<char> transparent;
  if (skip)
  {
    std::vector<glm::vec2> computed;
    if (!s.DataNodeRanges)
    {
      computed = ComputeDataNodeRanges(h, tree);
    }
    const std::vector<glm::vec2>& ranges = s.DataNodeRanges ? *s.DataNodeRanges : computed;
    if (ranges.size() != static_cast<std::size_t>(tree.DataNodeCount + 1))
    {
      throw std::invalid_argument("the data-node ranges do not belong to this tree");
    }
    transparent.resize(ranges.size());
    for (std::size_t k = 0; k < ranges.size(); ++k)
    {
      transparent[k] = TransparentRange(s.Transfer, ranges[k].x, ranges[k].y) ? 1 : 0;
    }
  }
  StatsSink sink;
  sink.Target = s.Stats;
  if (s.Stats)
  {
    *s.Stats = RenderStats();
  }
  const std::vector<double> isoValues = SortedIsoValues(s);
  const bool shaded = s.Light.Shade || s.Light.Shadows;
  ShadingContext shading = MakeShadingContext(s.Light, s.Transfer, h.Origin, h.Spacing0,
    glm::dvec3(tree.RootLo), glm::dvec3(tree.RootHi), s.View.Position, s.View.FocalPoint);
  // iso-surface bisection and shadow rays read what the samples read (nearest or smooth); the
  // gradient's neighbours likewise
  const bool smoothCells = s.SmoothCellData && !h.VertexCentred;
  const PointLookup lookup =
    smoothCells ? KdTreePointLookup(h, tree, true, atlas) : KdTreePointLookup(h, tree, false);
  if (smoothCells)
  {
    shading.Neighbours = lookup;
  }

  ForEachRow(s.Height, s.Threads, [&](int j) {
    std::vector<RaySegment> segments;
    RenderStats rowStats;
    for (int i = 0; i < s.Width; ++i)
    {
      glm::dvec3 wo, wd;
      s.View.Ray(s.Width, s.Height, i + 0.5, j + 0.5, wo, wd);
      const glm::vec3 o = (glm::vec3(wo) - worldOrigin) / spacing;
      const glm::vec3 d = glm::vec3(wd) / spacing;
      segments.clear();
      float tMax = std::numeric_limits<float>::infinity();
      glm::dvec3 background = s.Background, hitColour;
      double hit = 0.0;
      if (s.Opaque && s.Opaque(wo, wd, hit, hitColour))
      {
        tMax = static_cast<float>(hit);
        background = hitColour;
      }
      double clip0, clip1;
      if (ClipInterval(s, wo, wd, clip0, clip1))
      {
        TraverseKdTree(tree, o, d, static_cast<float>(std::max(0.0, clip0)),
          static_cast<float>(std::min(static_cast<double>(tMax), clip1)), lod, segments);
      }
      rowStats.Rays += segments.empty() ? 0 : 1;
      rowStats.Segments += static_cast<long long>(segments.size());
      for (const RaySegment& seg : segments)
      {
        rowStats.DescentLevels += seg.Descent;
      }
      Accumulator<float> acc(s.Blend);
      IsoSurfaceTracker iso(shading, lookup, isoValues, -wd);
      glm::dvec3 isoColour(0.0);
      double isoAlpha = 0.0;
      for (const RaySegment& seg : segments)
      {
        if (seg.Data == 0)
        {
          iso.Break();
          continue;
        }
        if (acc.Done(s.OpacityThreshold))
        {
          break;
        }
        const uvec2 dn = tree.DataNodes.Texels[seg.Data];
        const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
        const glm::vec3 cellSize = tree.LevelCellSize[seg.Level];
        const float length = seg.T1 - seg.T0;
        const int n =
          std::max(1, static_cast<int>(std::ceil(length / stepOfLevel[seg.Level])));
        const float dt = length / static_cast<float>(n);
        ++rowStats.DataSegments;
        if (skip && transparent[seg.Data])
        {
          ++rowStats.SkippedSegments;
          rowStats.SkippedSamples += n;
          continue;
        }
        // packing path: the node's first cell sits at the data node's atlas offset; cells of
        // the node are [first, last] (clamped so float error never reaches a neighbour brick)
        const glm::ivec3 first = glm::ivec3(glm::floor(seg.NodeLo / cellSize));
        const glm::ivec3 last = glm::ivec3(glm::ceil(seg.NodeHi / cellSize)) - 1;
        const glm::ivec3 offset = amrspDataOffset(dn);
        for (int k = 0; k < n; ++k)
        {
          const float t = seg.T0 + (static_cast<float>(k) + 0.5f) * dt;
          const glm::vec3 p = o + t * d;
          float v;
          if (atlas && h.VertexCentred)
          {
            v = AtlasTrilinear(*atlas, glm::vec3(offset) + p / cellSize - glm::vec3(first), offset,
              offset + last + 1 - first);
          }
          else if (atlas)
          {
            const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(p / cellSize)), first, last);
            v = atlas->At(offset + cell - first);
          }
          else if (h.VertexCentred)
          {
            v = InterpolateVertices(
              h, g, glm::dvec3(p / cellSize) - glm::dvec3(h.Grids[g].Cells.Lo));
          }
          else
          {
            v = CellValue(h, g, glm::i64vec3(glm::floor(p / cellSize)));
          }
          if (s.SmoothCellData && !h.VertexCentred)
          {
            v = SmoothKdTree(h, tree, atlas, p, seg.Data, seg.NodeLo, v);
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
              iso.Sample(glm::dvec3(p), v, isoColour, isoAlpha);
            }
            continue;
          }
          const std::function<glm::dvec3(const glm::dvec3&)> shade = [&](const glm::dvec3& rgb) {
            return ShadeSample(shading, lookup, rgb, glm::dvec3(p), v, glm::dvec3(cellSize), -wd);
          };
          acc.Add(s.Transfer, v, dt, shaded ? &shade : nullptr);
          if (acc.Done(s.OpacityThreshold))
          {
            break;
          }
        }
      }
      rowStats.TerminatedRays += acc.Done(s.OpacityThreshold) ? 1 : 0;
      if (s.Blend == BlendMode::IsoSurface)
      {
        acc.Color = glm::vec3(isoColour);
        acc.Alpha = static_cast<float>(isoAlpha);
      }
      img.Pixels[static_cast<std::size_t>(j) * s.Width + i] = acc.Pixel(s.Transfer, background);
    }
    sink.Add(rowStats);
  });
  return img;
}

float SampleKdTreePoint(const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p,
  bool smooth)
{
  glm::vec3 ignored;
  return SampleCellsKdTree(h, tree, nullptr, p, smooth, ignored);
}

PointLookup KdTreePointLookup(const Hierarchy& h, const EncodedKdTree& tree, bool smooth,
  const BrickAtlas* atlas)
{
  if (!smooth || h.VertexCentred)
  {
    return [&h, &tree](const glm::dvec3& q, glm::dvec3& cellSize) {
      glm::vec3 size(1.0f);
      const double v = SampleKdTreeAtPoint(h, tree, glm::vec3(q), size);
      cellSize = glm::dvec3(size);
      return v;
    };
  }
  return [&h, &tree, atlas](const glm::dvec3& q, glm::dvec3& cellSize) {
    glm::vec3 size(1.0f);
    const double v = SampleCellsKdTree(h, tree, atlas, glm::vec3(q), true, size);
    cellSize = glm::dvec3(size);
    return v;
  };
}

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
  return DualCellInterpolate(x, cellSize, [&](const glm::dvec3& c) {
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
  return DualCellInterpolate(p, cellSize, [&](const glm::dvec3& c) {
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
  return [&h, &locator, lo, hi, smoothCells](const glm::dvec3& q, glm::dvec3& cellSize) {
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
    stepOfLevel.push_back(s.ReferenceSampleFactor * MinEdge(h.Spacing0 * h.CellSize(l)));
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

  StatsSink sink;
  sink.Target = s.Stats;
  if (s.Stats)
  {
    *s.Stats = RenderStats();
  }

  ForEachRow(s.Height, s.Threads, [&](int j) {
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
            const std::function<glm::dvec3(const glm::dvec3&)> shade =
              [&](const glm::dvec3& rgb) {
                return ShadeSample(shading, lookup, rgb, p, v, 1.0 / ratio, -wd);
              };
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
  });
  return img;
}

} // namespace amrsp
