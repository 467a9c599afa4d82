// SPDX-License-Identifier: BSD-3-Clause
// The clip box of the render settings.
#include "amrsp/RenderSettings.h"

#include <algorithm>
#include <limits>
#include <utility>

namespace amrsp
{

bool ClipInterval(
  const RenderSettings& s, const glm::dvec3& wo, const glm::dvec3& wd, double& t0, double& t1)
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

} // namespace amrsp
