// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspJson.h" // first: see AmrspJson.h

#include "AmrspSeries.h"

#include "AmrspCommandShared.h"
#include "AmrspDataset.h"
#include "AmrspDriver.h"
#include "AmrspGpuRenderer.h"
#include "AmrspProgress.h"

#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/SyntheticCosmo.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use
namespace
{

/// a < b comparing runs of digits as numbers (plt9 < plt10).
bool NaturalLess(const std::string& a, const std::string& b)
{
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size())
  {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
      std::isdigit(static_cast<unsigned char>(b[j])))
    {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie])))
      {
        ++ie;
      }
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je])))
      {
        ++je;
      }
      const std::string x = a.substr(i, ie - i), y = b.substr(j, je - j);
      const std::size_t xs = x.find_first_not_of('0'), ys = y.find_first_not_of('0');
      const std::string xv = xs == std::string::npos ? "" : x.substr(xs);
      const std::string yv = ys == std::string::npos ? "" : y.substr(ys);
      if (xv.size() != yv.size())
      {
        return xv.size() < yv.size();
      }
      if (xv != yv)
      {
        return xv < yv;
      }
      i = ie;
      j = je;
      continue;
    }
    if (a[i] != b[j])
    {
      return a[i] < b[j];
    }
    ++i;
    ++j;
  }
  return a.size() - i < b.size() - j;
}

double Median(std::vector<double> v)
{
  if (v.empty())
  {
    return -1.0;
  }
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// One step's hierarchy, its scalars mapped with `scale` as the series' first step's were.
Hierarchy LoadStep(const Arguments& a, const std::string& spec, const std::string& scale)
{
  LoadedDataset d = Load(a, spec, true, false);
  double lo = 0.0, hi = 0.0;
  PrepareScalars(d.Data, scale, lo, hi);
  return std::move(d.Data);
}

/// The first selected step: its hierarchy (scalars mapped), the settings of the whole series,
/// and the scale the later steps use.
struct SeriesStart
{
  Hierarchy Data;
  RenderSettings Settings;
  std::string Scale;
};

SeriesStart StartSeries(const Arguments& a, const std::string& spec)
{
  SeriesStart start;
  LoadedDataset d = Load(a, spec, true, false);
  const std::string name = d.Data.ArrayName;
  start.Settings = MakeSettings(d.Data, a);
  start.Scale = d.Data.ArrayName != name ? "log" : "linear"; // MakeSettings renames log10(...)
  start.Data = std::move(d.Data);
  return start;
}

std::string SeriesArgument(const Arguments& a)
{
  return a.Positional.size() > 1 ? a.Positional[1] : DefaultDataset;
}

} // namespace

std::vector<std::string> SeriesSteps(const std::string& spec)
{
  if (spec.rfind("synthetic:cosmo:", 0) == 0)
  {
    CosmoParameters p;
    try
    {
      p = ParseCosmoParameters(spec.substr(16));
    }
    catch (const std::exception& e)
    {
      throw UsageError{ std::string("bad synthetic:cosmo parameters: ") + e.what() };
    }
    std::vector<std::string> steps;
    for (int s = 0; s < p.Steps; ++s)
    {
      CosmoParameters step = p;
      step.Step = s;
      steps.push_back("synthetic:cosmo:" + FormatCosmoParameters(step));
    }
    return steps;
  }
  if (spec.find_first_of("*?") == std::string::npos)
  {
    return { spec };
  }
  glob_t found{};
  const int status = glob(spec.c_str(), 0, nullptr, &found);
  std::vector<std::string> steps;
  for (std::size_t i = 0; status == 0 && i < found.gl_pathc; ++i)
  {
    steps.emplace_back(found.gl_pathv[i]);
  }
  globfree(&found);
  if (steps.empty())
  {
    throw DatasetError("the series pattern '" + spec + "' matches no file or folder");
  }
  std::sort(steps.begin(), steps.end(), NaturalLess);
  return steps;
}

std::vector<int> SelectSteps(const std::string& time, int count)
{
  const auto number = [&time](const std::string& text) -> int
  {
    std::size_t used = 0;
    int value = -1;
    try
    {
      value = std::stoi(text, &used);
    }
    catch (const std::exception&)
    {
      used = 0;
    }
    if (used == 0 || used != text.size() || value < 0)
    {
      throw UsageError{ "--time takes all, a step N or steps A:B (0-based), not '" + time + "'" };
    }
    return value;
  };
  int first = 0, last = count - 1;
  if (time != "all")
  {
    const std::size_t colon = time.find(':');
    first = number(time.substr(0, colon));
    last = colon == std::string::npos ? first : number(time.substr(colon + 1));
  }
  if (first > last || last >= count)
  {
    throw UsageError{ "--time " + time + " is outside the series' steps 0 to " +
      std::to_string(count - 1) };
  }
  std::vector<int> steps;
  for (int s = first; s <= last; ++s)
  {
    steps.push_back(s);
  }
  return steps;
}

std::string StepOutputPath(const std::string& pattern, int step)
{
  const std::size_t percent = pattern.find('%');
  if (percent != std::string::npos)
  {
    std::vector<char> buffer(pattern.size() + 32);
    std::snprintf(buffer.data(), buffer.size(), pattern.c_str(), step);
    return buffer.data();
  }
  char number[16];
  std::snprintf(number, sizeof(number), "_%04d", step);
  const std::size_t dot = pattern.rfind('.');
  const std::size_t slash = pattern.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return pattern + number;
  }
  return pattern.substr(0, dot) + number + pattern.substr(dot);
}

int RenderSeries(
  const Method& m, std::string method, const Arguments& a, const std::string& bindlessAccess)
{
  const std::vector<std::string> specs = SeriesSteps(SeriesArgument(a));
  const std::vector<int> selected =
    SelectSteps(a.Get("time", "all"), static_cast<int>(specs.size()));
  const std::string pattern = a.Get("output", "render.png");
  std::unique_ptr<GpuRenderer> gpu;
  SeriesStart start;
  for (std::size_t k = 0; k < selected.size(); ++k)
  {
    const int step = selected[k];
    const auto t0 = Clock::now();
    Hierarchy h;
    if (k == 0)
    {
      start = StartSeries(a, specs[static_cast<std::size_t>(step)]);
      h = start.Data;
    }
    else
    {
      h = LoadStep(a, specs[static_cast<std::size_t>(step)], start.Scale);
    }
    const double load = Seconds(t0);
    const auto t1 = Clock::now();
    Image img;
    std::string how = "cpu";
    if (m.NeedsGpu)
    {
      double ms = 0.0;
      if (!gpu)
      {
        gpu = m.Make(method, MethodRequest{ h, start.Settings, ViewOf(a), bindlessAccess });
      }
      else
      {
        gpu->SetData(h);
      }
      const int refreshes = gpu->NumberOfValueRefreshes();
      img = gpu->Render(0.0, ms);
      std::ostringstream what;
      what << (gpu->NumberOfValueRefreshes() > refreshes ? "values refreshed" : "built")
           << " (build " << std::fixed << std::setprecision(3) << gpu->BuildSeconds()
           << " s, upload " << gpu->UploadSeconds() << " s)";
      how = what.str();
    }
    else
    {
      img = RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), start.Settings);
    }
    const double toImage = Seconds(t1);
    const std::string path = StepOutputPath(pattern, step);
    WritePng(img, path);
    std::cout << "step " << step << " (" << k + 1 << " of " << selected.size()
              << "): " << h.Grids.size() << " grids, " << how << ", load " << std::fixed
              << std::setprecision(3) << load << " s, to the image " << toImage << " s -> " << path
              << std::endl;
  }
  std::cout << "method: " << method << "\n";
  return 0;
}

int BenchSeries(const Arguments& a)
{
  const std::vector<std::string> specs = SeriesSteps(SeriesArgument(a));
  if (specs.size() < 2)
  {
    throw UsageError{ "--time-series needs a series of at least 2 steps (synthetic:cosmo:...,"
                      "steps=T or a quoted path pattern with * or ?)" };
  }
  std::stringstream list(a.Get("methods", "packing,multipass"));
  std::vector<std::string> methods;
  for (std::string name; std::getline(list, name, ',');)
  {
    const Method* m = FindMethod(name, BenchCommand);
    if (!m || !m->NeedsGpu || !m->IsKdTreeMapper())
    {
      throw UsageError{ "--time-series measures the GPU mappers (packing, bindless, linear, "
                        "auto-storage, multipass), not '" +
        name + "'" };
    }
    methods.push_back(name);
  }
  std::string why;
  if (!GpuRenderer::Available(why))
  {
    throw GpuError("--time-series needs an OpenGL context: " + why);
  }
  // every step in memory first: the timings start from the step's data
  SeriesStart start = StartSeries(a, specs[0]);
  std::vector<Hierarchy> steps{ start.Data };
  for (std::size_t s = 1; s < specs.size(); ++s)
  {
    steps.push_back(LoadStep(a, specs[s], start.Scale));
  }
  Json j;
  j["dataset"] = SeriesArgument(a);
  j["steps"] = static_cast<int>(steps.size());
  j["size"] = std::to_string(start.Settings.Width) + "x" + std::to_string(start.Settings.Height);
  j["methods"] = Json::object();
  for (const std::string& name : methods)
  {
    const Method& m = *FindMethod(name, BenchCommand);
    std::string method = name;
    std::unique_ptr<GpuRenderer> gpu =
      m.Make(method, MethodRequest{ steps[0], start.Settings, ViewOf(a), "auto" });
    double ms = 0.0;
    gpu->Render(0.0, ms); // the first step, the shaders compiled
    gpu->Render(0.0, ms);
    const double stillMs = ms;
    std::vector<double> switches, rebuilds, switchData, rebuildData;
    Json perStep = Json::array();
    for (std::size_t s = 1; s < steps.size(); ++s)
    {
      gpu->SetData(steps[s]); // the step's data in memory, as a reader's new output
      const int refreshes = gpu->NumberOfValueRefreshes();
      const auto t0 = Clock::now();
      gpu->Render(0.0, ms);
      const double seconds = Seconds(t0);
      const bool refreshed = gpu->NumberOfValueRefreshes() > refreshes;
      (refreshed ? switches : rebuilds).push_back(seconds);
      (refreshed ? switchData : rebuildData).push_back(gpu->BuildSeconds() + gpu->UploadSeconds());
      perStep.push_back({ { "step", s }, { "seconds", seconds }, { "refreshed", refreshed },
        { "build_s", gpu->BuildSeconds() }, { "upload_s", gpu->UploadSeconds() } });
    }
    Json r;
    r["step_switch_s"] = Median(switches);
    r["rebuild_s"] = Median(rebuilds);
    r["still_frame_s"] = stillMs / 1000.0;
    // the mapper's own part of those (build and upload, without the frame's draw)
    r["step_switch_build_upload_s"] = Median(switchData);
    r["rebuild_build_upload_s"] = Median(rebuildData);
    r["switch_over_rebuild"] =
      switches.empty() || rebuilds.empty() ? -1.0 : Median(switches) / Median(rebuilds);
    r["device"] = gpu->Device();
    if (SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(gpu.get()))
    {
      r["storage"] = singlePass->StorageUsed();
      if (m.Kind == MethodKind::Bindless && singlePass->StorageUsed().rfind("bindless", 0) != 0)
      {
        // its figures are the atlas's under bindless's name
        r["error"] =
          "bindless textures are not available: " + singlePass->BindlessFallbackReason() +
          " (on a CPU run with --driver zink)";
      }
    }
    r["per_step"] = perStep;
    j["methods"][name] = r;
  }
  const std::string json = a.Get("json", "");
  if (json == "-")
  {
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  if (!json.empty())
  {
    std::ofstream(json) << j.dump(2) << "\n";
  }
  std::cout << "| method | step_switch_s | rebuild_s | switch ÷ rebuild | build + upload: switch, "
               "rebuild | still frame s |\n"
               "|---|---|---|---|---|---|\n";
  for (const auto& item : j["methods"].items())
  {
    const Json& r = item.value();
    std::cout << "| " << item.key() << " | " << r["step_switch_s"].get<double>() << " | "
              << r["rebuild_s"].get<double>() << " | " << r["switch_over_rebuild"].get<double>()
              << " | " << r["step_switch_build_upload_s"].get<double>() << ", "
              << r["rebuild_build_upload_s"].get<double>() << " | "
              << r["still_frame_s"].get<double>() << " |\n";
  }
  std::cout << "series " << j["dataset"].get<std::string>() << ", " << steps.size() << " steps, "
            << j["size"].get<std::string>() << "\n";
  return 0;
}

} // namespace tool
} // namespace amrsp
