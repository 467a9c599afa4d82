// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspCommands.h"

#include "AmrspBench.h"
#include "AmrspBenchPlot.h"
#include "AmrspDataset.h"
#include "AmrspLighting.h"
#include "AmrspMultipass.h"
#include "AmrspDriver.h"
#include "AmrspPacking.h"
#include "AmrspUniform.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/Invariants.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"
#include "amrsp/VertexData.h"

#include "vtkImageData.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkPointData.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

namespace amrsp
{
namespace tool
{

const char* const DefaultDataset = "synthetic:cosmo:grids=200,levels=4,cells=1M,seed=7";

using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

std::string Arguments::Get(const std::string& key, const std::string& fallback) const
{
  const auto it = Options.find(key);
  return it == Options.end() ? fallback : it->second;
}

double Arguments::GetNumber(const std::string& key, double fallback) const
{
  const auto it = Options.find(key);
  if (it == Options.end())
  {
    return fallback;
  }
  try
  {
    std::size_t used = 0;
    const double v = std::stod(it->second, &used);
    if (used == it->second.size() && std::isfinite(v))
    {
      return v;
    }
  }
  catch (const std::exception&)
  {
  }
  throw UsageError{ "--" + key + " expects a number, got '" + it->second + "'" };
}

std::vector<double> Arguments::GetNumbers(const std::string& key, const std::string& fallback) const
{
  const std::string text = Get(key, fallback);
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');)
  {
    try
    {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(out.back()))
      {
        throw std::invalid_argument(item);
      }
    }
    catch (const std::exception&)
    {
      throw UsageError{ "--" + key + " expects comma-separated numbers, got '" + text + "'" };
    }
  }
  return out;
}

Arguments ParseArguments(int argc, char** argv, int first,
  const std::vector<std::string>& valueOptions, const std::vector<std::string>& flags)
{
  Arguments a;
  for (int i = first; i < argc; ++i)
  {
    std::string s = argv[i];
    if (s == "-o")
    {
      s = "--output";
    }
    if (s.size() > 2 && s.compare(0, 2, "--") == 0)
    {
      std::string key = s.substr(2), value;
      const std::size_t eq = key.find('=');
      if (eq != std::string::npos)
      {
        value = key.substr(eq + 1);
        key = key.substr(0, eq);
      }
      const bool takesValue =
        std::find(valueOptions.begin(), valueOptions.end(), key) != valueOptions.end();
      const bool isFlag = std::find(flags.begin(), flags.end(), key) != flags.end() || key == "help";
      if (!takesValue && !isFlag)
      {
        throw UsageError{ "unknown option --" + key };
      }
      if (takesValue && eq == std::string::npos)
      {
        if (i + 1 >= argc)
        {
          throw UsageError{ "--" + key + " needs a value" };
        }
        value = argv[++i];
      }
      a.Options[key] = takesValue ? value : "1";
    }
    else
    {
      a.Positional.push_back(s);
    }
  }
  return a;
}

namespace
{

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

int Fail(const std::string& message)
{
  std::cerr << "amrsp: error: " << message << "\n";
  return 1;
}

const std::vector<std::string> DatasetOptions = { "array", "component", "centering",
  "read-timeout" };
const std::vector<std::string> DatasetFlags = { "allow-partial", "strict" };
const std::vector<std::string> AtlasOptions = { "packer", "max-3d-texture-size", "atlas-budget-mb" };
const std::vector<std::string> ViewOptions = { "size", "azimuth", "elevation", "zoom", "tf",
  "scale", "unit-distance", "sample-factor", "reference-sample-factor", "lod", "threads", "blend",
  "view-json", "opacity-threshold", "empty-space-skipping", "interpolation", "shade", "iso",
  "shadows", "light", "crop" };

std::vector<std::string> Concat(std::initializer_list<std::vector<std::string>> lists)
{
  std::vector<std::string> all;
  for (const auto& l : lists)
  {
    all.insert(all.end(), l.begin(), l.end());
  }
  return all;
}

const char* const DatasetHelp =
  "DATASET is one of\n"
  "  PATH.hierarchy              an Enzo hierarchy (vtkAMREnzoReader)\n"
  "  PLOTFILE_FOLDER             an AMReX/BoxLib plotfile (vtkAMReXGridReader)\n"
  "  PATH.vthb | PATH.vth        VTK XML AMR (vtkXMLUniformGridAMRReader)\n"
  "  synthetic:pulse             VTK's vtkAMRGaussianPulseSource\n"
  "  synthetic:cosmo[:grids=N,levels=L,cells=C,seed=S]\n"
  "                              the project's cosmology-like generator (N and C accept k/M)\n"
  "Dataset options:\n"
  "  --array NAME                cell array to use (default: the first cell array)\n"
  "  --component I               component of a vector array (default: magnitude)\n"
  "  --centering auto|cell|vertex  auto: cell data cell-centred (nearest cell), point data\n"
  "                              vertex-centred (trilinear); vertex: convert cell data to\n"
  "                              vertices (continuous across grid and level interfaces)\n"
  "  --strict                    (the default) a file that yields fewer blocks than the\n"
  "                              dataset's own files describe is an error naming them\n"
  "  --allow-partial             render the blocks that could be read, with a warning\n"
  "  --read-timeout S            end with an error when VTK's reader is still busy after S\n"
  "                              seconds (default 120; exit code 75)\n";

const char* const AtlasHelp =
  "Atlas options (packed storage of the grid bricks):\n"
  "  --packer nfdh|best          the paper's next-fit-decreasing-height, or the guillotine-bestfit\n"
  "                              packer (default best)\n"
  "  --max-3d-texture-size N     per-axis texture limit (default 2048, GL_MAX_3D_TEXTURE_SIZE)\n"
  "  --atlas-budget-mb M         largest atlas in MiB of float texels (default: no limit)\n";

/// Packing settings from the command line.
struct AtlasRequest
{
  Packer Algorithm = Packer::Best;
  glm::ivec3 MaxDims{ 2048 };
  std::size_t MaxBytes = 0;
};

AtlasRequest ParseAtlasRequest(const Arguments& a)
{
  AtlasRequest r;
  try
  {
    r.Algorithm = ParsePacker(a.Get("packer", "best"));
  }
  catch (const std::invalid_argument& e)
  {
    throw UsageError{ e.what() };
  }
  const double size = a.GetNumber("max-3d-texture-size", 2048);
  const double budget = a.GetNumber("atlas-budget-mb", 0);
  if (size < 1 || budget < 0)
  {
    throw UsageError{ "--max-3d-texture-size and --atlas-budget-mb must be positive" };
  }
  r.MaxDims = AtlasLimits(static_cast<int>(size));
  r.MaxBytes = static_cast<std::size_t>(budget * 1024.0 * 1024.0);
  return r;
}

Json AtlasJson(const AtlasLayout& layout)
{
  return Json{ { "packer", layout.PackerName },
    { "dims", { layout.Dims.x, layout.Dims.y, layout.Dims.z } },
    { "used_texels", layout.UsedTexels }, { "total_texels", layout.TotalTexels },
    { "efficiency", layout.Efficiency },
    { "bytes", layout.TotalTexels * static_cast<int64_t>(AtlasTexelBytes) } };
}

const char* const ViewHelp =
  "View options (conventions of VTK's vtkCamera/vtkVolumeProperty; see README):\n"
  "  --size WxH                  image size (default 512x512)\n"
  "  --azimuth A --elevation E   degrees, applied after ResetCamera (default 30, 20)\n"
  "  --zoom Z                    vtkCamera::Zoom factor (default 1)\n"
  "  --tf PRESET                 transfer function: default, grey, hot, grey-opaque, sparse\n"
  "  --scale auto|linear|log     scalar mapping; auto = log10 when the data is positive and\n"
  "                              spans more than 3 decades (default auto)\n"
  "  --unit-distance D           ScalarOpacityUnitDistance in world units (default: diagonal/100)\n"
  "  --sample-factor F           samples per cell of each segment's level = 1/F (default 1)\n"
  "  --reference-sample-factor F step of the reference in finest-cell edges (default 0.5)\n"
  "  --lod PIXELS                level-of-detail threshold in pixels (default 0 = off)\n"
  "  --blend MODE                composite (default), maximum, minimum, average intensity or\n"
  "                              iso (iso-surfaces)\n"
  "  --threads N                 CPU threads (default: all cores)\n"
  "  --opacity-threshold T       early ray termination: a composite ray stops at opacity T\n"
  "                              (default 0.999; 1 = never early)\n"
  "  --empty-space-skipping on|off  skip data nodes whose value range is transparent\n"
  "                              (kD-tree methods, composite; default on; the reference never\n"
  "                              skips)\n"
  "  --interpolation nearest|smooth  cell-centred data: nearest cell (default) or the smooth\n"
  "                              dual-cell reconstruction across grids and levels (packing,\n"
  "                              CPU methods and the reference)\n"
  "  --view-json FILE            camera, transfer function and background from a JSON file\n"
  "                              (e.g. written from ParaView; see README) instead of the\n"
  "                              conventions above; its transfer function implies --scale linear\n"
  "  --shade on|off              gradient shading, vtkVolumeProperty's defaults (default off)\n"
  "  --iso F[,F...]              with --blend iso: iso-values as fractions of the transfer\n"
  "                              function's range, at most 8 (default 0.5)\n"
  "  --shadows STEP              shadow rays, step in world units (default 0 = off)\n"
  "  --light X,Y,Z               a point light at this world position (default: headlight)\n"
  "  --crop X0,X1,Y0,Y1,Z0,Z1    integrate the rays inside this world box only\n"
  "                              (vtkVolumeMapper's cropping of the central sub-volume)\n";

LoadedDataset Load(const Arguments& a, bool needValues, bool needVTK)
{
  DatasetRequest r;
  r.Spec = a.Positional.size() > 1 ? a.Positional[1] : DefaultDataset;
  r.Array = a.Get("array", "");
  r.Component = static_cast<int>(a.GetNumber("component", -1));
  r.Centering = a.Get("centering", "auto");
  r.NeedValues = needValues;
  r.NeedVTK = needVTK;
  if (a.Has("allow-partial") && a.Has("strict"))
  {
    throw UsageError{ "--allow-partial and --strict contradict each other" };
  }
  r.AllowPartial = a.Has("allow-partial");
  r.ReadTimeoutSeconds = a.GetNumber("read-timeout", 120.0);
  if (!(r.ReadTimeoutSeconds > 0.0))
  {
    throw UsageError{ "--read-timeout must be a positive number of seconds" };
  }
  return LoadDataset(r);
}

/// Maps the scalars for display (log10 when asked, or automatically for non-negative data whose
/// positive values span more than 3 decades; zeros map to the smallest positive value) and
/// returns their range.
void PrepareScalars(Hierarchy& h, const std::string& scale, double& lo, double& hi)
{
  lo = std::numeric_limits<double>::max();
  hi = -std::numeric_limits<double>::max();
  double minPositive = std::numeric_limits<double>::max();
  for (const GridValues& v : h.Values)
  {
    for (float x : v)
    {
      if (std::isfinite(x))
      {
        lo = std::min(lo, static_cast<double>(x));
        hi = std::max(hi, static_cast<double>(x));
        if (x > 0.0f)
        {
          minPositive = std::min(minPositive, static_cast<double>(x));
        }
      }
    }
  }
  if (lo > hi)
  {
    throw DatasetError("the array '" + h.ArrayName + "' has no finite value");
  }
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
  if (!(hi > 0.0))
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

void Bounds(const Hierarchy& h, glm::dvec3& lo, glm::dvec3& hi)
{
  lo = h.WorldLo(h.RootCells(), 0);
  hi = h.WorldHi(h.RootCells(), 0);
}

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
///                            "unit_distance": u },
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
    }
    if (j.contains("light"))
    {
      const Json& l = j.at("light");
      v.HasLight = true;
      v.LightPosition = JsonVector3(l.at("position"), "light.position");
      v.LightFocalPoint = JsonVector3(l.at("focal_point"), "light.focal_point");
      v.LightPositional = l.value("positional", false);
      v.LightColour = l.contains("colour") ? JsonVector3(l.at("colour"), "light.colour")
                                           : glm::dvec3(1.0);
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
void ApplyExplicitLighting(const ExplicitView& v, const Arguments& a, RenderSettings& s)
{
  if (v.HasLight)
  {
    if (a.Has("light"))
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
    if (s.Blend != BlendMode::IsoSurface || a.Has("iso"))
    {
      throw UsageError{ "--view-json iso_values need --blend iso and no --iso" };
    }
    s.IsoValues = v.IsoValues;
  }
}

} // namespace

RenderSettings MakeSettings(Hierarchy& h, const Arguments& a, glm::dvec2* range)
{
  ExplicitView explicitView;
  if (a.Has("view-json"))
  {
    explicitView = ReadViewJson(a.Get("view-json", ""));
    if (explicitView.HasCamera && (a.Has("azimuth") || a.Has("elevation") || a.Has("zoom")))
    {
      throw UsageError{ "--azimuth, --elevation and --zoom cannot change a --view-json camera" };
    }
    if (explicitView.HasTransfer && a.Has("tf"))
    {
      throw UsageError{ "--tf cannot be combined with a --view-json transfer function" };
    }
  }
  RenderSettings s;
  const std::string size = a.Get("size", "512x512");
  const std::size_t x = size.find('x');
  try
  {
    if (x == std::string::npos)
    {
      throw std::invalid_argument(size);
    }
    s.Width = std::stoi(size.substr(0, x));
    s.Height = std::stoi(size.substr(x + 1));
  }
  catch (const std::exception&)
  {
    throw UsageError{ "--size expects WxH, got '" + size + "'" };
  }
  if (s.Width < 1 || s.Height < 1 || s.Width > 16384 || s.Height > 16384)
  {
    throw UsageError{ "--size must be between 1x1 and 16384x16384" };
  }
  glm::dvec3 lo, hi;
  Bounds(h, lo, hi);
  if (explicitView.HasCamera)
  {
    s.View = explicitView.View;
  }
  else
  {
    s.View = Camera::ResetTo(lo, hi);
    s.View.Azimuth(a.GetNumber("azimuth", 30.0));
    s.View.Elevation(a.GetNumber("elevation", 20.0));
    s.View.OrthogonalizeViewUp();
    s.View.Zoom(a.GetNumber("zoom", 1.0));
  }
  if (explicitView.HasBackground)
  {
    s.Background = explicitView.Background;
  }
  double vlo, vhi;
  // an explicit transfer function is written in the data's own values
  PrepareScalars(h, a.Get("scale", explicitView.HasTransfer ? "linear" : "auto"), vlo, vhi);
  if (range)
  {
    *range = glm::dvec2(vlo, vhi);
  }
  const double fileUnit = explicitView.HasTransfer ? explicitView.Transfer.UnitDistance : 0.0;
  const double unit =
    a.GetNumber("unit-distance", fileUnit > 0.0 ? fileUnit : glm::length(hi - lo) / 100.0);
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
      s.Transfer = TransferFunction::Preset(a.Get("tf", "default"), vlo, vhi, unit);
    }
    catch (const std::invalid_argument& e)
    {
      throw UsageError{ e.what() };
    }
  }
  s.SampleDistanceFactor = a.GetNumber("sample-factor", 1.0);
  s.ReferenceSampleFactor = a.GetNumber("reference-sample-factor", 0.5);
  if (!(s.SampleDistanceFactor > 0.0) || !(s.ReferenceSampleFactor > 0.0))
  {
    throw UsageError{ "sample factors must be positive" };
  }
  s.LodThresholdPixels = static_cast<float>(a.GetNumber("lod", 0.0));
  const std::string blend = a.Get("blend", "composite");
  if (blend == "composite")
  {
    s.Blend = BlendMode::Composite;
  }
  else if (blend == "maximum")
  {
    s.Blend = BlendMode::Maximum;
  }
  else if (blend == "minimum")
  {
    s.Blend = BlendMode::Minimum;
  }
  else if (blend == "average")
  {
    s.Blend = BlendMode::Average;
  }
  else if (blend == "iso")
  {
    s.Blend = BlendMode::IsoSurface;
  }
  else
  {
    throw UsageError{ "--blend must be composite, maximum, minimum, average or iso" };
  }
  ApplyLightingOptions(s, a, vlo, vhi);
  ApplyExplicitLighting(explicitView, a, s);
  s.Threads = static_cast<int>(a.GetNumber("threads", 0.0));
  s.OpacityThreshold = a.GetNumber("opacity-threshold", 0.999);
  if (!(s.OpacityThreshold >= 0.0 && s.OpacityThreshold <= 1.0))
  {
    throw UsageError{ "--opacity-threshold must be between 0 and 1" };
  }
  const std::string skipping = a.Get("empty-space-skipping", "on");
  if (skipping != "on" && skipping != "off")
  {
    throw UsageError{ "--empty-space-skipping must be on or off" };
  }
  s.SkipEmptySpace = skipping == "on";
  const std::string interpolation = a.Get("interpolation", "nearest");
  if (interpolation != "nearest" && interpolation != "smooth")
  {
    throw UsageError{ "--interpolation must be nearest or smooth" };
  }
  s.SmoothCellData = interpolation == "smooth";
  if (a.Has("crop"))
  {
    const std::vector<double> c = a.GetNumbers("crop", "");
    if (c.size() != 6 || c[0] > c[1] || c[2] > c[3] || c[4] > c[5])
    {
      throw UsageError{ "--crop expects X0,X1,Y0,Y1,Z0,Z1 with X0 <= X1, Y0 <= Y1, Z0 <= Z1" };
    }
    s.Clip = true;
    s.ClipLo = glm::dvec3(c[0], c[2], c[4]);
    s.ClipHi = glm::dvec3(c[1], c[3], c[5]);
  }
  return s;
}

namespace
{

void WritePng(const Image& img, const std::string& path)
{
  vtkNew<vtkImageData> data;
  data->SetDimensions(img.Width, img.Height, 1);
  vtkNew<vtkUnsignedCharArray> rgb;
  rgb->SetNumberOfComponents(3);
  rgb->SetNumberOfTuples(static_cast<vtkIdType>(img.Width) * img.Height);
  const std::vector<std::uint8_t> bytes = img.Rgb8();
  std::copy(bytes.begin(), bytes.end(), rgb->GetPointer(0));
  data->GetPointData()->SetScalars(rgb);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    throw DatasetError("cannot write " + path);
  }
}

Json BoxJson(const glm::dvec3& lo, const glm::dvec3& hi)
{
  return Json::array({ lo.x, hi.x, lo.y, hi.y, lo.z, hi.z });
}

Json TextureJson(const UIntTexture3D& t)
{
  return Json{ { "dims", { t.Dims.x, t.Dims.y, t.Dims.z } }, { "bytes", t.Bytes() } };
}

bool WantsHelp(const Arguments& a)
{
  return a.Has("help");
}

} // namespace

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


int RunInspect(int argc, char** argv)
{
  const char* help =
    "usage: amrsp inspect [DATASET] [--json] [--array NAME] [--packer P] [--compare-packers]\n"
    "Loads the hierarchy, builds and encodes the kD-tree, checks its invariants, packs the\n"
    "bricks (layout only, no data copied) and prints the statistics (with --json: one JSON\n"
    "object; see README for the fields). --compare-packers adds the layout of every packer.\n";
  try
  {
    const Arguments a = ParseArguments(
      argc, argv, 1, Concat({ DatasetOptions, AtlasOptions }),
      Concat({ DatasetFlags, { "json", "compare-packers" } }));
    if (WantsHelp(a))
    {
      std::cout << help << AtlasHelp << DatasetHelp;
      return 0;
    }
    const AtlasRequest atlasRequest = ParseAtlasRequest(a);
    LoadedDataset d = Load(a, false, false);
    const Hierarchy& h = d.Data;

    auto t0 = Clock::now();
    const KdTree tree = BuildKdTree(h);
    const double kdSeconds = Seconds(t0);
    t0 = Clock::now();
    const EncodedKdTree enc = EncodeKdTree(h, tree);
    const double encodeSeconds = Seconds(t0);
    const InvariantReport inv = CheckKdTree(h, tree, &enc);
    const KdTreeStatistics st = tree.Statistics();
    const bool vertexBricks = h.VertexCentred || a.Get("centering", "auto") == "vertex";
    const std::vector<glm::ivec3> extents = BrickExtents(h, vertexBricks);
    Json atlas, byPacker = Json::object();
    double packSeconds = 0.0;
    try
    {
      const AtlasLayout layout = PackBricks(extents, atlasRequest.Algorithm, atlasRequest.MaxDims,
        static_cast<int64_t>(atlasRequest.MaxBytes / AtlasTexelBytes));
      atlas = AtlasJson(layout);
      packSeconds = layout.Seconds;
    }
    catch (const PackingError& e)
    {
      atlas = Json{ { "error", e.what() } };
    }
    if (a.Has("compare-packers"))
    {
      for (Packer p : { Packer::NextFitDecreasingHeight, Packer::Best })
      {
        try
        {
          const AtlasLayout layout = PackBricks(extents, p, atlasRequest.MaxDims,
            static_cast<int64_t>(atlasRequest.MaxBytes / AtlasTexelBytes));
          byPacker[PackerName(p)] = AtlasJson(layout);
          byPacker[PackerName(p)]["seconds"] = layout.Seconds;
        }
        catch (const PackingError& e)
        {
          byPacker[PackerName(p)] = Json{ { "error", e.what() } };
        }
      }
    }

    std::vector<int64_t> perLevel(static_cast<std::size_t>(h.NumberOfLevels()), 0);
    for (const Grid& g : h.Grids)
    {
      ++perLevel[g.Level];
    }
    Json ratios = Json::array();
    for (int l = 1; l < h.NumberOfLevels(); ++l)
    {
      const glm::ivec3 r = h.RefinementRatio[l];
      ratios.push_back({ r.x, r.y, r.z });
    }
    glm::dvec3 lo, hi;
    Bounds(h, lo, hi);
    Json j;
    j["dataset"] = d.Spec;
    j["format"] = d.Format;
    j["array"] = h.ArrayName;
    j["levels"] = h.NumberOfLevels();
    j["grids"] = h.Grids.size();
    j["grids_per_level"] = perLevel;
    j["cells"] = h.TotalCells();
    j["bounds"] = BoxJson(lo, hi);
    j["origin"] = { h.Origin.x, h.Origin.y, h.Origin.z };
    j["spacing0"] = { h.Spacing0.x, h.Spacing0.y, h.Spacing0.z };
    j["refinement_ratios"] = ratios;
    j["kd_nodes"] = st.Nodes;
    j["kd_data_nodes"] = st.DataNodes;
    j["node_types"] = { { "a", st.Refined }, { "b", st.Leaves }, { "c", st.Mixed },
      { "empty", st.Empty } };
    j["kd_depth"] = st.Depth;
    j["tree_texture"] = TextureJson(enc.Tree);
    j["data_nodes_texture"] = TextureJson(enc.DataNodes);
    j["centering"] = vertexBricks ? "vertex" : "cell";
    j["atlas"] = atlas;
    {
      // the paper's Table 2 "GPU memory": tree textures + grid data, for either storage
      const std::size_t treeBytes = KdTreeTextureBytes(enc.Tree, enc.DataNodes);
      std::size_t brickBytes = 0;
      for (const glm::ivec3& e : extents)
      {
        brickBytes += static_cast<std::size_t>(e.x) * e.y * e.z * AtlasTexelBytes;
      }
      Json memory;
      memory["tree"] = treeBytes;
      if (atlas.contains("total_texels"))
      {
        memory["packing"] = treeBytes + atlas["total_texels"].get<std::size_t>() * AtlasTexelBytes;
      }
      else
      {
        memory["packing"] = nullptr;
      }
      memory["bindless"] = treeBytes + brickBytes + HandleTextureBytes(extents.size());
      j["gpu_bytes"] = memory;
    }
    if (a.Has("compare-packers"))
    {
      j["atlas_by_packer"] = byPacker;
    }
    j["times_s"] = { { "load", d.LoadSeconds }, { "kdtree", kdSeconds },
      { "encode", encodeSeconds }, { "pack", packSeconds } };
    j["invariants"] = { { "ok", inv.Ok }, { "failure_count", inv.FailureCount },
      { "failures", inv.Failures } };

    if (a.Has("json"))
    {
      std::cout << j.dump(2) << "\n";
    }
    else
    {
      std::cout << "dataset      " << d.Spec << " (" << d.Format << "), array "
                << (h.ArrayName.empty() ? "-" : h.ArrayName) << "\n"
                << "levels       " << h.NumberOfLevels() << "\n"
                << "grids        " << h.Grids.size() << " per level " << j["grids_per_level"].dump()
                << "\n"
                << "cells        " << h.TotalCells() << "\n"
                << "bounds       " << j["bounds"].dump() << "\n"
                << "kD nodes     " << st.Nodes << " (data nodes " << st.DataNodes << "; types a "
                << st.Refined << ", b " << st.Leaves << ", c " << st.Mixed << ", empty " << st.Empty
                << "; depth " << st.Depth << ")\n"
                << "textures     tree " << j["tree_texture"].dump() << ", data nodes "
                << j["data_nodes_texture"].dump() << "\n"
                << "atlas        " << atlas.dump() << "\n"
                << "GPU memory   " << j["gpu_bytes"].dump()
                << " (bytes: tree textures + grid data, per storage)\n"
                << "times (s)    load " << d.LoadSeconds << ", kD-tree " << kdSeconds
                << ", encode " << encodeSeconds << ", pack " << packSeconds << "\n"
                << "invariants   " << (inv.Ok ? "ok" : "FAILED") << "\n";
      for (const std::string& f : inv.Failures)
      {
        std::cout << "  " << f << "\n";
      }
    }
    return inv.Ok ? 0 : 3;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp inspect --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
}

namespace
{
int RunImageCommand(int argc, char** argv, bool reference)
{
  const std::string name = reference ? "reference" : "render";
  const std::string help = "usage: amrsp " + name +
    " [DATASET] [-o FILE.png] [view options] [dataset options]\n" +
    (reference
        ? "Renders the independent CPU reference image: no kD-tree; each sample finds the finest\n"
          "cell containing it directly from the hierarchy's boxes.\n"
        : "Renders the dataset with one of the kD-tree raycasters and prints which method\n"
          "rendered. Methods: cpu-kdtree (the CPU traversal of the encoded tree textures that\n"
          "mirrors the GLSL shader, sampling the grids), cpu-packing (the same, sampling the\n"
          "packed atlas through the data nodes' offsets, as the packing shader does), packing\n"
          "(vtkSinglePassAMRVolumeMapper on the GPU: one packed R32F atlas, offscreen\n"
          "vtkRenderWindow; needs an X display here), multipass (vtkMultiPassAMRVolumeMapper,\n"
          "the paper's multi-pass baseline: the kD-tree ordered on the CPU, one draw per data\n"
          "node blended front to back; same atlas, same display needs), bindless (the same\n"
          "mapper with one texture per brick through GL_ARB_bindless_texture handles; where the\n"
          "context lacks the extension it renders with the atlas and says so).\n"
          "  --method M                  auto (default: packing where an OpenGL context can be\n"
          "                              had, else cpu-packing), packing, bindless, cpu-packing,\n"
          "                              cpu-kdtree, multipass\n"
          "  --bindless-access A         auto (default), direct or waterfall (see README)\n"
          "  --compare                   also render the CPU reference and the CPU kD-tree\n"
          "                              image and print the RMSE (0-255) against them\n");
  try
  {
    std::vector<std::string> valueOptions =
      Concat({ DatasetOptions, ViewOptions, AtlasOptions, { "output" } });
    valueOptions.push_back("repeat");
    if (!reference)
    {
      valueOptions.push_back("method");
      valueOptions.push_back("bindless-access");
      valueOptions.push_back("driver");
      valueOptions.push_back("backend");
    }
    const Arguments a = ParseArguments(argc, argv, 1, valueOptions,
      Concat({ DatasetFlags,
        reference ? std::vector<std::string>{ "stats" }
                  : std::vector<std::string>{ "compare", "stats" } }));
    if (WantsHelp(a))
    {
      std::cout << help << "  -o, --output FILE           PNG to write (default " << name
                << ".png)\n"
                << "  --repeat N                  render N timed frames after the first (default\n"
                   "                              1); prints their mean and minimum time\n"
                   "  --stats                     print the work counters (CPU: samples, skipped\n"
                   "                              segments and samples, terminated rays; packing:\n"
                   "                              transparent data nodes)\n"
                << ViewHelp << (reference ? "" : AtlasHelp) << (reference ? "" : DriverHelp)
                << DatasetHelp;
      return 0;
    }
    if (a.Positional.size() > 2)
    {
      throw UsageError{ "unexpected argument '" + a.Positional[2] + "'" };
    }
    std::string method = a.Get("method", "auto");
    if (!reference && method != "auto" && method != "cpu-kdtree" && method != "cpu-packing" &&
      method != "packing" && method != "bindless" && method != "multipass")
    {
      throw UsageError{ "unknown --method '" + method +
        "' (available in this build: auto, cpu-kdtree, cpu-packing, packing, bindless, "
        "multipass)" };
    }
    const std::string bindlessAccess = a.Get("bindless-access", "auto");
    if (bindlessAccess != "auto" && bindlessAccess != "direct" && bindlessAccess != "waterfall")
    {
      throw UsageError{ "unknown --bindless-access '" + bindlessAccess +
        "' (auto, direct or waterfall)" };
    }
    if (!reference)
    {
      SelectDriver(a.Get("driver", "default"));
      SelectBackend(a.Get("backend", "auto"));
    }
    if (!reference && method == "auto")
    {
      // the GPU mapper where an OpenGL context can be had, else its CPU mirror (said once)
      std::string why;
      method = PackingRenderer::Available(why) ? "packing" : "cpu-packing";
      if (method != "packing")
      {
        std::cerr << "amrsp: note: no OpenGL context for the GPU mapper (" << why
                  << "); rendering with cpu-packing\n";
      }
    }
    const AtlasRequest atlasRequest = ParseAtlasRequest(a);
    const std::string output = a.Get("output", name + ".png");
    LoadedDataset d = Load(a, true, false);
    glm::dvec2 range;
    RenderSettings s = MakeSettings(d.Data, a, &range);
    const int repeat = static_cast<int>(a.GetNumber("repeat", 1.0));
    if (repeat < 1)
    {
      throw UsageError{ "--repeat must be at least 1" };
    }
    RenderStats stats;
    s.Stats = &stats;
    std::vector<double> frameMs; // the timed frames
    std::ostringstream statsReport;

    auto t0 = Clock::now();
    Image img;
    double preprocess = 0.0;
    double renderSeconds = 0.0;
    std::ostringstream gpuReport;
    if (reference)
    {
      for (int k = 0; k < repeat; ++k)
      {
        t0 = Clock::now();
        img = RenderReference(d.Data, s);
        frameMs.push_back(1000.0 * Seconds(t0));
      }
    }
    else if (method == "packing" || method == "bindless" || method == "multipass")
    {
      std::unique_ptr<GpuRenderer> gpu;
      MultipassRenderer* multipass = nullptr;
      PackingRenderer* singlePass = nullptr;
      if (method == "multipass")
      {
        multipass = new MultipassRenderer(d.Data, s, ViewOf(a));
        gpu.reset(multipass);
      }
      else
      {
        singlePass = new PackingRenderer(d.Data, s, ViewOf(a), method, bindlessAccess);
        gpu.reset(singlePass);
      }
      GpuRenderer& r = *gpu;
      double firstMs = 0.0, ms = 0.0;
      r.Render(0.0, firstMs); // converts, builds, packs, uploads and compiles
      for (int k = 0; k < repeat; ++k)
      {
        img = r.Render(0.0, ms);
        frameMs.push_back(ms);
      }
      preprocess = r.BuildSeconds() + r.UploadSeconds();
      if (!multipass)
      {
        auto* packing = static_cast<PackingRenderer*>(gpu.get());
        statsReport << "stats: transparent data nodes "
                    << packing->GetMapper()->GetNumberOfTransparentDataNodes() << " of "
                    << packing->GetMapper()->GetNumberOfDataNodes() << " (skipping "
                    << (packing->GetMapper()->GetEmptySpaceSkipping() ? "on" : "off")
                    << ", opacity threshold " << packing->GetMapper()->GetOpacityThreshold()
                    << ")\n";
      }
      const double cameraDifference = CameraDifference(r.LastCamera(), s.View);
      if (singlePass)
      {
        const std::string used = singlePass->StorageUsed();
        if (method == "bindless" && used.rfind("bindless", 0) != 0)
        {
          std::cerr << "amrsp: note: bindless textures cannot be used here ("
                    << singlePass->BindlessFallbackReason()
                    << "; on a CPU try --driver zink); rendered with the packed atlas\n";
          method = "packing";
        }
        gpuReport << "storage: " << used << "; textures for packing "
                  << singlePass->PackedBytes() / (1024.0 * 1024.0) << " MiB, for bindless "
                  << singlePass->BindlessBytes() / (1024.0 * 1024.0) << " MiB\n";
      }
      gpuReport << "device: " << r.Device() << "\n"
                << "backend: " << r.Backend() << " (VTK " << VtkVersion() << ", ParaView "
                << ParaViewVersion() << ")\n"
                << "atlas: "
                << (singlePass && method == "bindless" ? "not used (bindless)"
                                                       : r.AtlasDimensions() + " texels")
                << ", textures " << r.TextureBytes() / (1024.0 * 1024.0) << " MiB\n"
                << "mapper (s): build " << r.BuildSeconds() << " (conversion, kD-tree, packing"
                << (multipass ? "" : ", encoding") << "; done in GetBounds), upload "
                << r.UploadSeconds() << "; first frame " << firstMs / 1000.0
                << " (upload, shader compile, render)\n";
      if (multipass)
      {
        gpuReport << "passes: " << multipass->Passes()
                  << " draws (data nodes, front to back), ordering on the CPU "
                  << multipass->OrderSeconds() * 1000.0 << " ms\n";
      }
      gpuReport << "camera: VTK's camera and the tool's conventions "
                << (cameraDifference < 1e-6 ? "agree" : "DIFFER") << " (relative difference "
                << cameraDifference << ")\n";
    }
    else if (method == "cpu-kdtree")
    {
      const EncodedKdTree enc = EncodeKdTree(d.Data, BuildKdTree(d.Data));
      const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(d.Data, enc);
      s.DataNodeRanges = &ranges;
      preprocess = Seconds(t0);
      for (int k = 0; k < repeat; ++k)
      {
        t0 = Clock::now();
        img = RenderKdTree(d.Data, enc, s);
        frameMs.push_back(1000.0 * Seconds(t0));
      }
    }
    else
    {
      const BrickAtlas atlas = BuildBrickAtlas(
        d.Data, atlasRequest.Algorithm, atlasRequest.MaxDims, atlasRequest.MaxBytes);
      const EncodedKdTree enc = EncodeKdTree(d.Data, BuildKdTree(d.Data), &atlas.Layout.Origins);
      const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(d.Data, enc);
      s.DataNodeRanges = &ranges;
      preprocess = Seconds(t0);
      std::cout << "atlas: " << AtlasJson(atlas.Layout).dump() << "\n";
      for (int k = 0; k < repeat; ++k)
      {
        t0 = Clock::now();
        img = RenderKdTree(d.Data, enc, s, &atlas);
        frameMs.push_back(1000.0 * Seconds(t0));
      }
    }
    if (method != "packing" && method != "bindless" && method != "multipass")
    {
      statsReport << "stats: rays " << stats.Rays << ", samples " << stats.Samples
                  << ", data segments " << stats.DataSegments << ", skipped segments "
                  << stats.SkippedSegments << " (" << stats.SkippedSamples
                  << " samples), rays terminated early " << stats.TerminatedRays;
      if (stats.Segments > 0)
      {
        statsReport << ", traversal segments " << stats.Segments << " (tree levels descended "
                    << "per segment " << double(stats.DescentLevels) / double(stats.Segments)
                    << ")";
      }
      statsReport << "\n";
    }
    s.Stats = nullptr;
    s.DataNodeRanges = nullptr;
    double meanMs = 0.0, minMs = frameMs.empty() ? 0.0 : frameMs.front();
    for (double ms : frameMs)
    {
      meanMs += ms / static_cast<double>(frameMs.size());
      minMs = std::min(minMs, ms);
    }
    renderSeconds = meanMs / 1000.0;
    WritePng(img, output);
    std::cout << "method: " << (reference ? "cpu-reference" : method) << "\n"
              << "dataset: " << d.Spec << " (" << d.Format << "), array " << d.Data.ArrayName
              << ", " << d.Data.Grids.size() << " grids, " << d.Data.NumberOfLevels()
              << " levels\n"
              << "scalars: " << d.Data.ArrayName << " in [" << range.x << ", " << range.y
              << "], transfer function '"
              << (a.Has("view-json") && !a.Has("tf") ? "view-json" : a.Get("tf", "default"))
              << "'\n"
              << "image: " << output << " (" << s.Width << "x" << s.Height << ")\n"
              << gpuReport.str()
              << "times (s): load " << d.LoadSeconds << ", preprocess " << preprocess
              << ", render " << renderSeconds << "\n";
    if (repeat > 1)
    {
      std::cout << "frames: " << repeat << ", ms mean " << meanMs << ", min " << minMs << "\n";
    }
    if (a.Has("stats"))
    {
      std::cout << statsReport.str();
    }
    if (!reference && a.Has("compare"))
    {
      const Image ref = RenderReference(d.Data, s);
      std::cout << "rmse (0-255) vs cpu-reference: " << Rmse(img, ref);
      if (method != "cpu-kdtree")
      {
        const Image kd = RenderKdTree(d.Data, EncodeKdTree(d.Data, BuildKdTree(d.Data)), s);
        std::cout << ", vs cpu-kdtree: " << Rmse(img, kd);
      }
      if (method == "multipass")
      {
        // the single-pass mapper samples the same segments: the images should agree closely
        PackingRenderer packing(d.Data, s, ViewOf(a));
        double ms = 0.0;
        std::cout << ", vs packing: " << Rmse(img, packing.Render(0.0, ms));
      }
      std::cout << "\n";
    }
    double covered = 0.0;
    for (const glm::vec4& p : img.Pixels)
    {
      covered += p.a > 0.02f ? 1.0 : 0.0;
    }
    if (covered < 0.001 * img.Pixels.size())
    {
      std::cerr << "amrsp: warning: the image is nearly empty: the transfer function gives the "
                   "data almost no opacity (try --scale log, another --array, or a smaller "
                   "--unit-distance)\n";
    }
    return 0;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp " + name + " --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
}
} // namespace

int RunReference(int argc, char** argv)
{
  return RunImageCommand(argc, argv, true);
}

int RunRender(int argc, char** argv)
{
  return RunImageCommand(argc, argv, false);
}

namespace
{
/// Parses "WxH" (both at least `minimum`); throws UsageError naming `option`.
void ParseSize(const std::string& text, const std::string& option, int minimum, int& w, int& h)
{
  char x = 0;
  std::istringstream in(text);
  if (!(in >> w >> x >> h) || x != 'x' || !in.eof() || w < minimum || h < minimum)
  {
    throw UsageError{ "--" + option + " expects WxH with W, H >= " + std::to_string(minimum) +
      ", got '" + text + "'" };
  }
}

std::vector<std::string> SplitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');)
  {
    if (!item.empty())
    {
      items.push_back(item);
    }
  }
  return items;
}

/// --scaling-sizes "GRIDS:LEVELS:CELLS,..." to synthetic:cosmo specs.
std::vector<std::string> ScalingDatasets(const std::string& text, const std::string& seed)
{
  std::vector<std::string> specs;
  for (const std::string& item : SplitList(text))
  {
    std::vector<std::string> parts;
    std::stringstream in(item);
    for (std::string p; std::getline(in, p, ':');)
    {
      parts.push_back(p);
    }
    if (parts.size() != 3 || parts[0].empty() || parts[1].empty() || parts[2].empty())
    {
      throw UsageError{ "--scaling-sizes expects GRIDS:LEVELS:CELLS,... (e.g. 2666:4:19M), got '" +
        item + "'" };
    }
    specs.push_back("synthetic:cosmo:grids=" + parts[0] + ",levels=" + parts[1] +
      ",cells=" + parts[2] + ",seed=" + seed);
  }
  if (specs.empty())
  {
    throw UsageError{ "--scaling-sizes is empty" };
  }
  return specs;
}

const char* const DefaultScalingSizes = "200:4:1M,2666:4:19M,18528:4:33M,39061:13:140M";
} // namespace

int RunBench(int argc, char** argv)
{
  std::ostringstream help;
  help
    << "usage: amrsp bench [DATASET] [--size WxH] [--frames N] [--methods LIST] [--json FILE]\n"
       "                   [--plot FILE.png [--plot-size WxH]] [--rounds R]\n"
       "       amrsp bench --scaling [--scaling-sizes G:L:C,...] [--methods LIST] [--size WxH]\n"
       "                   [--frames N] [--json FILE] [--rounds R]\n"
       "Renders an orbit of N frames (default 8; --scaling: 2) per method in one process, after\n"
       "one untimed warm-up frame per method (build, upload, shader compile: first_frame_ms),\n"
       "each frame ending with glFinish before the clock is read. Prints Markdown: Table 1\n"
       "(grids, levels, cells, kD nodes, kD data nodes) and Table 2 (GPU memory, preprocessing,\n"
       "fps, RMSE/PSNR of frame 0 against the CPU reference) next to the paper's figures when the\n"
       "dataset has one of the paper's sizes. --json FILE (- for stdout instead of Markdown)\n"
       "writes {dataset, image, frames, statistics, methods: {NAME: {fps, ms_mean, ms_median,\n"
       "rmse, psnr, gpu_bytes, preprocess_s: {...}, ...} or {error}}}. --plot writes bar charts\n"
       "of fps, GPU memory and RMSE (--plot-size, default 900x600). --save-images DIR writes\n"
       "frame 0 of every method (METHOD.png) and the CPU reference (reference.png) there.\n"
       "--rounds R (default 1) keeps the GPU methods alive and renders R - 1 more orbits per\n"
       "method, interleaved (order reversed every round), for ratios on a machine whose load\n"
       "drifts: rounds_ms_mean, ms_rounds_median and fps_vs_packing (median of the per-round\n"
       "ratios) per method, and a table of them.\n"
       "--scaling runs synthetic:cosmo at each GRIDS:LEVELS:CELLS of --scaling-sizes (default "
    << DefaultScalingSizes
    << ",\n"
       "the paper's datasets 1-3 and a small one; default size 128x128, methods packing,multipass)\n"
       "and reports how preprocessing and frame time grow; a size that cannot run is a row with\n"
       "its error.\n"
       "Methods (default "
    << DefaultBenchMethods << "):\n";
  for (const auto& m : BenchMethodHelp())
  {
    help << "  " << std::left << std::setw(25) << m.first << m.second << "\n";
  }
  try
  {
    const Arguments a = ParseArguments(argc, argv, 1,
      Concat({ DatasetOptions, ViewOptions,
        { "frames", "methods", "json", "plot", "plot-size", "scaling-sizes", "seed",
          "save-images", "driver", "backend", "rounds" } }),
      Concat({ DatasetFlags, { "scaling" } }));
    if (WantsHelp(a))
    {
      std::cout << help.str() << ViewHelp << DriverHelp << DatasetHelp;
      return 0;
    }
    // every method of the run renders in contexts of this driver (comparable timings)
    SelectDriver(a.Get("driver", "default"));
    SelectBackend(a.Get("backend", "auto"));
    const bool scaling = a.Has("scaling");
    if (scaling && a.Positional.size() > 1)
    {
      throw UsageError{ "--scaling takes no DATASET (it generates synthetic:cosmo at "
                        "--scaling-sizes)" };
    }
    if (!scaling && (a.Has("scaling-sizes") || a.Has("seed")))
    {
      throw UsageError{ "--scaling-sizes and --seed need --scaling" };
    }
    if (scaling && a.Has("plot"))
    {
      throw UsageError{ "--plot draws one dataset's methods; it does not apply to --scaling" };
    }
    if (a.Has("plot-size") && !a.Has("plot"))
    {
      throw UsageError{ "--plot-size needs --plot FILE.png" };
    }
    const double framesValue = a.GetNumber("frames", scaling ? 2 : 8);
    if (framesValue < 1 || framesValue != std::floor(framesValue))
    {
      throw UsageError{ "--frames must be a whole number of at least 1" };
    }
    const double roundsValue = a.GetNumber("rounds", 1);
    if (roundsValue < 1 || roundsValue > 1000 || roundsValue != std::floor(roundsValue))
    {
      throw UsageError{ "--rounds must be a whole number from 1 to 1000" };
    }
    BenchOptions o;
    o.Frames = static_cast<int>(framesValue);
    o.Rounds = static_cast<int>(roundsValue);
    o.ImageFolder = a.Get("save-images", "");
    if (a.Has("save-images") && (scaling || o.ImageFolder.empty()))
    {
      throw UsageError{ "--save-images needs a folder and does not apply to --scaling" };
    }
    if (!o.ImageFolder.empty())
    {
      std::error_code error; // created before the (possibly long) run, so a bad path fails now
      std::filesystem::create_directories(o.ImageFolder, error);
      if (error)
      {
        throw std::runtime_error(
          "cannot create the --save-images folder '" + o.ImageFolder + "': " + error.message());
      }
    }
    o.View = ViewOf(a);
    o.Methods = SplitList(a.Get("methods", scaling ? "packing,multipass" : DefaultBenchMethods));
    if (o.Methods.empty())
    {
      throw UsageError{ "--methods is empty" };
    }
    for (const std::string& m : o.Methods)
    {
      if (!IsBenchMethod(m))
      {
        throw UsageError{ "unknown method '" + m +
          "' in --methods (cpu-kdtree, packing, bindless, multipass, uniform-gpu[:LEVEL], "
          "vtk-amr-resample[:N|:finest])" };
      }
    }
    int plotWidth = 900, plotHeight = 600;
    if (a.Has("plot-size"))
    {
      ParseSize(a.Get("plot-size", ""), "plot-size", 1, plotWidth, plotHeight);
      if (plotWidth < 300 || plotHeight < 200)
      {
        throw UsageError{ "--plot-size must be at least 300x200" };
      }
    }
    const std::string plot = a.Get("plot", "");
    if (a.Has("plot") && (plot.size() < 5 || plot.substr(plot.size() - 4) != ".png"))
    {
      throw UsageError{ "--plot expects a file name ending in .png, got '" + plot + "'" };
    }
    if (a.Has("plot") && !std::ofstream(plot, std::ios::app))
    {
      return Fail("cannot write the plot file '" + plot + "'");
    }
    const std::string jsonPath = a.Get("json", "");
    if (a.Has("json") && jsonPath.empty())
    {
      throw UsageError{ "--json needs a file name (or - for stdout)" };
    }
    Arguments viewArgs = a;
    if (!a.Has("size"))
    {
      viewArgs.Options["size"] = scaling ? "128x128" : "256x256";
    }
    std::string device;
    {
      std::string why;
      device = GpuRenderer::Available(why) ? "" : "no OpenGL here: " + why;
    }

    Json j;
    if (!scaling)
    {
      LoadedDataset d = Load(viewArgs, true, false);
      RenderSettings s = MakeSettings(d.Data, viewArgs);
      const Image reference = RenderReference(d.Data, s);
      j["dataset"] = d.Spec;
      j["image"] = { s.Width, s.Height };
      j["frames"] = o.Frames;
      j["statistics"] = DatasetStatistics(d.Data);
      j["methods"] = RunBenchMethods(d.Data, s, reference, o, j["statistics"]);
    }
    else
    {
      j["dataset"] = "synthetic:cosmo (scaling)";
      j["frames"] = o.Frames;
      j["rows"] = Json::array();
      // the table grows row by row on stdout (a size that exhausts memory may end the process)
      const std::vector<std::string> specs =
        ScalingDatasets(a.Get("scaling-sizes", DefaultScalingSizes), a.Get("seed", "7"));
      int width = 0, height = 0; // checked before the first row (rows catch their own errors)
      ParseSize(viewArgs.Get("size", ""), "size", 1, width, height);
      const bool progressive = jsonPath != "-";
      if (progressive)
      {
        std::string size = viewArgs.Get("size", "");
        if (size.find('x') != std::string::npos)
        {
          size.replace(size.find('x'), 1, "×");
        }
        std::cout << ScalingMarkdownHeader(size, o.Frames) << std::flush;
      }
      for (const std::string& spec : specs)
      {
        Json row;
        row["dataset"] = spec;
        try
        {
          Arguments rowArgs = viewArgs;
          rowArgs.Positional = { "bench", spec };
          LoadedDataset d = Load(rowArgs, true, false);
          RenderSettings s = MakeSettings(d.Data, rowArgs);
          j["image"] = { s.Width, s.Height };
          row["load_s"] = d.LoadSeconds;
          row["statistics"] = DatasetStatistics(d.Data);
          // timings only: no CPU reference image (the plain bench measures the RMSE)
          BenchOptions timingOnly = o;
          timingOnly.CompareImages = false;
          row["methods"] = RunBenchMethods(d.Data, s, Image(), timingOnly, row["statistics"]);
        }
        catch (const std::exception& e)
        {
          row["error"] = e.what();
        }
        catch (const UsageError& e)
        {
          row["error"] = e.Message;
        }
        if (progressive)
        {
          std::cout << ScalingMarkdownRow(row) << std::flush;
        }
        j["rows"].push_back(row);
      }
      if (progressive)
      {
        for (const Json& row : j["rows"])
        {
          if (row.contains("methods") && !RoundsMarkdown(row["methods"]).empty())
          {
            std::cout << "\n`" << row["dataset"].get<std::string>() << "`:\n"
                      << RoundsMarkdown(row["methods"]);
          }
        }
      }
    }
    if (!device.empty())
    {
      j["device"] = device;
    }
    else if (!scaling)
    {
      for (const auto& m : j["methods"].items())
      {
        if (m.value().contains("device"))
        {
          j["device"] = m.value()["device"];
          break;
        }
      }
    }
    // where the run rendered: the window system of the GPU methods and the library versions
    if (!scaling)
    {
      for (const auto& m : j["methods"].items())
      {
        if (m.value().contains("backend"))
        {
          j["backend"] = m.value()["backend"];
          break;
        }
      }
    }
    j["vtk_version"] = VtkVersion();
    j["paraview_version"] = ParaViewVersion();
    if (a.Has("plot"))
    {
      WriteBenchPlot(j, plot, plotWidth, plotHeight);
    }
    if (jsonPath == "-")
    {
      std::cout << j.dump(2) << "\n";
    }
    else
    {
      if (!jsonPath.empty())
      {
        std::ofstream out(jsonPath);
        if (!(out << j.dump(2) << "\n"))
        {
          return Fail("cannot write the JSON file '" + jsonPath + "'");
        }
      }
      if (!scaling)
      {
        std::cout << BenchMarkdown(j);
      }
    }
    return 0;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp bench --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e.what());
  }
}

} // namespace tool
} // namespace amrsp
