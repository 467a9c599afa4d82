// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/InteractiveQuality.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace amrsp
{
namespace
{
/// The rungs' image sample distances within the limits, finest first (at least one rung).
std::vector<double> Rungs(const InteractiveQuality::Limits& limits)
{
  const double lo = std::max(1.0, limits.MinimumImageSampleDistance);
  const double hi = std::max(lo, limits.MaximumImageSampleDistance);
  std::vector<double> rungs{ lo };
  for (double d : { 1.5, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0 })
  {
    if (d > lo && d < hi)
    {
      rungs.push_back(d);
    }
  }
  if (hi > lo)
  {
    rungs.push_back(hi);
  }
  return rungs;
}

FrameQuality AtRung(double d, const InteractiveQuality::Limits& limits)
{
  FrameQuality q;
  q.ImageSampleDistance = d;
  q.SampleDistanceScale = limits.AdjustSampleDistance ? d : 1.0;
  return q;
}
} // namespace

double InteractiveQuality::CostFraction(const FrameQuality& q)
{
  const double d = q.ImageSampleDistance;
  return (RayShare + (1.0 - RayShare) / q.SampleDistanceScale) / (d * d);
}

double InteractiveQuality::Predict(const FrameQuality& q) const
{
  const auto own = this->Measured.find({ q.ImageSampleDistance, q.SampleDistanceScale });
  if (own != this->Measured.end())
  {
    return own->second;
  }
  // the measured quality whose cost fraction is nearest (in ratio) to q's
  const double fraction = CostFraction(q);
  double best = 0.0, bestDistance = 0.0;
  for (const auto& m : this->Measured)
  {
    FrameQuality other;
    other.ImageSampleDistance = m.first.first;
    other.SampleDistanceScale = m.first.second;
    const double ratio = fraction / CostFraction(other);
    const double distance = std::fabs(std::log(ratio));
    if (best == 0.0 || distance < bestDistance)
    {
      best = m.second * ratio;
      bestDistance = distance;
    }
  }
  return best;
}

FrameQuality InteractiveQuality::Choose(double budgetSeconds, const Limits& limits) const
{
  const std::vector<double> rungs = Rungs(limits);
  if (this->Measured.empty())
  {
    return AtRung(rungs.back(), limits);
  }
  for (double d : rungs)
  {
    const FrameQuality q = AtRung(d, limits);
    if (this->Predict(q) <= budgetSeconds)
    {
      return q;
    }
  }
  return AtRung(rungs.back(), limits);
}

void InteractiveQuality::Record(const FrameQuality& q, double seconds)
{
  if (!(seconds > 0.0))
  {
    return;
  }
  const auto key = std::make_pair(q.ImageSampleDistance, q.SampleDistanceScale);
  const auto own = this->Measured.find(key);
  this->Measured[key] = own != this->Measured.end() ? 0.5 * (own->second + seconds) : seconds;
}

} // namespace amrsp
