// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspRenderRequest.h"

#include "amrsp/Shading.h"

#include <stdexcept>
#include <utility>

namespace amrsp
{
namespace harness
{

namespace
{
/// --size WxH into the request (1 to 16384 each).
void ParseImageSize(const std::string& size, RenderRequest& r)
{
  const std::size_t x = size.find('x');
  try
  {
    if (x == std::string::npos)
    {
      throw std::invalid_argument(size);
    }
    r.Width = std::stoi(size.substr(0, x));
    r.Height = std::stoi(size.substr(x + 1));
  }
  catch (const std::exception&)
  {
    throw UsageError{ "--size expects WxH, got '" + size + "'" };
  }
  if (r.Width < 1 || r.Height < 1 || r.Width > 16384 || r.Height > 16384)
  {
    throw UsageError{ "--size must be between 1x1 and 16384x16384" };
  }
}

/// An on|off option.
bool OnOff(const Arguments& a, const std::string& key, const std::string& fallback)
{
  const std::string value = a.Get(key, fallback);
  if (value != "on" && value != "off")
  {
    throw UsageError{ "--" + key + " must be on or off" };
  }
  return value == "on";
}

/// --ablation none|traversal-only|sampling-only[:N].
void ParseAblation(const std::string& ablation, RenderRequest& r)
{
  const std::string samplingOnly = "sampling-only";
  if (ablation == "traversal-only")
  {
    r.Ablation = 1;
  }
  else if (ablation.rfind(samplingOnly, 0) == 0)
  {
    r.Ablation = 2;
    if (ablation.size() > samplingOnly.size())
    {
      const std::string n = ablation.substr(samplingOnly.size() + 1);
      if (ablation[samplingOnly.size()] != ':' || n.empty() || n.size() > 7 ||
        n.find_first_not_of("0123456789") != std::string::npos || std::stoi(n) < 1)
      {
        throw UsageError{ "--ablation sampling-only:N needs a whole N from 1 to 9999999, got '" +
          ablation + "'" };
      }
      r.AblationSamples = std::stoi(n);
    }
  }
  else if (ablation != "none")
  {
    throw UsageError{ "--ablation must be none, traversal-only or sampling-only[:N], got '" +
      ablation + "'" };
  }
}
} // namespace

RenderRequest ParseRenderRequest(const Arguments& a)
{
  RenderRequest r;
  r.ViewJson = a.Get("view-json", "");
  ParseImageSize(a.Get("size", "512x512"), r);
  const std::pair<const char*, std::optional<double>*> numbers[] = { { "azimuth", &r.Azimuth },
    { "elevation", &r.Elevation }, { "zoom", &r.Zoom }, { "unit-distance", &r.UnitDistance } };
  for (const auto& number : numbers)
  {
    if (a.Has(number.first))
    {
      *number.second = a.GetNumber(number.first, 0.0);
    }
  }
  if (r.UnitDistance && !(*r.UnitDistance > 0.0))
  {
    throw UsageError{ "--unit-distance must be positive" };
  }
  if (a.Has("tf"))
  {
    r.Tf = a.Get("tf", "");
  }
  if (a.Has("scale"))
  {
    r.Scale = a.Get("scale", "");
  }
  r.Range = a.Get("range", "step");
  r.SampleFactor = a.GetNumber("sample-factor", 1.0);
  r.ReferenceSampleFactor = a.GetNumber("reference-sample-factor", 0.5);
  if (!(r.SampleFactor > 0.0) || !(r.ReferenceSampleFactor > 0.0))
  {
    throw UsageError{ "sample factors must be positive" };
  }
  r.Lod = a.GetNumber("lod", 0.0);
  r.AtlasPageMiB = a.GetNumber("atlas-page-mib", 0.0);
  if (r.AtlasPageMiB < 0.0)
  {
    throw UsageError{ "--atlas-page-mib must be positive" };
  }
  if (!ParseIn(BlendModeNames, a.Get("blend", "composite").c_str(), r.Blend))
  {
    throw UsageError{ "--blend must be " + WordsOf(BlendModeNames) };
  }
  r.Shade = OnOff(a, "shade", "off");
  r.ShadowStep = a.GetNumber("shadows", 0.0);
  if (r.ShadowStep < 0.0)
  {
    throw UsageError{ "--shadows expects a positive step (0 = off)" };
  }
  if (a.Has("light"))
  {
    const std::vector<double> p = a.GetNumbers("light", "");
    if (p.size() != 3)
    {
      throw UsageError{ "--light expects X,Y,Z" };
    }
    r.Light = glm::dvec3(p[0], p[1], p[2]);
  }
  if (a.Has("iso") && r.Blend != BlendMode::IsoSurface)
  {
    throw UsageError{ "--iso needs --blend iso" };
  }
  if (a.Has("iso"))
  {
    r.Iso = a.GetNumbers("iso", "0.5");
    if (r.Iso->empty() || r.Iso->size() > static_cast<std::size_t>(MaxIsoValues))
    {
      throw UsageError{ "--iso takes 1 to 8 values" };
    }
  }
  r.Threads = static_cast<int>(a.GetNumber("threads", 0.0));
  r.OpacityThreshold = a.GetNumber("opacity-threshold", 0.999);
  if (!(r.OpacityThreshold >= 0.0 && r.OpacityThreshold <= 1.0))
  {
    throw UsageError{ "--opacity-threshold must be between 0 and 1" };
  }
  r.SkipEmptySpace = OnOff(a, "empty-space-skipping", "on");
  r.Ropes = OnOff(a, "ropes", "on");
  if (!ParseIn(RayLoopNames, a.Get("loop", "nested").c_str(), r.Loop))
  {
    throw UsageError{ "--loop must be " + WordsOf(RayLoopNames) };
  }
  if (!ParseIn(RayCasterNames, a.Get("caster", "auto").c_str(), r.Caster))
  {
    throw UsageError{ "--caster must be " + WordsOf(RayCasterNames) };
  }
  ParseAblation(a.Get("ablation", "none"), r);
  const std::string interpolation = a.Get("interpolation", "nearest");
  if (interpolation != "nearest" && interpolation != "smooth")
  {
    throw UsageError{ "--interpolation must be nearest or smooth" };
  }
  r.SmoothCells = interpolation == "smooth";
  if (a.Has("crop"))
  {
    const std::vector<double> c = a.GetNumbers("crop", "");
    if (c.size() != 6 || c[0] > c[1] || c[2] > c[3] || c[4] > c[5])
    {
      throw UsageError{ "--crop expects X0,X1,Y0,Y1,Z0,Z1 with X0 <= X1, Y0 <= Y1, Z0 <= Z1" };
    }
    r.Crop = std::array<double, 6>{ c[0], c[1], c[2], c[3], c[4], c[5] };
  }
  return r;
}

} // namespace harness
} // namespace amrsp
