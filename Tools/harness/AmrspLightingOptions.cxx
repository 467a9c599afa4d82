// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspLightingOptions.h"

#include "AmrspArguments.h"

#include <sstream>

namespace amrsp
{
namespace harness
{

const std::vector<std::string> LightingOptions = { "shade", "iso", "shadows", "light" };

void ApplyLightingOptions(RenderSettings& s, const Arguments& a, double lo, double hi)
{
  const std::string shade = a.Get("shade", "off");
  if (shade != "on" && shade != "off")
  {
    throw UsageError{ "--shade must be on or off" };
  }
  s.Light.Shade = shade == "on";
  s.Light.ShadowStep = a.GetNumber("shadows", 0.0);
  if (s.Light.ShadowStep < 0.0)
  {
    throw UsageError{ "--shadows expects a positive step (0 = off)" };
  }
  s.Light.Shadows = s.Light.ShadowStep > 0.0;
  if (a.Has("light"))
  {
    const std::vector<double> p = a.GetNumbers("light", "");
    if (p.size() != 3)
    {
      throw UsageError{ "--light expects X,Y,Z" };
    }
    s.Light.Headlight = false;
    s.Light.Positional = true;
    s.Light.Position = glm::dvec3(p[0], p[1], p[2]);
    s.Light.FocalPoint = s.View.FocalPoint;
  }
  if (a.Has("iso") && s.Blend != BlendMode::IsoSurface)
  {
    throw UsageError{ "--iso needs --blend iso" };
  }
  if (s.Blend == BlendMode::IsoSurface)
  {
    const std::vector<double> f = a.GetNumbers("iso", "0.5");
    if (f.empty() || f.size() > static_cast<std::size_t>(MaxIsoValues))
    {
      throw UsageError{ "--iso takes 1 to 8 values" };
    }
    s.IsoValues.clear();
    for (double x : f)
    {
      s.IsoValues.push_back(lo + x * (hi - lo));
    }
  }
}

} // namespace harness
} // namespace amrsp
