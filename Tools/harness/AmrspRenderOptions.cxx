// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspRenderOptions.h"

#include "AmrspDataset.h"

#include "amrsp/VertexData.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

namespace amrsp
{
namespace harness
{

using Json = nlohmann::ordered_json;

const std::vector<std::string> RenderOptionNames = { "size", "azimuth", "elevation", "zoom", "tf",
  "scale", "unit-distance", "sample-factor", "reference-sample-factor", "lod", "threads", "blend",
  "view-json", "opacity-threshold", "empty-space-skipping", "interpolation", "shade", "iso",
  "shadows", "light", "crop", "ropes", "ablation", "loop", "caster", "range" };

ScalarSpan MeasureScalars(const Hierarchy& h)
{
  ScalarSpan span;
  span.Lo = std::numeric_limits<double>::max();
  span.Hi = -std::numeric_limits<double>::max();
  for (const GridValues& v : h.Values)
  {
    for (float x : v)
    {
      if (std::isfinite(x))
      {
        span.Lo = std::min(span.Lo, static_cast<double>(x));
        span.Hi = std::max(span.Hi, static_cast<double>(x));
        if (x > 0.0f)
        {
          span.MinPositive = std::min(span.MinPositive, static_cast<double>(x));
        }
      }
    }
  }
  if (span.Lo > span.Hi)
  {
    throw DatasetError("the array '" + h.ArrayName + "' has no finite value");
  }
  return span;
}

ScalarSpan Union(const ScalarSpan& a, const ScalarSpan& b)
{
  ScalarSpan u;
  u.Lo = std::min(a.Lo, b.Lo);
  u.Hi = std::max(a.Hi, b.Hi);
  u.MinPositive = std::min(a.MinPositive, b.MinPositive);
  return u;
}

ScalarSpan ParseScalarSpan(const std::string& text)
{
  const std::size_t colon = text.find(':');
  ScalarSpan span;
  bool ok = colon != std::string::npos;
  try
  {
    std::size_t used = 0;
    span.Lo = ok ? std::stod(text.substr(0, colon), &used) : 0.0;
    ok = ok && used == colon;
    span.Hi = ok ? std::stod(text.substr(colon + 1), &used) : 0.0;
    ok = ok && used == text.size() - colon - 1;
  }
  catch (const std::exception&)
  {
    ok = false;
  }
  if (!ok || !std::isfinite(span.Lo) || !std::isfinite(span.Hi) || !(span.Lo < span.Hi))
  {
    throw UsageError{ "--range takes all, step or LO:HI with finite LO < HI, not '" + text + "'" };
  }
  span.MinPositive = span.Lo > 0.0 ? span.Lo : std::numeric_limits<double>::max();
  return span;
}

void PrepareScalars(
  Hierarchy& h, const std::string& scale, double& lo, double& hi, const ScalarSpan* over)
{
  const ScalarSpan span = over ? *over : MeasureScalars(h);
  lo = span.Lo;
  hi = span.Hi;
  const double minPositive = span.MinPositive;
  bool useLog = scale == "log";
  if (scale == "auto")
  {
    useLog = lo >= 0.0 && hi > 0.0 && hi / minPositive > 1e3;
  }
  else if (scale != "log" && scale != "linear")
  {
    throw UsageError{ "--scale must be auto, linear or log" };
  }
  if (!useLog)
  {
    return;
  }
  if (!(hi > 0.0) || !(minPositive < std::numeric_limits<double>::max()))
  {
    throw DatasetError("--scale log needs positive values in '" + h.ArrayName + "'");
  }
  for (GridValues& v : h.Values)
  {
    for (float& x : v)
    {
      x = static_cast<float>(std::log10(std::max(static_cast<double>(x), minPositive)));
    }
  }
  h.ArrayName = "log10(" + h.ArrayName + ")";
  lo = std::log10(minPositive);
  hi = std::log10(hi);
  if (h.VertexCentred)
  {
    MakeVertexDataContinuous(h); // continuous in the displayed (logarithmic) scalar
  }
}

namespace
{

/// A view described explicitly (--view-json). Absent parts keep the conventions.
struct ExplicitView
{
  bool HasCamera = false;
  Camera View;
  bool HasTransfer = false;
  TransferFunction Transfer;
  bool HasBackground = false;
  glm::dvec3 Background{ 0.0 };
  /// The light (world coordinates) and the material of the shading.
  bool HasLight = false;
  bool LightPositional = false;
  glm::dvec3 LightPosition{ 0.0 };
  glm::dvec3 LightFocalPoint{ 0.0 };
  glm::dvec3 LightColour{ 1.0 };
  bool HasMaterial = false;
  double Ambient = 0.0, Diffuse = 0.0, Specular = 0.0, SpecularPower = 1.0;
  /// Iso-values in the data's own values (--blend iso).
  std::vector<double> IsoValues;
};

glm::dvec3 JsonVector3(const Json& j, const std::string& what)
{
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
  {
    throw UsageError{ "--view-json: '" + what + "' must be an array of 3 numbers" };
  }
  return glm::dvec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
}

/// Reads --view-json FILE:
///   { "camera": { "position": [x,y,z], "focal_point": [x,y,z], "view_up": [x,y,z],
///                 "view_angle": degrees, "parallel_projection": false, "parallel_scale": s },
///     "transfer_function": { "rgb_points": [[x,r,g,b], ...], "opacity_points": [[x,a], ...],
///                            "unit_distance": u, "color_log_scale": false,
///                            "opacity_log_scale": false },
///     "background": [r,g,b],
///     "light": { "position": [x,y,z], "focal_point": [x,y,z], "positional": false,
///                "colour": [r,g,b] },                       (colour: diffuse colour x intensity)
///     "material": { "ambient": a, "diffuse": d, "specular": s, "specular_power": p },
///     "iso_values": [v, ...] }                               (with --blend iso; data values)
/// Every part is optional. Points are sorted by x; the functions are piecewise linear in the
/// scalar and clamp beyond their end points (vtkColorTransferFunction in RGB space,
/// vtkPiecewiseFunction with midpoint 0.5 and sharpness 0).
ExplicitView ReadViewJson(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
  {
    throw UsageError{ "--view-json: cannot open '" + path + "'" };
  }
  Json j;
  try
  {
    j = Json::parse(in);
  }
  catch (const std::exception& e)
  {
    throw UsageError{ "--view-json: '" + path + "' is not valid JSON: " + e.what() };
  }
  if (!j.is_object())
  {
    throw UsageError{ "--view-json: '" + path + "' must hold a JSON object" };
  }
  ExplicitView v;
  try
  {
    if (j.contains("camera"))
    {
      const Json& c = j.at("camera");
      v.HasCamera = true;
      v.View.Position = JsonVector3(c.at("position"), "camera.position");
      v.View.FocalPoint = JsonVector3(c.at("focal_point"), "camera.focal_point");
      v.View.ViewUp = JsonVector3(c.at("view_up"), "camera.view_up");
      v.View.ViewAngle = c.value("view_angle", 30.0);
      v.View.Parallel = c.value("parallel_projection", false);
      v.View.ParallelScale = c.value("parallel_scale", 1.0);
      if (!(glm::length(v.View.Position - v.View.FocalPoint) > 0.0) ||
        !(glm::length(v.View.ViewUp) > 0.0) || !(v.View.ViewAngle > 0.0) ||
        !(v.View.ViewAngle < 180.0) || !(v.View.ParallelScale > 0.0))
      {
        throw UsageError{ "--view-json: the camera is degenerate (position at the focal point, "
                          "zero view-up, or a view angle or parallel scale out of range)" };
      }
    }
    if (j.contains("transfer_function"))
    {
      const Json& t = j.at("transfer_function");
      v.HasTransfer = true;
      for (const Json& p : t.at("rgb_points"))
      {
        if (!p.is_array() || p.size() != 4)
        {
          throw UsageError{ "--view-json: every rgb_points entry must be [x, r, g, b]" };
        }
        v.Transfer.Color.push_back(
          { p[0].get<double>(), { p[1].get<double>(), p[2].get<double>(), p[3].get<double>() } });
      }
      for (const Json& p : t.at("opacity_points"))
      {
        if (!p.is_array() || p.size() != 2)
        {
          throw UsageError{ "--view-json: every opacity_points entry must be [x, a]" };
        }
        v.Transfer.Opacity.push_back({ p[0].get<double>(), p[1].get<double>() });
      }
      if (v.Transfer.Color.empty() || v.Transfer.Opacity.empty())
      {
        throw UsageError{ "--view-json: rgb_points and opacity_points must not be empty" };
      }
      std::stable_sort(v.Transfer.Color.begin(), v.Transfer.Color.end(),
        [](const TransferFunction::ColorPoint& a, const TransferFunction::ColorPoint& b)
        { return a.X < b.X; });
      std::stable_sort(v.Transfer.Opacity.begin(), v.Transfer.Opacity.end(),
        [](const TransferFunction::OpacityPoint& a, const TransferFunction::OpacityPoint& b)
        { return a.X < b.X; });
      v.Transfer.UnitDistance = t.value("unit_distance", 0.0); // 0: the usual default
      // ParaView's UseLogScale of the colour map and of the opacity function
      v.Transfer.ColorLogScale = t.value("color_log_scale", false);
      v.Transfer.OpacityLogScale = t.value("opacity_log_scale", false);
    }
    if (j.contains("light"))
    {
      const Json& l = j.at("light");
      v.HasLight = true;
      v.LightPosition = JsonVector3(l.at("position"), "light.position");
      v.LightFocalPoint = JsonVector3(l.at("focal_point"), "light.focal_point");
      v.LightPositional = l.value("positional", false);
      v.LightColour =
        l.contains("colour") ? JsonVector3(l.at("colour"), "light.colour") : glm::dvec3(1.0);
    }
    if (j.contains("material"))
    {
      const Json& m = j.at("material");
      v.HasMaterial = true;
      v.Ambient = m.at("ambient").get<double>();
      v.Diffuse = m.at("diffuse").get<double>();
      v.Specular = m.at("specular").get<double>();
      v.SpecularPower = m.at("specular_power").get<double>();
    }
    if (j.contains("iso_values"))
    {
      for (const Json& x : j.at("iso_values"))
      {
        v.IsoValues.push_back(x.get<double>());
      }
      if (v.IsoValues.empty() || v.IsoValues.size() > static_cast<std::size_t>(MaxIsoValues))
      {
        throw UsageError{ "--view-json: iso_values takes 1 to 8 values" };
      }
    }
    if (j.contains("background"))
    {
      v.HasBackground = true;
      v.Background = JsonVector3(j.at("background"), "background");
    }
  }
  catch (const Json::exception& e)
  {
    throw UsageError{ "--view-json: '" + path + "': " + e.what() };
  }
  return v;
}

/// The light, material and iso-values of a --view-json file override the conventions.
void ApplyExplicitLighting(const ExplicitView& v, const RenderRequest& r, RenderSettings& s)
{
  if (v.HasLight)
  {
    if (r.Light)
    {
      throw UsageError{ "--light cannot be combined with a --view-json light" };
    }
    s.Light.Headlight = false;
    s.Light.Positional = v.LightPositional;
    s.Light.Position = v.LightPosition;
    s.Light.FocalPoint = v.LightFocalPoint;
    s.Light.Colour = v.LightColour;
  }
  if (v.HasMaterial)
  {
    s.Light.Ambient = v.Ambient;
    s.Light.Diffuse = v.Diffuse;
    s.Light.Specular = v.Specular;
    s.Light.SpecularPower = v.SpecularPower;
  }
  if (!v.IsoValues.empty())
  {
    if (s.Blend != BlendMode::IsoSurface || r.Iso)
    {
      throw UsageError{ "--view-json iso_values need --blend iso and no --iso" };
    }
    s.IsoValues = v.IsoValues;
  }
}

} // namespace

RenderSettings MakeSettings(
  Hierarchy& h, const RenderRequest& r, glm::dvec2* range, const ScalarSpan* over)
{
  ExplicitView explicitView;
  if (!r.ViewJson.empty())
  {
    explicitView = ReadViewJson(r.ViewJson);
    if (explicitView.HasCamera && (r.Azimuth || r.Elevation || r.Zoom))
    {
      throw UsageError{ "--azimuth, --elevation and --zoom cannot change a --view-json camera" };
    }
    if (explicitView.HasTransfer && r.Tf)
    {
      throw UsageError{ "--tf cannot be combined with a --view-json transfer function" };
    }
  }
  RenderSettings s;
  s.Width = r.Width;
  s.Height = r.Height;
  glm::dvec3 lo, hi;
  Bounds(h, lo, hi);
  if (explicitView.HasCamera)
  {
    s.View = explicitView.View;
  }
  else
  {
    s.View = Camera::ResetTo(lo, hi);
    s.View.Azimuth(r.Azimuth.value_or(30.0));
    s.View.Elevation(r.Elevation.value_or(20.0));
    s.View.OrthogonalizeViewUp();
    s.View.Zoom(r.Zoom.value_or(1.0));
  }
  if (explicitView.HasBackground)
  {
    s.Background = explicitView.Background;
  }
  double vlo, vhi;
  // an explicit transfer function is written in the data's own values
  // --range all and step are a series' choice (AmrspSeries.cxx hands the span over all steps)
  ScalarSpan givenSpan;
  if (!over && r.Range != "all" && r.Range != "step")
  {
    givenSpan = ParseScalarSpan(r.Range);
    over = &givenSpan;
  }
  PrepareScalars(h, r.Scale.value_or(explicitView.HasTransfer ? "linear" : "auto"), vlo, vhi, over);
  if (range)
  {
    *range = glm::dvec2(vlo, vhi);
  }
  const double fileUnit = explicitView.HasTransfer ? explicitView.Transfer.UnitDistance : 0.0;
  const double unit =
    r.UnitDistance.value_or(fileUnit > 0.0 ? fileUnit : glm::length(hi - lo) / 100.0);
  if (!(unit > 0.0))
  {
    throw UsageError{ "--unit-distance must be positive" };
  }
  if (explicitView.HasTransfer)
  {
    s.Transfer = explicitView.Transfer;
    s.Transfer.UnitDistance = unit;
  }
  else
  {
    try
    {
      s.Transfer = TransferFunction::Preset(r.Tf.value_or("default"), vlo, vhi, unit);
    }
    catch (const std::invalid_argument& e)
    {
      throw UsageError{ e.what() };
    }
  }
  s.SampleDistanceFactor = r.SampleFactor;
  s.ReferenceSampleFactor = r.ReferenceSampleFactor;
  s.LodThresholdPixels = static_cast<float>(r.Lod);
  s.AtlasPageBytes = static_cast<long long>(r.AtlasPageMiB * 1024.0 * 1024.0);
  s.Blend = r.Blend;
  // shading, shadows, the light and the iso-values (fractions of the transfer function's range)
  s.Light.Shade = r.Shade;
  s.Light.ShadowStep = r.ShadowStep;
  s.Light.Shadows = r.ShadowStep > 0.0;
  if (r.Light)
  {
    s.Light.Headlight = false;
    s.Light.Positional = true;
    s.Light.Position = *r.Light;
    s.Light.FocalPoint = s.View.FocalPoint;
  }
  if (s.Blend == BlendMode::IsoSurface)
  {
    s.IsoValues.clear();
    for (double x : r.Iso.value_or(std::vector<double>{ 0.5 }))
    {
      s.IsoValues.push_back(vlo + x * (vhi - vlo));
    }
  }
  ApplyExplicitLighting(explicitView, r, s);
  s.Threads = r.Threads;
  s.OpacityThreshold = r.OpacityThreshold;
  s.SkipEmptySpace = r.SkipEmptySpace;
  s.Ropes = r.Ropes;
  s.GpuRayLoop = r.Loop;
  s.GpuRayCaster = r.Caster;
  s.GpuAblation = r.Ablation;
  s.GpuAblationSamples = r.AblationSamples;
  s.SmoothCellData = r.SmoothCells;
  if (r.Crop)
  {
    const std::array<double, 6>& c = *r.Crop;
    s.Clip = true;
    s.ClipLo = glm::dvec3(c[0], c[2], c[4]);
    s.ClipHi = glm::dvec3(c[1], c[3], c[5]);
  }
  return s;
}

RenderSettings MakeSettings(
  Hierarchy& h, const Arguments& a, glm::dvec2* range, const ScalarSpan* over)
{
  return MakeSettings(h, ParseRenderRequest(a), range, over);
}

RenderSettings MakeSettings(Hierarchy& h, const std::vector<std::string>& optionWords)
{
  return MakeSettings(h, ParseArguments(optionWords, RenderOptionNames));
}

void Bounds(const Hierarchy& h, glm::dvec3& lo, glm::dvec3& hi)
{
  lo = h.WorldLo(h.RootCells(), 0);
  hi = h.WorldHi(h.RootCells(), 0);
}

ViewAngles ViewOf(const Arguments& a)
{
  ViewAngles v;
  v.Azimuth = a.GetNumber("azimuth", 30.0);
  v.Elevation = a.GetNumber("elevation", 20.0);
  v.Zoom = a.GetNumber("zoom", 1.0);
  // a --view-json camera is used as it is (MakeSettings checked that no angle changes it)
  v.UseSettingsCamera = a.Has("view-json");
  return v;
}

/// Largest difference between the VTK camera the mapper used and the tool's own camera, relative
/// to the camera distance (the view angle in degrees / 180).
double CameraDifference(const Camera& a, const Camera& b)
{
  const double scale = std::max(1e-300, glm::length(b.Position - b.FocalPoint));
  double d = glm::length(a.Position - b.Position) / scale;
  d = std::max(d, glm::length(a.FocalPoint - b.FocalPoint) / scale);
  d = std::max(d, glm::length(glm::normalize(a.ViewUp) - glm::normalize(b.ViewUp)));
  d = std::max(d, std::abs(a.ViewAngle - b.ViewAngle) / 180.0);
  return d;
}

} // namespace harness
} // namespace amrsp
