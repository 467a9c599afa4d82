// SPDX-License-Identifier: BSD-3-Clause
// Transfer functions (piecewise linear, clamped, as VTK's) and the presets.
#include "amrsp/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace amrsp
{

namespace
{
template <typename Point, typename Value, typename Get>
Value Interpolate(
  const std::vector<Point>& points, double s, bool logScale, Value fallback, Get get)
{
  if (points.empty())
  {
    return fallback;
  }
  if (s <= points.front().X || (logScale && !(s > 0.0)))
  {
    return get(points.front());
  }
  if (s >= points.back().X)
  {
    return get(points.back());
  }
  const auto upper = std::upper_bound(
    points.begin(), points.end(), s, [](double v, const Point& p) { return v < p.X; });
  const Point& b = *upper;
  const Point& a = *(upper - 1);
  double w = b.X > a.X ? (s - a.X) / (b.X - a.X) : 0.0;
  if (logScale && a.X > 0.0 && b.X > a.X)
  {
    w = (std::log10(s) - std::log10(a.X)) / (std::log10(b.X) - std::log10(a.X));
  }
  return get(a) * (1.0 - w) + get(b) * w;
}
} // namespace

glm::dvec3 TransferFunction::EvaluateColor(double s) const
{
  return Interpolate(
    Color, s, ColorLogScale, glm::dvec3(1.0), [](const ColorPoint& p) { return p.Rgb; });
}

double TransferFunction::EvaluateOpacity(double s) const
{
  return Interpolate(
    Opacity, s, OpacityLogScale, 0.0, [](const OpacityPoint& p) { return p.Opacity; });
}

std::vector<std::string> TransferFunction::PresetNames()
{
  return { "default", "grey", "hot", "grey-opaque", "sparse" };
}

TransferFunction TransferFunction::Preset(
  const std::string& name, double lo, double hi, double unitDistance)
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
} // namespace amrsp
