// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspCommandShared.h"

#include "AmrspBench.h"
#include "AmrspSeries.h"
#include "AmrspBenchPlot.h"
#include "AmrspDriver.h"
#include "AmrspMethods.h"
#include "AmrspProgress.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

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

namespace
{
/// The usage text of `amrsp bench` (without the shared view, driver and dataset options).
std::string BenchHelp()
{
  std::ostringstream help;
  help
    << "usage: amrsp bench [DATASET] [--size WxH] [--frames N] [--methods LIST] [--json FILE]\n"
       "                   [--plot FILE.png [--plot-size WxH]] [--rounds R]\n"
       "                   [--interactive [--interactive-rate FPS]] [--counters] [--occupancy]\n"
       "                   [--no-compare]\n"
       "       amrsp bench --scaling [--scaling-sizes G:L:C,...] [--methods LIST] [--size WxH]\n"
       "                   [--frames N] [--json FILE] [--rounds R]\n"
       "       amrsp bench SERIES --time-series [--methods LIST] [--size WxH] [--json FILE]\n"
       "       amrsp bench SERIES --soak N [--methods METHOD] [--size WxH] [--json FILE]\n"
       "Renders an orbit of N frames (default 8; --scaling: 2) per method in one process, after\n"
       "one untimed warm-up frame per method (build, upload, shader compile: first_frame_ms),\n"
       "each frame ending with glFinish before the clock is read. Prints Markdown: Table 1\n"
       "(grids, levels, cells, kD nodes, kD data nodes) and Table 2 (GPU memory, preprocessing,\n"
       "fps, RMSE/PSNR of frame 0 against the CPU reference) next to the paper's figures when the\n"
       "dataset has one of the paper's sizes. --json FILE (- for stdout instead of Markdown)\n"
       "writes {dataset, image, frames, statistics, methods: {NAME: {fps, ms_mean, ms_median,\n"
       "rmse, psnr, gpu_bytes, preprocess_s: {...}, time_to_first_image_s, peak_rss_bytes,\n"
       "...} or {error}}}. --plot writes bar charts of fps, GPU memory and RMSE (--plot-size,\n"
       "default 900x600). --save-images DIR writes\n"
       "frame 0 of every method (METHOD.png) and the CPU reference (reference.png) there.\n"
       "--rounds R (default 1) keeps the GPU methods alive and renders R - 1 more orbits per\n"
       "method, interleaved (order reversed every round), for ratios on a machine whose load\n"
       "drifts: rounds_ms_mean, ms_rounds_median and fps_vs_packing (median of the per-round\n"
       "ratios) per method, and a table of them; fps_vs_multipass likewise. Where the OpenGL\n"
       "context has timer queries every GPU method also reports its GPU time per frame\n"
       "(gpu_ms_mean, gpu_ms_median; with rounds rounds_gpu_ms_mean, gpu_ms_rounds_median).\n"
       "--counters adds to every method that renders the kD-tree a \"work\" object, the cost\n"
       "model of frame 0 counted by the CPU mirror of the shader: segments_per_ray,\n"
       "descent_steps_per_ray, samples_per_ray, texel_fetches_per_ray, steps_per_ray (means;\n"
       "_p95: 95th percentiles), steps_per_pixel, lockstep_steps_per_pixel (8x4 tiles of 32\n"
       "lanes), lockstep_efficiency; multipass also draws and fragments_per_pixel; the\n"
       "single-pass methods also \"gpu\": the shader's own segment, descent and sample totals\n"
       "of the same frame and whether they agree with the mirror's (docs/performance.md).\n"
       "--occupancy adds to every single-pass method an \"occupancy\" object: where the rays of\n"
       "frame 0 ran, through NVIDIA's GL_NV_shader_thread_group (the mapper's\n"
       "OccupancyProbe): {available, caster, rays, sms (distinct multiprocessors), sm_count,\n"
       "warps (distinct multiprocessor and warp-slot pairs), most_warps_on_one_sm}, or\n"
       "{available: false, why} on other drivers.\n"
       "--no-compare renders no CPU reference image (no rmse or psnr): timings and counters\n"
       "only, for sizes where the reference would take long.\n"
       "--interactive draws, after each single-pass method's orbit, every orbit frame as an\n"
       "interactive frame (the render window's DesiredUpdateRate at --interactive-rate, default 5\n"
       "as ParaView's interactive renders) and then still at the same camera: interactive {fps,\n"
       "ms_mean, still_ms_mean, speedup, rmse_mean, rmse_max (0-255, against its still frame),\n"
       "image_sample_distance, sample_distance_scale, allocated_s, still_bit_identical}.\n"
       "--time-series renders the steps of SERIES (synthetic:cosmo:...,steps=T[,regrid=K] or a\n"
       "quoted path pattern with * or ?) in order with one renderer per GPU method (default\n"
       "packing,multipass), all steps in memory first: step_switch_s is the median time from a\n"
       "step's new vtkOverlappingAMR to its first image over the steps whose hierarchy did not\n"
       "change (the mapper uploads the values only), rebuild_s the same over the regrid steps,\n"
       "with switch_over_rebuild, still_frame_s, the mapper's own part step_switch_build_upload_s\n"
       "and rebuild_build_upload_s, storage (single pass; bindless that fell back to the atlas\n"
       "gets an error), and per_step {seconds, refreshed, build_s, upload_s}.\n"
       "--soak N changes the step of SERIES N times (each step read again from its files, as a\n"
       "reader hands it over) and moves the camera with each, through one renderer of METHOD\n"
       "(default packing): resident_mib and descriptors {start, after_warm_up, end}, a trace,\n"
       "value_refreshes, builds, seconds. A dataset without * or ? is a series of one step.\n"
       "--scaling runs synthetic:cosmo at each GRIDS:LEVELS:CELLS of --scaling-sizes (default "
    << DefaultScalingSizes
    << ",\n"
       "the paper's datasets 1-3 and a small one; default size 128x128, methods "
       "packing,multipass)\n"
       "and reports how preprocessing and frame time grow; a size that cannot run is a row with\n"
       "its error.\n"
       "Methods (default "
    << DefaultBenchMethods() << "):\n";
  PrintMethodHelp(help, BenchCommand);
  return help.str();
}

/// What `amrsp bench` was asked for, checked.
struct BenchRequest
{
  bool Scaling = false;
  BenchOptions Options;
  /// The dataset and view arguments, with the default image size filled in.
  Arguments ViewArguments;
  std::string Plot; // PNG of the bar charts ("" for none)
  int PlotWidth = 900;
  int PlotHeight = 600;
  std::string JsonPath; // "" for none, "-" for stdout
};

/// Checks the options of `a` (UsageError naming the problem) and creates the --save-images
/// folder, so that a bad path fails before a long run.
BenchRequest ParseBenchRequest(const Arguments& a)
{
  BenchRequest r;
  const bool scaling = a.Has("scaling");
  r.Scaling = scaling;
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
  BenchOptions& o = r.Options;
  o.Frames = static_cast<int>(framesValue);
  o.Rounds = static_cast<int>(roundsValue);
  if (a.Has("interactive-rate") && !a.Has("interactive"))
  {
    throw UsageError{ "--interactive-rate needs --interactive" };
  }
  if (a.Has("interactive"))
  {
    o.InteractiveRate = a.GetNumber("interactive-rate", 5.0);
    if (!(o.InteractiveRate >= 1.0 && o.InteractiveRate <= 1.0e6) || scaling)
    {
      throw UsageError{ "--interactive takes a --interactive-rate from 1 to 1e6 frames a second "
                        "and does not apply to --scaling" };
    }
  }
  o.Counters = a.Has("counters");
  o.Occupancy = a.Has("occupancy");
  if (o.Occupancy && scaling)
  {
    throw UsageError{ "--occupancy does not apply to --scaling" };
  }
  o.CompareImages = !a.Has("no-compare");
  if (a.Has("no-compare") && a.Has("save-images"))
  {
    throw UsageError{ "--no-compare renders no CPU reference: it does not go with --save-images" };
  }
  if (o.Counters && scaling)
  {
    throw UsageError{ "--counters does not apply to --scaling" };
  }
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
  o.Methods = SplitList(a.Get("methods", scaling ? "packing,multipass" : DefaultBenchMethods()));
  if (o.Methods.empty())
  {
    throw UsageError{ "--methods is empty" };
  }
  for (const std::string& m : o.Methods)
  {
    if (!FindMethod(m, BenchCommand))
    {
      throw UsageError{ "unknown method '" + m + "' in --methods (" + MethodList(BenchCommand) +
        ")" };
    }
  }
  if (a.Has("plot-size"))
  {
    ParseSize(a.Get("plot-size", ""), "plot-size", 1, r.PlotWidth, r.PlotHeight);
    if (r.PlotWidth < 300 || r.PlotHeight < 200)
    {
      throw UsageError{ "--plot-size must be at least 300x200" };
    }
  }
  r.Plot = a.Get("plot", "");
  if (a.Has("plot") && (r.Plot.size() < 5 || r.Plot.substr(r.Plot.size() - 4) != ".png"))
  {
    throw UsageError{ "--plot expects a file name ending in .png, got '" + r.Plot + "'" };
  }
  r.JsonPath = a.Get("json", "");
  if (a.Has("json") && r.JsonPath.empty())
  {
    throw UsageError{ "--json needs a file name (or - for stdout)" };
  }
  r.ViewArguments = a;
  if (!a.Has("size"))
  {
    r.ViewArguments.Options["size"] = scaling ? "128x128" : "256x256";
  }
  return r;
}

/// The methods of one dataset against its CPU reference.
Json BenchDataset(const BenchRequest& r)
{
  LoadedDataset d = Load(r.ViewArguments, true, false);
  RenderSettings s = MakeSettings(d.Data, r.ViewArguments);
  RenderSettings referenceSettings = s;
  referenceSettings.Progress = ProgressOf("reference");
  BenchOptions o = r.Options;
  const Image reference = o.CompareImages ? RenderReference(d.Data, referenceSettings) : Image();
  Json j;
  j["dataset"] = d.Spec;
  j["image"] = { s.Width, s.Height };
  j["frames"] = r.Options.Frames;
  j["statistics"] = DatasetStatistics(d.Data);
  j["methods"] = RunBenchMethods(d.Data, s, reference, o, j["statistics"]);
  return j;
}

/// The methods' timings on synthetic:cosmo at each --scaling-sizes entry, one row each; with
/// Markdown output the table grows row by row on stdout (a size that exhausts memory may end
/// the process).
Json BenchScaling(const BenchRequest& r, const Arguments& a)
{
  Json j;
  j["dataset"] = "synthetic:cosmo (scaling)";
  j["frames"] = r.Options.Frames;
  j["rows"] = Json::array();
  const std::vector<std::string> specs =
    ScalingDatasets(a.Get("scaling-sizes", DefaultScalingSizes), a.Get("seed", "7"));
  int width = 0, height = 0; // checked before the first row (rows catch their own errors)
  ParseSize(r.ViewArguments.Get("size", ""), "size", 1, width, height);
  const bool progressive = r.JsonPath != "-";
  if (progressive)
  {
    std::string size = r.ViewArguments.Get("size", "");
    if (size.find('x') != std::string::npos)
    {
      size.replace(size.find('x'), 1, "×");
    }
    std::cout << ScalingMarkdownHeader(size, r.Options.Frames) << std::flush;
  }
  for (const std::string& spec : specs)
  {
    Json row;
    row["dataset"] = spec;
    try
    {
      Arguments rowArgs = r.ViewArguments;
      rowArgs.Positional = { "bench", spec };
      LoadedDataset d = Load(rowArgs, true, false);
      RenderSettings s = MakeSettings(d.Data, rowArgs);
      j["image"] = { s.Width, s.Height };
      row["load_s"] = d.LoadSeconds;
      row["statistics"] = DatasetStatistics(d.Data);
      // timings only: no CPU reference image (the plain bench measures the RMSE)
      BenchOptions timingOnly = r.Options;
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
  return j;
}

/// Where the run rendered: the device (or why there was none), the window system of the GPU
/// methods and the library versions.
void AddRunContext(Json& j, const std::string& noDevice, bool scaling)
{
  const auto firstMethodWith = [&j](const char* key)
  {
    for (const auto& m : j["methods"].items())
    {
      if (m.value().contains(key))
      {
        j[key] = m.value()[key];
        break;
      }
    }
  };
  if (!noDevice.empty())
  {
    j["device"] = noDevice;
  }
  else if (!scaling)
  {
    firstMethodWith("device");
  }
  if (!scaling)
  {
    firstMethodWith("backend");
  }
  j["vtk_version"] = VtkVersion();
  j["paraview_version"] = ParaViewVersion();
}
} // namespace

int RunBench(int argc, char** argv)
{
  try
  {
    const Arguments a = ParseArguments(argc, argv, 1,
      Concat({ DatasetOptions, RenderOptionNames,
        { "frames", "methods", "json", "plot", "plot-size", "scaling-sizes", "seed", "save-images",
          "driver", "backend", "rounds", "interactive-rate", "soak" } }),
      Concat({ DatasetFlags,
        { "scaling", "interactive", "counters", "occupancy", "no-compare", "time-series" } }));
    if (WantsHelp(a))
    {
      std::cout << BenchHelp() << ViewHelp << DriverHelp << DatasetHelp;
      return 0;
    }
    // every method of the run renders in contexts of this driver (comparable timings)
    SelectDriver(a.Get("driver", "default"));
    SelectBackend(a.Get("backend", "auto"));
    if (a.Has("time-series"))
    {
      return BenchSeries(a);
    }
    if (a.Has("soak"))
    {
      return SoakSeries(a);
    }
    const BenchRequest r = ParseBenchRequest(a);
    if (!r.Plot.empty() && !std::ofstream(r.Plot, std::ios::app))
    {
      return Fail("cannot write the plot file '" + r.Plot + "'");
    }
    std::string noDevice;
    {
      std::string why;
      noDevice = GpuRenderer::Available(why) ? "" : "no OpenGL here: " + why;
    }
    Json j = r.Scaling ? BenchScaling(r, a) : BenchDataset(r);
    AddRunContext(j, noDevice, r.Scaling);
    if (!r.Plot.empty())
    {
      WriteBenchPlot(j, r.Plot, r.PlotWidth, r.PlotHeight);
    }
    if (r.JsonPath == "-")
    {
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    if (!r.JsonPath.empty())
    {
      std::ofstream out(r.JsonPath);
      if (!(out << j.dump(2) << "\n"))
      {
        return Fail("cannot write the JSON file '" + r.JsonPath + "'");
      }
    }
    if (!r.Scaling)
    {
      std::cout << BenchMarkdown(j);
    }
    return 0;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp bench --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e);
  }
}

} // namespace tool
} // namespace amrsp
