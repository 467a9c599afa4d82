// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspJson.h" // first: see AmrspJson.h

#include "AmrspSeries.h"

#include "AmrspCommandShared.h"
#include "AmrspDataset.h"
#include "AmrspDriver.h"
#include "AmrspGpuRenderer.h"
#include "AmrspProcessResources.h"
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

namespace
{
/// --json FILE writes `j` there; --json - prints it, and then true: the table is left out.
bool WriteJson(const Arguments& a, const Json& j)
{
  const std::string json = a.Get("json", "");
  if (json == "-")
  {
    std::cout << j.dump(2) << "\n";
    return true;
  }
  if (!json.empty())
  {
    std::ofstream(json) << j.dump(2) << "\n";
  }
  return false;
}

/// The span of the values of every step of the series (each step read once).
ScalarSpan SeriesSpan(const Arguments& a, const std::vector<std::string>& specs)
{
  ScalarSpan span;
  for (std::size_t s = 0; s < specs.size(); ++s)
  {
    const LoadedDataset d = Load(a, specs[s], true, false);
    const ScalarSpan step = MeasureScalars(d.Data);
    span = s == 0 ? step : Union(span, step);
  }
  return span;
}
} // namespace

int RenderSeries(const Method& m, std::string method, const Arguments& a,
  BindlessAccess bindlessAccess, const SeriesCompare& compare)
{
  const std::vector<std::string> specs = SeriesSteps(SeriesArgument(a));
  const std::vector<int> selected =
    SelectSteps(a.Get("time", "all"), static_cast<int>(specs.size()));
  const std::string pattern = a.Get("output", "render.png");
  const std::string rangeChoice = a.Get("range", "all");
  // the values the colours span: all steps' (each read once more first), each step's, or given
  std::unique_ptr<ScalarSpan> over;
  if (rangeChoice == "all")
  {
    const auto t0 = Clock::now();
    over.reset(new ScalarSpan(SeriesSpan(a, specs)));
    std::cout << "range: all " << specs.size() << " steps, [" << over->Lo << ", " << over->Hi
              << "] (read in " << std::fixed << std::setprecision(3) << Seconds(t0) << " s)"
              << std::defaultfloat << std::endl;
  }
  std::unique_ptr<GpuRenderer> gpu;
  for (std::size_t k = 0; k < selected.size(); ++k)
  {
    const int step = selected[k];
    const auto t0 = Clock::now();
    LoadedDataset d = Load(a, specs[static_cast<std::size_t>(step)], true, false);
    glm::dvec2 range;
    const RenderSettings settings = MakeSettings(d.Data, a, &range, over.get());
    const Hierarchy& h = d.Data;
    const double load = Seconds(t0);
    const auto t1 = Clock::now();
    Image img;
    std::string how = "cpu";
    if (m.NeedsGpu)
    {
      double ms = 0.0;
      if (!gpu)
      {
        gpu = m.Make(method, MethodRequest{ h, settings, ViewOf(a), bindlessAccess });
      }
      else
      {
        gpu->SetTransferFunction(settings.Transfer);
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
      img = RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), settings);
    }
    const double toImage = Seconds(t1);
    const std::string path = StepOutputPath(pattern, step);
    WritePng(img, path);
    std::cout << "step " << step << " (" << k + 1 << " of " << selected.size()
              << "): " << h.Grids.size() << " grids, " << h.ArrayName << " ["
              << std::setprecision(6) << range.x << ", " << range.y << "], " << how << ", load "
              << std::fixed << std::setprecision(3) << load << " s, to the image " << toImage
              << " s -> " << path << std::defaultfloat << std::endl;
    if (a.Has("compare"))
    {
      compare(img, d, settings);
    }
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
  // every step in memory first: the timings start from the step's data. The colours span
  // every step's values (--range all, as render --time).
  std::vector<LoadedDataset> loaded;
  ScalarSpan span;
  for (std::size_t s = 0; s < specs.size(); ++s)
  {
    loaded.push_back(Load(a, specs[s], true, false));
    const ScalarSpan step = MeasureScalars(loaded.back().Data);
    span = s == 0 ? step : Union(span, step);
  }
  const std::string rangeChoice = a.Get("range", "all");
  if (rangeChoice == "step")
  {
    throw UsageError{ "--time-series renders every step with one transfer function: --range all "
                      "or LO:HI" };
  }
  RenderSettings settings;
  std::vector<Hierarchy> steps;
  for (std::size_t s = 0; s < loaded.size(); ++s)
  {
    const RenderSettings stepSettings =
      MakeSettings(loaded[s].Data, a, nullptr, rangeChoice == "all" ? &span : nullptr);
    if (s == 0)
    {
      settings = stepSettings;
    }
    steps.push_back(std::move(loaded[s].Data));
  }
  loaded.clear();
  Json j;
  j["dataset"] = SeriesArgument(a);
  j["steps"] = static_cast<int>(steps.size());
  j["size"] = std::to_string(settings.Width) + "x" + std::to_string(settings.Height);
  j["methods"] = Json::object();
  for (const std::string& name : methods)
  {
    const Method& m = *FindMethod(name, BenchCommand);
    std::string method = name;
    std::unique_ptr<GpuRenderer> gpu =
      m.Make(method, MethodRequest{ steps[0], settings, ViewOf(a) });
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
      r["storage"] = singlePass->StorageUsedInWords();
      if (m.Kind == MethodKind::Bindless &&
        singlePass->StorageUsed() != DataStorage::BindlessTextures)
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
  if (WriteJson(a, j))
  {
    return 0;
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

int SoakSeries(const Arguments& a)
{
  const std::vector<std::string> specs = SeriesSteps(SeriesArgument(a));
  const double requested = a.GetNumber("soak", 1000.0);
  if (!(requested >= 1.0 && requested <= 1e7))
  {
    throw UsageError{ "--soak takes a number of step changes from 1 to 10^7" };
  }
  const int changes = static_cast<int>(requested);
  const std::string method = a.Get("methods", "packing");
  const Method* m = FindMethod(method, BenchCommand);
  if (!m || !m->NeedsGpu || !m->IsKdTreeMapper())
  {
    throw UsageError{ "--soak runs one GPU mapper (packing, bindless, linear, auto-storage, "
                      "multipass), not '" +
      method + "'" };
  }
  std::string why;
  if (!GpuRenderer::Available(why))
  {
    throw GpuError("--soak needs an OpenGL context: " + why);
  }
  const auto started = Clock::now();
  const ScalarSpan span = SeriesSpan(a, specs);
  // a step as a reader hands it over: read again from its files (or generated) at every change
  const auto readStep = [&a, &specs, &span](int step, RenderSettings* settings)
  {
    LoadedDataset d = Load(a, specs[static_cast<std::size_t>(step)], true, false);
    const RenderSettings s = MakeSettings(d.Data, a, nullptr, &span);
    if (settings)
    {
      *settings = s;
    }
    return std::move(d.Data);
  };
  RenderSettings settings;
  const Hierarchy first = readStep(0, &settings);
  std::string methodName = method;
  std::unique_ptr<GpuRenderer> gpu =
    m->Make(methodName, MethodRequest{ first, settings, ViewOf(a) });
  double ms = 0.0;
  gpu->Render(0.0, ms);
  struct Sample
  {
    long long Resident;
    int Descriptors;
    int Changes;
  };
  const auto sample = [](int done) { return Sample{ ResidentBytes(), OpenDescriptors(), done }; };
  const Sample start = sample(0);
  // warm-up: every step seen twice, at least 10 changes (caches, the driver's shader variants)
  const int warmUp = std::min(changes, std::max(10, 2 * static_cast<int>(specs.size())));
  Sample warm = start;
  std::vector<Json> trace;
  int refreshes = 0, builds = 0;
  for (int i = 1; i <= changes; ++i)
  {
    const int step = i % static_cast<int>(specs.size());
    gpu->SetData(readStep(step, nullptr));
    const int before = gpu->NumberOfValueRefreshes(), buildsBefore = gpu->NumberOfBuilds();
    gpu->Render(3.6 * i, ms); // a camera move with every step change
    refreshes += gpu->NumberOfValueRefreshes() > before;
    builds += gpu->NumberOfBuilds() > buildsBefore;
    if (i == warmUp)
    {
      warm = sample(i);
    }
    if (i % std::max(1, changes / 20) == 0 || i == changes)
    {
      const Sample s = sample(i);
      trace.push_back({ { "changes", i }, { "resident_mib", s.Resident / 1048576.0 },
        { "descriptors", s.Descriptors } });
    }
  }
  const Sample end = sample(changes);
  Json j;
  j["dataset"] = SeriesArgument(a);
  j["method"] = method;
  j["steps"] = static_cast<int>(specs.size());
  j["step_changes"] = changes;
  j["camera_moves"] = changes;
  j["warm_up_changes"] = warmUp;
  j["size"] = std::to_string(settings.Width) + "x" + std::to_string(settings.Height);
  j["value_refreshes"] = refreshes;
  j["builds"] = builds;
  j["seconds"] = Seconds(started);
  j["device"] = gpu->Device();
  j["resident_mib"] = { { "start", start.Resident / 1048576.0 },
    { "after_warm_up", warm.Resident / 1048576.0 }, { "end", end.Resident / 1048576.0 } };
  j["descriptors"] = { { "start", start.Descriptors }, { "after_warm_up", warm.Descriptors },
    { "end", end.Descriptors } };
  j["trace"] = trace;
  if (WriteJson(a, j))
  {
    return 0;
  }
  std::cout << std::fixed << std::setprecision(1) << "soak " << j["dataset"].get<std::string>()
            << " (" << specs.size() << " steps, " << method << ", " << j["size"].get<std::string>()
            << "): " << changes << " step changes and camera moves in " << Seconds(started)
            << " s; resident memory " << start.Resident / 1048576.0 << " MiB at the start, "
            << warm.Resident / 1048576.0 << " after " << warmUp << " changes, "
            << end.Resident / 1048576.0 << " at the end; open descriptors " << start.Descriptors
            << ", " << warm.Descriptors << ", " << end.Descriptors << std::defaultfloat << "\n";
  return 0;
}

} // namespace tool
} // namespace amrsp
