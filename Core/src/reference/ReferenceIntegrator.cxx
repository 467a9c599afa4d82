// SPDX-License-Identifier: BSD-3-Clause
// The independent reference integrator: no kD-tree, the finest cell found from the grids' boxes,
// and its own rules (ReferenceRules.h). Ray marching of amrsp/Render.h's "Reference integrator".
#include "amrsp/ReferenceRender.h"

#include "ReferenceRules.h"

#include "amrsp/ParallelFor.h"
#include "amrsp/Progress.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace amrsp
{
namespace
{
using namespace reference;

constexpr double Infinity = std::numeric_limits<double>::infinity();

/// The interval [t0, t1] of the ray o + t d inside the box [lo, hi] (slab test); false: missed.
bool SlabInterval(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo,
  const glm::dvec3& hi, double& t0, double& t1)
{
  t0 = -Infinity;
  t1 = Infinity;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    const double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return true;
}

/// The sampling distance of each level: ReferenceSampleFactor x the smallest world edge of its
/// cells.
std::vector<double> StepOfLevels(const Hierarchy& h, double factor)
{
  std::vector<double> steps;
  for (int level = 0; level < h.NumberOfLevels(); ++level)
  {
    const glm::dvec3 edge = h.Spacing0 / glm::dvec3(h.CumulativeRatio(level));
    steps.push_back(factor * std::min(edge.x, std::min(edge.y, edge.z)));
  }
  return steps;
}

void CheckSettings(const Hierarchy& h, const RenderSettings& s)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("the hierarchy has no scalar values to render");
  }
  // any number of iso-values: the limit of 8 is the shader's, not the reference's
  if (s.Blend == BlendMode::IsoSurface && s.IsoValues.empty())
  {
    throw std::invalid_argument("iso-surface blending needs at least one iso-value");
  }
  if (s.Light.Shadows && !(s.Light.ShadowStep > 0.0))
  {
    throw std::invalid_argument("shadow rays need a positive step (Lighting::ShadowStep)");
  }
}

/// One ray's state for the intensity projections: the scalar kept (maximum, minimum) or the
/// length-weighted sum (average).
struct Projection
{
  bool Any = false;
  double Kept = 0.0;
  double Sum = 0.0;
  double Length = 0.0;
};

class RayMarcher
{
public:
  RayMarcher(const Hierarchy& h, const RenderSettings& s, const Field& field, const Shader& shader)
    : H(h)
    , S(s)
    , F(field)
    , Shading(shader)
    , Steps(StepOfLevels(h, s.ReferenceSampleFactor))
    , IsoValues(s.IsoValues)
    , Lit(s.Light.Shade || s.Light.Shadows)
  {
  }

  glm::vec4 Pixel(int i, int j, RenderStats& stats) const;

private:
  const Hierarchy& H;
  const RenderSettings& S;
  const Field& F;
  const Shader& Shading;
  std::vector<double> Steps;
  std::vector<double> IsoValues;
  bool Lit;
};

glm::vec4 RayMarcher::Pixel(int i, int j, RenderStats& stats) const
{
  glm::dvec3 wo, wd;
  this->S.View.Ray(this->S.Width, this->S.Height, i + 0.5, j + 0.5, wo, wd);
  const glm::dvec3 o = (wo - this->H.Origin) / this->H.Spacing0;
  const glm::dvec3 d = wd / this->H.Spacing0;
  const glm::dvec3 towardEye = -wd;

  double tBegin, tEnd;
  bool hit = SlabInterval(o, d, this->F.RootLo(), this->F.RootHi(), tBegin, tEnd);
  if (this->S.Clip)
  {
    double c0, c1;
    hit = SlabInterval(wo, wd, this->S.ClipLo, this->S.ClipHi, c0, c1) && c0 < c1 && hit;
    tBegin = std::max(tBegin, c0);
    tEnd = std::min(tEnd, c1);
  }
  glm::dvec3 background = this->S.Background;
  double opaqueDistance = 0.0;
  glm::dvec3 opaqueColour;
  if (this->S.Opaque && this->S.Opaque(wo, wd, opaqueDistance, opaqueColour))
  {
    tEnd = std::min(tEnd, opaqueDistance);
    background = opaqueColour;
  }
  const BlendMode mode = this->S.Blend;
  const bool stopEarly = mode == BlendMode::Composite && this->S.OpacityThreshold < 1.0;
  Compositor light;
  Projection projection;
  bool havePrevious = false; // iso-surfaces: the previous present sample
  glm::dvec3 previousP(0.0);
  double previousV = 0.0;

  double t = std::max(0.0, tBegin);
  if (hit && t < tEnd)
  {
    ++stats.Rays;
  }
  while (hit && t < tEnd)
  {
    if (stopEarly && light.Alpha() >= this->S.OpacityThreshold)
    {
      break;
    }
    // the step: the level-0 step, shrunk until the finest level at its midpoint asks for no less
    double dt = std::min(this->Steps[0], tEnd - t);
    int level = this->F.LevelAt(o + (t + 0.5 * dt) * d);
    while (level > 0 && this->Steps[level] < dt * (1.0 - 1e-12))
    {
      dt = this->Steps[level];
      level = this->F.LevelAt(o + (t + 0.5 * dt) * d);
    }
    const glm::dvec3 p = o + (t + 0.5 * dt) * d;
    t += dt;
    int valueLevel = -1;
    const double v = this->F.At(p, &valueLevel);
    if (valueLevel < 0)
    {
      havePrevious = false; // empty space breaks iso-surface pairs
      continue;
    }
    ++stats.Samples;
    if (std::isnan(v))
    {
      havePrevious = false; // missing data: transparent, and no crossing through it
      continue;
    }
    switch (mode)
    {
      case BlendMode::Maximum:
        projection.Kept = projection.Any ? std::max(projection.Kept, v) : v;
        projection.Any = true;
        break;
      case BlendMode::Minimum:
        projection.Kept = projection.Any ? std::min(projection.Kept, v) : v;
        projection.Any = true;
        break;
      case BlendMode::Average:
        projection.Sum += v * dt;
        projection.Length += dt;
        projection.Any = true;
        break;
      case BlendMode::Composite:
      {
        const double alpha =
          CorrectedOpacity(OpacityOf(this->S.Transfer, v), dt, this->S.Transfer.UnitDistance);
        if (alpha > 0.0)
        {
          glm::dvec3 colour = ColourOf(this->S.Transfer, v);
          if (this->Lit)
          {
            colour = this->Shading.Shade(colour, p, v, valueLevel, towardEye);
          }
          light.Add(colour, alpha);
        }
        break;
      }
      case BlendMode::IsoSurface:
        if (havePrevious)
        {
          for (const Crossing& c :
            FindCrossings(this->F, this->IsoValues, previousP, previousV, p, v))
          {
            glm::dvec3 colour = ColourOf(this->S.Transfer, c.IsoValue);
            if (this->Lit)
            {
              int hitLevel = -1;
              double hitValue = this->F.At(c.Hit, &hitLevel);
              if (hitLevel < 0 || std::isnan(hitValue))
              {
                hitValue = c.IsoValue;
                hitLevel = 0;
              }
              colour = this->Shading.Shade(colour, c.Hit, hitValue, hitLevel, towardEye);
            }
            const double opacity =
              std::min(1.0, std::max(0.0, OpacityOf(this->S.Transfer, c.IsoValue)));
            light.Add(colour, opacity);
          }
        }
        havePrevious = true;
        previousP = p;
        previousV = v;
        break;
    }
  }
  if (stopEarly && light.Alpha() >= this->S.OpacityThreshold)
  {
    ++stats.TerminatedRays;
  }
  if (mode == BlendMode::Maximum || mode == BlendMode::Minimum || mode == BlendMode::Average)
  {
    // the kept scalar through the transfer function, opacity uncorrected
    if (projection.Any && (mode != BlendMode::Average || projection.Length > 0.0))
    {
      const double s =
        mode == BlendMode::Average ? projection.Sum / projection.Length : projection.Kept;
      const double alpha = std::min(1.0, OpacityOf(this->S.Transfer, s));
      light.Add(ColourOf(this->S.Transfer, s), alpha);
    }
  }
  const glm::dvec3 rgb = light.Radiance + light.Transmittance * background;
  return glm::vec4(glm::vec3(rgb), static_cast<float>(light.Alpha()));
}
} // namespace

PointLookup ReferencePointLookup(const Hierarchy& h, const FinestCellLocator& locator, bool smooth)
{
  const auto field = std::make_shared<Field>(h, locator, smooth);
  return [field](const glm::dvec3& p, glm::dvec3& cellSize)
  {
    int level = -1;
    const double v = field->At(p, &level);
    if (level >= 0)
    {
      cellSize = field->CellSizeOf(level);
    }
    return level >= 0 ? v : std::numeric_limits<double>::quiet_NaN();
  };
}

Image RenderReference(const Hierarchy& h, const RenderSettings& s)
{
  CheckSettings(h, s);
  Image img;
  img.Width = s.Width;
  img.Height = s.Height;
  img.Pixels.resize(static_cast<std::size_t>(s.Width) * s.Height);
  const FinestCellLocator locator(h);
  const Field field(h, locator, s.SmoothCellData);
  const Light light = ResolveLight(s.Light, s.View);
  const Shader shader(field, light, s.Transfer);
  const RayMarcher marcher(h, s, field, shader);

  RenderStats total;
  std::mutex totalLock;
  ProgressTicker ticker(s.Progress, s.Height);
  ParallelForInterleaved(
    s.Height,
    [&](int64_t row)
    {
      const int j = static_cast<int>(row);
      RenderStats stats;
      for (int i = 0; i < s.Width; ++i)
      {
        img.Pixels[static_cast<std::size_t>(j) * s.Width + i] = marcher.Pixel(i, j, stats);
      }
      {
        std::lock_guard<std::mutex> guard(totalLock);
        total.Rays += stats.Rays;
        total.Samples += stats.Samples;
        total.TerminatedRays += stats.TerminatedRays;
      }
      ticker.Done();
    },
    s.Threads);
  ticker.Finish();
  if (s.Stats)
  {
    *s.Stats = total;
  }
  return img;
}
} // namespace amrsp
