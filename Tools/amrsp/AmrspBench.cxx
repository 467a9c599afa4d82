// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspBench.h"

#include "AmrspAmrResample.h"
#include "AmrspBenchWork.h"
#include "AmrspMethods.h"
#include "AmrspMultipass.h"
#include "AmrspProcessResources.h"
#include "AmrspSinglePass.h"
#include "AmrspProgress.h"
#include "AmrspUniform.h"

#include "amrsp/BrickPacking.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkImageData.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

using Json = BenchJson;
using Clock = std::chrono::steady_clock;

std::string Fixed(double v, int digits)
{
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

namespace
{
/// Starts a new peak of this process's resident memory (Linux: "5" to /proc/self/clear_refs
/// resets VmHWM to the current resident size), after handing the heap that earlier rows and
/// methods freed back to the system (glibc keeps it resident otherwise, and it would count in
/// the next method's peak). False where that cannot be done.
bool ResetPeakResidentMemory()
{
#ifdef __GLIBC__
  malloc_trim(0);
#endif
  std::ofstream clear("/proc/self/clear_refs");
  return static_cast<bool>(clear << "5" << std::flush);
}

double Seconds(Clock::time_point since)
{
  return std::chrono::duration<double>(Clock::now() - since).count();
}

double Psnr(double rmse)
{
  return rmse > 0.0 ? 20.0 * std::log10(255.0 / rmse) : 99.0;
}

/// fps, ms_mean, ms_median of the frame times (milliseconds).
void Summarize(const std::vector<double>& ms, Json& out)
{
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  double mean = 0.0;
  for (double v : ms)
  {
    mean += v / static_cast<double>(ms.size());
  }
  const std::size_t n = sorted.size();
  out["fps"] = 1000.0 / mean;
  out["ms_mean"] = mean;
  out["ms_median"] = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Mean of `v`, or -1 when it is empty or holds a negative value (a frame without GPU time).
double MeanOrUnknown(const std::vector<double>& v)
{
  double sum = 0.0;
  for (double x : v)
  {
    if (x < 0.0)
    {
      return -1.0;
    }
    sum += x;
  }
  return v.empty() ? -1.0 : sum / static_cast<double>(v.size());
}

/// One warm-up frame (builds, uploads, compiles; reported as first_frame_ms, not timed with the
/// orbit), then `frames` frames of the orbit, with the GPU's own time of each frame where timer
/// queries work (gpu_ms_mean, gpu_ms_median). Returns frame 0 of the orbit.
Image Orbit(GpuRenderer& r, int frames, Json& out)
{
  double firstMs = 0.0;
  r.Render(0.0, firstMs);
  std::vector<double> ms, gpuMs;
  Image first;
  for (int f = 0; f < frames; ++f)
  {
    double frameMs = 0.0;
    Image img = r.Render(360.0 * f / frames, frameMs);
    ms.push_back(frameMs);
    gpuMs.push_back(r.LastGpuMilliseconds());
    if (f == 0)
    {
      first = std::move(img);
    }
  }
  Summarize(ms, out);
  out["first_frame_ms"] = firstMs;
  if (MeanOrUnknown(gpuMs) >= 0.0)
  {
    out["gpu_ms_mean"] = MeanOrUnknown(gpuMs);
    out["gpu_ms_median"] = Median(gpuMs);
  }
  return first;
}

/// Mean ms/frame of one more orbit of an already warm renderer, and its mean GPU time (-1
/// where it has none).
std::pair<double, double> OrbitMeanMs(GpuRenderer& r, int frames)
{
  double sum = 0.0;
  std::vector<double> gpuMs;
  for (int f = 0; f < frames; ++f)
  {
    double frameMs = 0.0;
    r.Render(360.0 * f / frames, frameMs);
    sum += frameMs;
    gpuMs.push_back(r.LastGpuMilliseconds());
  }
  return { sum / frames, MeanOrUnknown(gpuMs) };
}

/// A GPU method kept alive for the interleaved rounds: its name and one more orbit (ms/frame
/// and GPU ms/frame, -1 without timer queries).
struct KeptRenderer
{
  std::string Method;
  std::function<std::pair<double, double>()> OrbitMs;
};

/// fps_vs_NAME and fps_vs_NAME_range of every kept method against `base` (the median and
/// range over rounds of base's ms / the method's ms).
void RatiosAgainst(const std::string& base, const std::map<std::string, std::vector<double>>& ms,
  const std::vector<KeptRenderer>& kept, Json& methods)
{
  const auto against = ms.find(base);
  if (against == ms.end())
  {
    return;
  }
  for (const KeptRenderer& k : kept)
  {
    const std::vector<double>& mine = ms.at(k.Method);
    if (against->second.size() != mine.size())
    {
      continue;
    }
    std::vector<double> ratios;
    for (std::size_t i = 0; i < mine.size(); ++i)
    {
      ratios.push_back(against->second[i] / mine[i]);
    }
    Json& r = methods[k.Method];
    r["fps_vs_" + base] = Median(ratios);
    r["fps_vs_" + base + "_range"] = { *std::min_element(ratios.begin(), ratios.end()),
      *std::max_element(ratios.begin(), ratios.end()) };
  }
}

/// Rounds 2..o.Rounds of the methods in `kept` (BenchOptions::Rounds), into `methods`.
void RunRounds(const std::vector<KeptRenderer>& kept, const BenchOptions& o, Json& methods)
{
  std::map<std::string, std::vector<double>> ms, gpuMs;
  for (const KeptRenderer& k : kept)
  {
    ms[k.Method].push_back(methods[k.Method]["ms_mean"].get<double>());
    gpuMs[k.Method].push_back(methods[k.Method].value("gpu_ms_mean", -1.0));
  }
  const double orbits = static_cast<double>((o.Rounds - 1) * kept.size());
  for (int round = 1; round < o.Rounds; ++round)
  {
    for (std::size_t i = 0; i < kept.size(); ++i)
    {
      const KeptRenderer& k = kept[round % 2 ? kept.size() - 1 - i : i];
      ReportProgress("bench rounds", "round " + std::to_string(round + 1) + ", " + k.Method,
        static_cast<double>((round - 1) * kept.size() + i) / orbits);
      if (methods[k.Method].contains("rounds_error"))
      {
        continue;
      }
      try
      {
        const std::pair<double, double> orbit = k.OrbitMs();
        ms[k.Method].push_back(orbit.first);
        gpuMs[k.Method].push_back(orbit.second);
      }
      catch (const std::exception& e)
      {
        methods[k.Method]["rounds_error"] = e.what();
      }
    }
  }
  ReportProgress("bench rounds", "done", 1.0);
  for (const KeptRenderer& k : kept)
  {
    Json& r = methods[k.Method];
    const std::vector<double>& mine = ms[k.Method];
    r["rounds_ms_mean"] = mine;
    r["ms_rounds_median"] = Median(mine);
    const std::vector<double>& gpu = gpuMs[k.Method];
    if (std::none_of(gpu.begin(), gpu.end(), [](double v) { return v < 0.0; }))
    {
      r["rounds_gpu_ms_mean"] = gpu;
      r["gpu_ms_rounds_median"] = Median(gpu);
    }
  }
  RatiosAgainst("packing", ms, kept, methods);
  RatiosAgainst("multipass", ms, kept, methods);
}

/// The frames methods are compared against: the CPU reference, and frame 0 of the CPU kD-tree
/// integrator (rendered when first asked for) and of packing (when it ran).
struct Comparisons
{
  const Hierarchy& H;
  const RenderSettings& S;
  const Image& Reference;
  Image KdTree;
  Image Packing;

  const Image& KdTreeFrame()
  {
    if (KdTree.Pixels.empty())
    {
      KdTree = RenderKdTree(H, EncodeKdTree(H, BuildKdTree(H)), S);
    }
    return KdTree;
  }
};

/// cpu-kdtree: the tree and its encoding timed, then the orbit (no warm-up frame).
Image BenchKdTree(
  const Hierarchy& h, const RenderSettings& s, const BenchOptions& o, Comparisons& c, Json& r)
{
  auto t0 = Clock::now();
  const KdTree tree = BuildKdTree(h);
  const double tree_s = Seconds(t0);
  t0 = Clock::now();
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  const double encode_s = Seconds(t0);
  std::vector<double> ms;
  const Camera start = s.View;
  Image first;
  for (int f = 0; f < o.Frames; ++f)
  {
    RenderSettings fs = s;
    fs.View = start;
    fs.View.Azimuth(360.0 * f / o.Frames);
    t0 = Clock::now();
    Image img = RenderKdTree(h, enc, fs);
    ms.push_back(1000.0 * Seconds(t0));
    if (f == 0)
    {
      first = std::move(img);
    }
  }
  Summarize(ms, r);
  if (o.CompareImages)
  {
    r["rmse"] = Rmse(first, c.Reference);
    r["psnr"] = Psnr(r["rmse"].get<double>());
  }
  r["gpu_bytes"] = enc.Tree.Bytes() + enc.DataNodes.Bytes();
  r["preprocess_s"] = { { "tree", tree_s }, { "encode", encode_s } };
  c.KdTree = first;
  return first;
}

/// uniform-gpu's figures after its orbit.
void UniformFields(const UniformGpuRenderer& gpu, const Image& first, const BenchOptions& o,
  const Comparisons& c, Json& r)
{
  if (o.CompareImages)
  {
    r["rmse"] = Rmse(first, c.Reference);
    r["psnr"] = Psnr(r["rmse"].get<double>());
    if (!c.Packing.Pixels.empty())
    {
      r["rmse_vs_packing"] = Rmse(first, c.Packing);
    }
  }
  r["level"] = gpu.Level();
  r["grid"] = gpu.Dimensions();
  r["gpu_bytes"] = gpu.TextureBytes();
  r["preprocess_s"] = { { "resample", gpu.ResampleSeconds() } };
}

/// The figures of the other GPU methods after their orbit. Throws GpuError when bindless fell
/// back to the atlas (its figures would be packing's under bindless's name).
void MapperFields(const Method& m, GpuRenderer& gpu, const Image& first, const BenchOptions& o,
  const Json& stats, Comparisons& c, BenchWork& work, Json& r)
{
  if (SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(&gpu))
  {
    r["storage"] = singlePass->StorageUsedInWords();
    r["ropes"] = singlePass->GetMapper()->GetLastRopes();
    r["loop"] = RayLoopName(singlePass->LoopUsed());
    r["caster"] = RayCasterName(singlePass->CasterUsed());
    const std::string casterFallback = singlePass->GetMapper()->GetRayCasterFallbackReason();
    if (!casterFallback.empty())
    {
      r["caster_fallback"] = casterFallback; // why the compute caster asked for did not run
    }
    if (c.S.GpuAblation != 0)
    {
      r["ablation"] = c.S.GpuAblation == 1
        ? std::string("traversal-only")
        : "sampling-only:" + std::to_string(c.S.GpuAblationSamples);
    }
    r["gpu_bytes_packing"] = singlePass->PackedBytes();
    r["gpu_bytes_bindless"] = singlePass->BindlessBytes();
    if (m.Kind == MethodKind::Bindless &&
      singlePass->StorageUsed() != DataStorage::BindlessTextures)
    {
      throw GpuError("bindless textures are not available: " +
        singlePass->BindlessFallbackReason() + " (on a CPU run with --driver zink)");
    }
  }
  if (o.CompareImages)
  {
    r["rmse"] = Rmse(first, c.Reference);
    r["psnr"] = Psnr(r["rmse"].get<double>());
    if (m.IsKdTreeMapper())
    {
      r["rmse_vs_cpu_kdtree"] = Rmse(first, c.KdTreeFrame());
    }
    if (m.Kind != MethodKind::Packing && !c.Packing.Pixels.empty())
    {
      r["rmse_vs_packing"] = Rmse(first, c.Packing);
    }
  }
  r["gpu_bytes"] = gpu.TextureBytes();
  r["device"] = gpu.Device();
  r["backend"] = gpu.Backend();
  r["opengl_version"] = gpu.OpenGLVersion();
  if (m.IsKdTreeMapper())
  {
    const SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(&gpu);
    const DataStorage storage = singlePass ? singlePass->StorageUsed() : DataStorage::PackedAtlas;
    const bool bindless = storage == DataStorage::BindlessTextures;
    const bool linear = storage == DataStorage::LinearBricks;
    r["atlas"] = bindless ? std::string("none (one texture per grid)")
      : linear            ? std::string("none (bricks back to back)")
                          : gpu.AtlasDimensions();
    r["builds"] = gpu.NumberOfBuilds();
    // tree, encode, pack: the core steps timed by the tool on the CPU; build: the mapper's own
    // total (conversion from vtkOverlappingAMR, tree, packing, encoding)
    const Json& cpu = stats["times_s"];
    Json pre = { { "tree", cpu["tree"] } };
    if (m.Kind != MethodKind::Multipass)
    {
      pre["encode"] = cpu["encode"];
      r["gpu_bytes_tree"] = stats["tree_texture_bytes"];
    }
    if (m.Kind != MethodKind::Bindless && m.Kind != MethodKind::Linear && !bindless && !linear)
    {
      pre["pack"] = cpu["pack"];
    }
    pre["build"] = gpu.BuildSeconds();
    pre["upload"] = gpu.UploadSeconds();
    r["preprocess_s"] = pre;
  }
  if (MultipassRenderer* mp = dynamic_cast<MultipassRenderer*>(&gpu))
  {
    r["passes"] = mp->Passes();
    r["order_ms"] = 1000.0 * mp->OrderSeconds();
    r["accumulation_bytes"] = mp->AccumulationBytes();
  }
  if (o.Counters && m.IsKdTreeMapper())
  {
    r["work"] = m.Kind == MethodKind::Multipass ? work.Multipass() : work.SinglePass(gpu);
  }
  SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(&gpu);
  if (o.Occupancy && singlePass)
  {
    const SinglePassRenderer::Occupancy occupancy = singlePass->RenderOccupancy();
    Json& j = r["occupancy"];
    j["available"] = occupancy.Available;
    if (!occupancy.Available)
    {
      j["why"] = occupancy.Why;
    }
    else
    {
      j["caster"] = RayCasterName(occupancy.Caster);
      j["rays"] = occupancy.Rays;
      j["sms"] = occupancy.Multiprocessors;
      j["sm_count"] = occupancy.ChipMultiprocessors;
      j["warps"] = occupancy.Warps;
      j["most_warps_on_one_sm"] = occupancy.MostWarpsOnOne;
    }
  }
  if (m.Kind == MethodKind::Packing && o.CompareImages)
  {
    c.Packing = first;
  }
#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
  if (AmrResampleRenderer* ar = dynamic_cast<AmrResampleRenderer*>(&gpu))
  {
    const glm::ivec3 n = ar->Samples();
    const glm::dvec3 cells = ar->FinestCellsPerSample();
    r["samples"] = { n.x, n.y, n.z };
    r["grid"] = gpu.AtlasDimensions();
    r["finest_cells_per_sample"] = std::max(cells.x, std::max(cells.y, cells.z));
    r["resamplings"] = ar->NumberOfBuilds();
    r["render_mode"] = ar->RenderMode();
    // the internal mapper's upload is part of first_frame_ms
    r["preprocess_s"] = { { "resample", ar->BuildSeconds() } };
  }
#endif
}

} // namespace

void WriteImagePng(const Image& img, const std::string& path)
{
  const std::vector<std::uint8_t> rgb = img.Rgb8();
  vtkNew<vtkImageData> data;
  data->SetDimensions(img.Width, img.Height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  std::copy(rgb.begin(), rgb.end(), static_cast<std::uint8_t*>(data->GetScalarPointer()));
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    throw std::runtime_error("cannot write the image '" + path + "'");
  }
}

Json DatasetStatistics(const Hierarchy& h)
{
  Json j;
  j["grids"] = h.Grids.size();
  j["levels"] = h.NumberOfLevels();
  j["cells"] = h.TotalCells();
  auto t0 = Clock::now();
  const KdTree tree = BuildKdTree(h);
  const double tree_s = Seconds(t0);
  t0 = Clock::now();
  const EncodedKdTree enc = EncodeKdTree(h, tree);
  const double encode_s = Seconds(t0);
  const KdTreeStatistics st = tree.Statistics();
  j["kd_nodes"] = st.Nodes;
  j["kd_data_nodes"] = st.DataNodes;
  j["tree_texture_bytes"] = KdTreeTextureBytes(enc.Tree, enc.DataNodes);
  double pack_s = 0.0;
  try
  {
    const AtlasLayout layout =
      PackBricks(BrickExtents(h, h.VertexCentred), Packer::Best, AtlasLimits(2048));
    pack_s = layout.Seconds;
    j["atlas"] = { { "dims", { layout.Dims.x, layout.Dims.y, layout.Dims.z } },
      { "efficiency", layout.Efficiency } };
  }
  catch (const std::exception& e)
  {
    j["atlas"] = { { "error", e.what() } };
  }
  j["times_s"] = { { "tree", tree_s }, { "encode", encode_s }, { "pack", pack_s } };
  return j;
}

Json RunBenchMethods(const Hierarchy& h, const RenderSettings& s, const Image& reference,
  const BenchOptions& o, const Json& stats)
{
  Json methods = Json::object();
  Comparisons c{ h, s, reference, Image(), Image() };
  BenchWork work(h, s);
  if (!o.ImageFolder.empty() && o.CompareImages)
  {
    WriteImagePng(reference, o.ImageFolder + "/reference.png");
  }
  std::vector<KeptRenderer> kept; // for the interleaved rounds (o.Rounds > 1)
  for (const std::string& m : o.Methods)
  {
    Json r;
    Image frame0;
    try
    {
      const Method* method = FindMethod(m, BenchCommand);
      if (!method)
      {
        throw std::invalid_argument("unknown method '" + m + "'");
      }
      if (method->Kind == MethodKind::CpuKdTree)
      {
        frame0 = BenchKdTree(h, s, o, c, r);
      }
      else
      {
        // from the hierarchy in memory to the first image: the renderer's set-up (conversion,
        // build), then the warm-up frame (upload, shader compile, render); the peak resident
        // memory of the process from here to the end of the first orbit
        const bool peakReset = ResetPeakResidentMemory();
        const auto t0 = std::chrono::steady_clock::now();
        std::shared_ptr<GpuRenderer> gpu = method->Make(m, MethodRequest{ h, s, o.View });
        const double setupS =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const Image first = Orbit(*gpu, o.Frames, r);
        r["time_to_first_image_s"] = setupS + r["first_frame_ms"].get<double>() / 1000.0;
        const long long peak = PeakResidentBytes();
        if (peakReset && peak > 0)
        {
          r["peak_rss_bytes"] = peak;
        }
        if (o.Rounds > 1)
        {
          const int frames = o.Frames;
          kept.push_back({ m, [gpu, frames]() { return OrbitMeanMs(*gpu, frames); } });
        }
        if (const UniformGpuRenderer* uniform = dynamic_cast<UniformGpuRenderer*>(gpu.get()))
        {
          UniformFields(*uniform, first, o, c, r);
        }
        else
        {
          MapperFields(*method, *gpu, first, o, stats, c, work, r);
          if (o.InteractiveRate > 0.0)
          {
            InteractiveFields(*gpu, first, o, r);
          }
        }
        frame0 = first; // not where MapperFields threw
      }
    }
    catch (const std::exception& e)
    {
      r = { { "error", e.what() } };
    }
    if (!o.ImageFolder.empty() && !frame0.Pixels.empty())
    {
      std::string file = m;
      std::replace(file.begin(), file.end(), ':', '-');
      WriteImagePng(frame0, o.ImageFolder + "/" + file + ".png");
    }
    if (r.contains("error") && !kept.empty() && kept.back().Method == m)
    {
      kept.pop_back(); // a method that failed after its orbit (bindless fell back) has no rounds
    }
    methods[m] = r;
  }
  if (o.Rounds > 1 && !kept.empty())
  {
    RunRounds(kept, o, methods);
  }
  return methods;
}

} // namespace tool
} // namespace amrsp
