// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The kD-tree integrator's (KdTreeIntegrator.cxx, the shader's CPU mirror) row scheduler,
/// front-to-back accumulator of every blend mode, grid sampling, dual-cell interpolation of smooth
/// cells and work counters. Internal to the core library. The independent reference
/// (src/reference/) has its own and may not include this header (Core.ReferenceIndependence).

#include "amrsp/FinestCellLocator.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/Progress.h"
#include "amrsp/RenderSettings.h"
#include "amrsp/Shading.h"
#include "amrsp/TransferFunction.h"
#include "amrsp/VertexData.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace amrsp
{
namespace integration
{

/// row(j) for every image row j, the rows interleaved over `threads` workers (0: one per core),
/// reporting the fraction of rows done to `progress` when set.
template <class Row>
void ForEachRow(int height, int threads, const Row& row, const ProgressCallback& progress = nullptr)
{
  ProgressTicker ticker(progress, height);
  ParallelForInterleaved(
    height,
    [&row, &ticker](int64_t j)
    {
      row(static_cast<int>(j));
      ticker.Done();
    },
    threads);
  ticker.Finish();
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
    const T a =
      T(1) - std::pow(T(1) - std::min(opacity, T(1)), static_cast<T>(dt / tf.UnitDistance));
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

inline void RequireValues(const Hierarchy& h)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("the hierarchy has no scalar values to render");
  }
}

/// Value of grid `g` at `p` (level-0 index units): nearest cell for cell-centred data,
/// trilinear between vertices for vertex-centred data.
inline float SampleGrid(const Hierarchy& h, int32_t g, const glm::dvec3& p, const glm::dvec3& ratio)
{
  if (h.VertexCentred)
  {
    return InterpolateVertices(h, g, p * ratio - glm::dvec3(h.Grids[g].Cells.Lo));
  }
  return CellValue(h, g, glm::i64vec3(glm::floor(p * ratio)));
}

/// Whether `cell` (cells of the grid's level) is one of grid g's cells, covered or not.
inline bool GridHasCell(const Hierarchy& h, int32_t g, const glm::i64vec3& cell)
{
  const Box& box = h.Grids[g].Cells;
  return glm::all(glm::greaterThanEqual(cell, box.Lo)) && glm::all(glm::lessThan(cell, box.Hi));
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

/// The iso-values sorted ascending; throws for too many.
inline std::vector<double> SortedIsoValues(const RenderSettings& s)
{
  if (s.Blend == BlendMode::IsoSurface &&
    (s.IsoValues.empty() || s.IsoValues.size() > static_cast<std::size_t>(MaxIsoValues)))
  {
    throw std::invalid_argument(
      "iso-surface blending needs 1 to " + std::to_string(MaxIsoValues) + " iso-values");
  }
  if (s.Light.Shadows && !(s.Light.ShadowStep > 0.0))
  {
    throw std::invalid_argument("shadow rays need a positive step (Lighting::ShadowStep)");
  }
  std::vector<double> v = s.IsoValues;
  std::sort(v.begin(), v.end());
  return v;
}

inline bool OutsideBox(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
  return p.x < lo.x || p.y < lo.y || p.z < lo.z || p.x >= hi.x || p.y >= hi.y || p.z >= hi.z;
}

} // namespace integration
} // namespace amrsp
