// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/InteractiveQuality.h"

#include <algorithm>
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
  return this->FullSeconds * CostFraction(q);
}

FrameQuality InteractiveQuality::Choose(double budgetSeconds, const Limits& limits) const
{
  const std::vector<double> rungs = Rungs(limits);
  if (this->FullSeconds <= 0.0)
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
  const double full = seconds / CostFraction(q);
  this->FullSeconds = this->FullSeconds > 0.0 ? 0.5 * (this->FullSeconds + full) : full;
}

} // namespace amrsp
