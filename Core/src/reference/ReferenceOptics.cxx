// SPDX-License-Identifier: BSD-3-Clause
// The reference's transfer-function evaluation, opacity correction and compositing.
#include "ReferenceRules.h"

#include <cmath>
#include <cstddef>

namespace amrsp
{
namespace reference
{
namespace
{
/// The interpolation weight of scalar s between control points at xa < xb.
double Weight(double xa, double xb, double s, bool logScale)
{
  if (logScale && xa > 0.0)
  {
    return (std::log(s) - std::log(xa)) / (std::log(xb) - std::log(xa));
  }
  return (s - xa) / (xb - xa);
}

/// Piecewise-linear evaluation by a linear scan over the control points (ascending X); y(point)
/// gives a point's value.
template <typename Point, typename Y>
auto PiecewiseLinear(const std::vector<Point>& points, double s, bool logScale, Y y)
{
  const std::size_t n = points.size();
  if (s <= points[0].X || (logScale && s <= 0.0))
  {
    return y(points[0]);
  }
  for (std::size_t i = 1; i < n; ++i)
  {
    if (s < points[i].X)
    {
      const Point& a = points[i - 1];
      const Point& b = points[i];
      if (!(b.X > a.X))
      {
        return y(a);
      }
      const double w = Weight(a.X, b.X, s, logScale);
      return y(a) + w * (y(b) - y(a));
    }
  }
  return y(points[n - 1]);
}
} // namespace

glm::dvec3 ColourOf(const TransferFunction& tf, double scalar)
{
  if (tf.Color.empty())
  {
    return glm::dvec3(1.0);
  }
  return PiecewiseLinear(tf.Color, scalar, tf.ColorLogScale,
    [](const TransferFunction::ColorPoint& point) { return point.Rgb; });
}

double OpacityOf(const TransferFunction& tf, double scalar)
{
  if (tf.Opacity.empty())
  {
    return 0.0;
  }
  return PiecewiseLinear(tf.Opacity, scalar, tf.OpacityLogScale,
    [](const TransferFunction::OpacityPoint& point) { return point.Opacity; });
}

double CorrectedOpacity(double opacity, double length, double unitDistance)
{
  if (!(opacity > 0.0) || !(length > 0.0))
  {
    return 0.0;
  }
  if (opacity >= 1.0)
  {
    return 1.0;
  }
  return 1.0 - std::exp(std::log1p(-opacity) * length / unitDistance);
}

void Compositor::Add(const glm::dvec3& colour, double alpha)
{
  this->Radiance += this->Transmittance * alpha * colour;
  this->Transmittance *= 1.0 - alpha;
}

} // namespace reference
} // namespace amrsp
