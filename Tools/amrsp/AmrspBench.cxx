// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspBench.h"

#include "AmrspAmrResample.h"
#include "AmrspDriver.h"
#include "AmrspMultipass.h"
#include "AmrspPacking.h"
#include "AmrspUniform.h"

#include "amrsp/BrickPacking.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace amrsp
{
namespace tool
{

using Json = BenchJson;
using Clock = std::chrono::steady_clock;

const char* const DefaultBenchMethods =
  "cpu-kdtree,packing,bindless,multipass,uniform-gpu,vtk-amr-resample,vtk-amr-resample:finest";

const std::vector<std::pair<std::string, std::string>>& BenchMethodHelp()
{
  static const std::vector<std::pair<std::string, std::string>> help = {
    { "cpu-kdtree", "the CPU kD-tree integrator (amrsp::RenderKdTree)" },
    { "packing", "vtkSinglePassAMRVolumeMapper, packed atlas (the paper's single pass)" },
    { "bindless",
      "vtkSinglePassAMRVolumeMapper, one texture per grid through bindless handles (needs "
      "GL_ARB_bindless_texture: --driver zink on a CPU)" },
    { "multipass", "vtkMultiPassAMRVolumeMapper: one draw per kD-tree data node (paper §6)" },
    { "uniform-gpu[:LEVEL]",
      "vtkGPUVolumeRayCastMapper on one uniform resampling at the finest level (or LEVEL)" },
    { "vtk-amr-resample[:N]",
      "VTK's vtkAMRVolumeMapper (ParaView's VTK only) at its default 128^3 samples (or N^3)" },
    { "vtk-amr-resample:finest",
      "vtkAMRVolumeMapper at two samples per finest cell edge (where that fits)" },
  };
  return help;
}

namespace
{

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

/// One warm-up frame (builds, uploads, compiles; reported as first_frame_ms, not timed with the
/// orbit), then `frames` frames of the orbit. Returns frame 0 of the orbit.
template <class Renderer>
Image Orbit(Renderer& r, int frames, Json& out)
{
  double firstMs = 0.0;
  r.Render(0.0, firstMs);
  std::vector<double> ms;
  Image first;
  for (int f = 0; f < frames; ++f)
  {
    double frameMs = 0.0;
    Image img = r.Render(360.0 * f / frames, frameMs);
    ms.push_back(frameMs);
    if (f == 0)
    {
      first = std::move(img);
    }
  }
  Summarize(ms, out);
  out["first_frame_ms"] = firstMs;
  return first;
}

/// Mean ms/frame of one more orbit of an already warm renderer.
template <class Renderer>
double OrbitMeanMs(Renderer& r, int frames)
{
  double sum = 0.0;
  for (int f = 0; f < frames; ++f)
  {
    double frameMs = 0.0;
    r.Render(360.0 * f / frames, frameMs);
    sum += frameMs;
  }
  return sum / frames;
}

double Median(std::vector<double> v)
{
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// A GPU method kept alive for the interleaved rounds: its name and one more orbit.
struct KeptRenderer
{
  std::string Method;
  std::function<double()> OrbitMs;
};

/// Rounds 2..o.Rounds of the methods in `kept` (BenchOptions::Rounds), into `methods`.
void RunRounds(const std::vector<KeptRenderer>& kept, const BenchOptions& o, Json& methods)
{
  std::map<std::string, std::vector<double>> ms;
  for (const KeptRenderer& k : kept)
  {
    ms[k.Method].push_back(methods[k.Method]["ms_mean"].get<double>());
  }
  for (int round = 1; round < o.Rounds; ++round)
  {
    for (std::size_t i = 0; i < kept.size(); ++i)
    {
      const KeptRenderer& k = kept[round % 2 ? kept.size() - 1 - i : i];
      if (methods[k.Method].contains("rounds_error"))
      {
        continue;
      }
      try
      {
        ms[k.Method].push_back(k.OrbitMs());
      }
      catch (const std::exception& e)
      {
        methods[k.Method]["rounds_error"] = e.what();
      }
    }
  }
  const auto packing = ms.find("packing");
  for (const KeptRenderer& k : kept)
  {
    Json& r = methods[k.Method];
    const std::vector<double>& mine = ms[k.Method];
    r["rounds_ms_mean"] = mine;
    r["ms_rounds_median"] = Median(mine);
    if (packing != ms.end() && packing->second.size() == mine.size())
    {
      std::vector<double> ratios;
      for (std::size_t i = 0; i < mine.size(); ++i)
      {
        ratios.push_back(packing->second[i] / mine[i]);
      }
      r["fps_vs_packing"] = Median(ratios);
      r["fps_vs_packing_range"] = { *std::min_element(ratios.begin(), ratios.end()),
        *std::max_element(ratios.begin(), ratios.end()) };
    }
  }
}

/// The renderer of a method that goes through GpuRenderer, or a GpuError saying why it cannot.
std::unique_ptr<GpuRenderer> MakeGpuRenderer(
  const std::string& m, const Hierarchy& h, const RenderSettings& s, const ViewAngles& view)
{
  if (m == "packing")
  {
    return std::unique_ptr<GpuRenderer>(new PackingRenderer(h, s, view));
  }
  if (m == "multipass")
  {
    return std::unique_ptr<GpuRenderer>(new MultipassRenderer(h, s, view));
  }
  if (m == "bindless")
  {
    // the mapper falls back to the atlas where bindless cannot run; the bench then reports an
    // error instead of packing's figures under bindless's name (checked after the warm-up frame)
    return std::unique_ptr<GpuRenderer>(new PackingRenderer(h, s, view, "bindless"));
  }
  std::string why;
  if (!AmrResampleAvailable(why))
  {
    throw GpuError(why);
  }
#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
  glm::ivec3 samples(0);
  if (m == "vtk-amr-resample:finest")
  {
    samples = glm::ivec3(-1);
  }
  else if (m != "vtk-amr-resample")
  {
    const std::string n = m.substr(std::string("vtk-amr-resample:").size());
    if (n.empty() || n.find_first_not_of("0123456789") != std::string::npos || n.size() > 4 ||
      std::stoi(n) < 2 || std::stoi(n) > 2048)
    {
      throw GpuError("vtk-amr-resample:N needs N in 2..2048 or 'finest', got '" + n + "'");
    }
    samples = glm::ivec3(std::stoi(n));
  }
  return std::unique_ptr<GpuRenderer>(new AmrResampleRenderer(h, s, view, samples));
#else
  return nullptr;
#endif
}

} // namespace

bool IsBenchMethod(const std::string& m)
{
  return m == "cpu-kdtree" || m == "packing" || m == "bindless" || m == "multipass" ||
    m == "uniform-gpu" || m.rfind("uniform-gpu:", 0) == 0 || m == "vtk-amr-resample" ||
    m.rfind("vtk-amr-resample:", 0) == 0;
}

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
  const Json& cpu = stats["times_s"];
  Image kdFrame0;      // the CPU kD-tree image of frame 0
  Image packingFrame0; // the packing image of frame 0
  auto kdImage = [&]() -> const Image& {
    if (kdFrame0.Pixels.empty())
    {
      kdFrame0 = RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), s);
    }
    return kdFrame0;
  };
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
      if (m == "cpu-kdtree")
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
          r["rmse"] = Rmse(first, reference);
          r["psnr"] = Psnr(r["rmse"].get<double>());
        }
        r["gpu_bytes"] = enc.Tree.Bytes() + enc.DataNodes.Bytes();
        r["preprocess_s"] = { { "tree", tree_s }, { "encode", encode_s } };
        frame0 = first;
        kdFrame0 = std::move(first);
      }
      else if (m == "uniform-gpu" || m.rfind("uniform-gpu:", 0) == 0)
      {
        int level = h.NumberOfLevels() - 1;
        if (m != "uniform-gpu")
        {
          const std::string l = m.substr(12);
          if (l.empty() || l.size() > 3 || l.find_first_not_of("0123456789") != std::string::npos ||
            std::stoi(l) >= h.NumberOfLevels())
          {
            throw GpuError("uniform-gpu level '" + l + "' does not exist (levels 0.." +
              std::to_string(h.NumberOfLevels() - 1) + ")");
          }
          level = std::stoi(l);
        }
        auto gpuShared = std::make_shared<UniformGpuRenderer>(h, s, o.View, level);
        UniformGpuRenderer& gpu = *gpuShared;
        const Image first = Orbit(gpu, o.Frames, r);
        if (o.Rounds > 1)
        {
          const int frames = o.Frames;
          kept.push_back({ m, [gpuShared, frames]() { return OrbitMeanMs(*gpuShared, frames); } });
        }
        frame0 = first;
        if (o.CompareImages)
        {
          r["rmse"] = Rmse(first, reference);
          r["psnr"] = Psnr(r["rmse"].get<double>());
          if (!packingFrame0.Pixels.empty())
          {
            r["rmse_vs_packing"] = Rmse(first, packingFrame0);
          }
        }
        r["level"] = level;
        r["grid"] = gpu.Dimensions();
        r["gpu_bytes"] = gpu.TextureBytes();
        r["preprocess_s"] = { { "resample", gpu.ResampleSeconds() } };
      }
      else
      {
        std::shared_ptr<GpuRenderer> gpu = MakeGpuRenderer(m, h, s, o.View);
        const Image first = Orbit(*gpu, o.Frames, r);
        if (o.Rounds > 1)
        {
          const int frames = o.Frames;
          kept.push_back({ m, [gpu, frames]() { return OrbitMeanMs(*gpu, frames); } });
        }
        PackingRenderer* singlePass = dynamic_cast<PackingRenderer*>(gpu.get());
        if (singlePass)
        {
          r["storage"] = singlePass->StorageUsed();
          r["gpu_bytes_packing"] = singlePass->PackedBytes();
          r["gpu_bytes_bindless"] = singlePass->BindlessBytes();
          if (m == "bindless" && singlePass->StorageUsed().rfind("bindless", 0) != 0)
          {
            throw GpuError("bindless textures are not available: " +
              singlePass->BindlessFallbackReason() + " (on a CPU run with --driver zink)");
          }
        }
        frame0 = first;
        if (o.CompareImages)
        {
          r["rmse"] = Rmse(first, reference);
          r["psnr"] = Psnr(r["rmse"].get<double>());
          if (m == "packing" || m == "bindless" || m == "multipass")
          {
            r["rmse_vs_cpu_kdtree"] = Rmse(first, kdImage());
          }
          if (m != "packing" && !packingFrame0.Pixels.empty())
          {
            r["rmse_vs_packing"] = Rmse(first, packingFrame0);
          }
        }
        r["gpu_bytes"] = gpu->TextureBytes();
        r["device"] = gpu->Device();
        r["backend"] = gpu->Backend();
        if (m == "packing" || m == "bindless" || m == "multipass")
        {
          r["atlas"] = m == "bindless" ? std::string("none (one texture per grid)")
                                       : gpu->AtlasDimensions();
          r["builds"] = gpu->NumberOfBuilds();
          // tree, encode, pack: the core steps timed by the tool on the CPU; build: the mapper's
          // own total (conversion from vtkOverlappingAMR, tree, packing, encoding)
          Json pre = { { "tree", cpu["tree"] } };
          if (m != "multipass")
          {
            pre["encode"] = cpu["encode"];
            r["gpu_bytes_tree"] = stats["tree_texture_bytes"];
          }
          if (m != "bindless")
          {
            pre["pack"] = cpu["pack"];
          }
          pre["build"] = gpu->BuildSeconds();
          pre["upload"] = gpu->UploadSeconds();
          r["preprocess_s"] = pre;
        }
        if (MultipassRenderer* mp = dynamic_cast<MultipassRenderer*>(gpu.get()))
        {
          r["passes"] = mp->Passes();
          r["order_ms"] = 1000.0 * mp->OrderSeconds();
          r["accumulation_bytes"] = mp->AccumulationBytes();
        }
        if (m == "packing" && o.CompareImages)
        {
          packingFrame0 = first;
        }
#ifdef AMRSP_HAVE_VTK_AMR_VOLUME_MAPPER
        if (AmrResampleRenderer* ar = dynamic_cast<AmrResampleRenderer*>(gpu.get()))
        {
          const glm::ivec3 n = ar->Samples();
          const glm::dvec3 c = ar->FinestCellsPerSample();
          r["samples"] = { n.x, n.y, n.z };
          r["grid"] = gpu->AtlasDimensions();
          r["finest_cells_per_sample"] = std::max(c.x, std::max(c.y, c.z));
          r["resamplings"] = ar->NumberOfBuilds();
          r["render_mode"] = ar->RenderMode();
          // the internal mapper's upload is part of first_frame_ms
          r["preprocess_s"] = { { "resample", ar->BuildSeconds() } };
        }
#endif
      }
    }
    catch (const GpuError& e)
    {
      r = { { "error", e.what() } };
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

int PaperDataset(const Json& stats)
{
  const int64_t grids = stats.value("grids", int64_t(0));
  const int levels = stats.value("levels", 0);
  if (grids == 2666 && levels == 4)
  {
    return 1;
  }
  if (grids == 18528 && levels == 4)
  {
    return 2;
  }
  if (grids == 39061 && levels == 13)
  {
    return 3;
  }
  return 0;
}

namespace
{
// The paper's Table 1 (grids, levels, cells, kD nodes, kD data nodes) and Table 2 (GPU memory
// MB as tree + data, preprocessing s, fps on its GTX 680) for datasets 1-3.
struct PaperRow
{
  const char* Cells;
  long long KdNodes, KdDataNodes;
};
const PaperRow PaperTable1[3] = { { "19 × 10^6", 30096, 27249 }, { "33 × 10^6", 178114, 162095 },
  { "140 × 10^6", 368225, 343389 } };
struct PaperTiming
{
  const char* Method;
  const char* Memory[3];
  double Preprocess[3];
  double Fps[3];
};
const PaperTiming PaperTable2[3] = {
  { "multipass", { "71.4", "124.2", "530.3" }, { 1.1, 2.6, 6.8 }, { 4.2, 2.1, 0.8 } },
  { "packing", { "0.5 + 239.3", "2.7 + 310.3", "4.3 + 1000.2" }, { 3.4, 7.5, 8.1 },
    { 3.2, 1.6, 1.2 } },
  { "bindless", { "0.5 + 71.4", "2.8 + 124.2", "6.1 + 530.3" }, { 1.7, 3.2, 7.4 },
    { 2.1, 0.9, 0.4 } },
};

std::string Fixed(double v, int digits)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

std::string Thousands(long long v)
{
  std::string d = std::to_string(v < 0 ? -v : v), out;
  for (std::size_t i = 0; i < d.size(); ++i)
  {
    if (i > 0 && (d.size() - i) % 3 == 0)
    {
      out += ',';
    }
    out += d[i];
  }
  return (v < 0 ? "-" : "") + out;
}

std::string Mb(double bytes)
{
  return Fixed(bytes / 1.0e6, bytes < 1.0e5 ? 3 : 1);
}

/// Total preprocessing seconds of a method: the sum of its preprocess_s entries that are
/// separate steps (the mapper's build already contains tree, encode and pack).
double PreprocessTotal(const Json& r)
{
  const Json& p = r["preprocess_s"];
  if (p.contains("build"))
  {
    return p["build"].get<double>() + p.value("upload", 0.0);
  }
  double sum = 0.0;
  for (const auto& item : p.items())
  {
    sum += item.value().get<double>();
  }
  return sum;
}

std::string PreprocessDetail(const Json& r)
{
  std::string out;
  for (const auto& item : r["preprocess_s"].items())
  {
    out += (out.empty() ? "" : ", ") + item.key() + " " + Fixed(item.value().get<double>(), 3);
  }
  return out;
}
} // namespace

std::string RoundsMarkdown(const Json& methods)
{
  std::ostringstream md;
  std::size_t rounds = 0;
  for (const auto& item : methods.items())
  {
    if (item.value().contains("rounds_ms_mean"))
    {
      rounds = std::max(rounds, item.value()["rounds_ms_mean"].size());
    }
  }
  if (rounds < 2)
  {
    return "";
  }
  md << "\nInterleaved rounds (" << rounds
     << " orbits per method, the methods' order reversed every round; fps relative to packing = "
        "median over rounds of packing's ms/frame over the method's)\n\n"
     << "| method | ms/frame per round | median | fps relative to packing (min–max) |\n"
     << "|---|---|---|---|\n";
  for (const auto& item : methods.items())
  {
    const Json& r = item.value();
    if (!r.contains("rounds_ms_mean"))
    {
      continue;
    }
    md << "| " << item.key() << " | ";
    bool first = true;
    for (const Json& v : r["rounds_ms_mean"])
    {
      md << (first ? "" : ", ") << Fixed(v.get<double>(), 1);
      first = false;
    }
    md << " | " << Fixed(r["ms_rounds_median"].get<double>(), 1) << " | ";
    if (r.contains("fps_vs_packing"))
    {
      md << Fixed(r["fps_vs_packing"].get<double>(), 2) << " ("
         << Fixed(r["fps_vs_packing_range"][0].get<double>(), 2) << "–"
         << Fixed(r["fps_vs_packing_range"][1].get<double>(), 2) << ")";
    }
    else
    {
      md << "—";
    }
    md << (r.contains("rounds_error") ? " (stopped: " + r["rounds_error"].get<std::string>() + ")"
                                      : "")
       << " |\n";
  }
  return md.str();
}

std::string BenchMarkdown(const Json& bench)
{
  std::ostringstream md;
  const Json& st = bench["statistics"];
  const int paper = PaperDataset(st);
  md << "Dataset `" << bench["dataset"].get<std::string>() << "`, " << bench["image"][0] << "×"
     << bench["image"][1] << ", " << bench["frames"] << "-frame orbit";
  if (bench.contains("device") && !bench["device"].get<std::string>().empty())
  {
    md << ", " << bench["device"].get<std::string>();
  }
  if (bench.contains("backend"))
  {
    md << " through " << bench["backend"].get<std::string>();
  }
  if (bench.contains("vtk_version"))
  {
    md << " (VTK " << bench["vtk_version"].get<std::string>() << ", ParaView "
       << bench["paraview_version"].get<std::string>() << ")";
  }
  md << (paper ? ", the size of the paper's dataset " + std::to_string(paper) +
             " (the hierarchy is the project's synthetic one, not the paper's data)"
               : "")
     << ".\n\n";
  md << "Table 1 (dataset)\n\n"
     << "| | grids | levels | cells | kD nodes | kD data nodes |\n"
     << "|---|---|---|---|---|---|\n"
     << "| this dataset | " << Thousands(st["grids"].get<long long>()) << " | " << st["levels"]
     << " | " << Thousands(st["cells"].get<long long>()) << " | "
     << Thousands(st["kd_nodes"].get<long long>()) << " | "
     << Thousands(st["kd_data_nodes"].get<long long>()) << " |\n";
  if (paper)
  {
    const PaperRow& p = PaperTable1[paper - 1];
    md << "| paper, dataset " << paper << " | " << Thousands(st["grids"].get<long long>()) << " | "
       << st["levels"] << " | " << p.Cells << " | " << Thousands(p.KdNodes) << " | "
       << Thousands(p.KdDataNodes) << " |\n";
  }
  md << "\nTable 2 (per method; GPU memory in MB = 10^6 bytes, tree textures + data; "
        "preprocessing = the mapper's build + upload, or the resampling; RMSE of frame 0 against "
        "the CPU reference, 0-255)\n\n"
     << "| method | GPU memory [MB] | preprocessing [s] | fps | ms/frame (median) | RMSE | "
        "PSNR [dB] |";
  if (paper)
  {
    md << " paper: memory | paper: preprocessing | paper: fps |";
  }
  md << "\n|---|---|---|---|---|---|---|" << (paper ? "---|---|---|" : "") << "\n";
  for (const auto& item : bench["methods"].items())
  {
    const Json& r = item.value();
    const PaperTiming* pt = nullptr;
    for (const PaperTiming& t : PaperTable2)
    {
      if (item.key() == t.Method)
      {
        pt = &t;
      }
    }
    md << "| " << item.key() << " | ";
    if (r.contains("error"))
    {
      md << "cannot run: " << r["error"].get<std::string>() << " | | | | | |";
    }
    else
    {
      const double data = r["gpu_bytes"].get<double>();
      const double tree = r.value("gpu_bytes_tree", 0.0);
      md << (tree > 0 ? Mb(tree) + " + " + Mb(data - tree) : Mb(data)) << " | "
         << Fixed(PreprocessTotal(r), 3) << " (" << PreprocessDetail(r) << ") | "
         << Fixed(r["fps"].get<double>(), 2) << " | " << Fixed(r["ms_median"].get<double>(), 1)
         << " | " << Fixed(r["rmse"].get<double>(), 3) << " | "
         << Fixed(r["psnr"].get<double>(), 1) << " |";
    }
    if (paper)
    {
      if (pt)
      {
        md << " " << pt->Memory[paper - 1] << " | " << Fixed(pt->Preprocess[paper - 1], 1)
           << " | " << Fixed(pt->Fps[paper - 1], 1) << " |";
      }
      else
      {
        md << " — | — | — |";
      }
    }
    md << "\n";
  }
  if (paper)
  {
    md << "\nThe paper's figures: GTX 680, its own real cosmology data of that size (its image "
          "size is not stated).\n";
  }
  md << RoundsMarkdown(bench["methods"]);
  return md.str();
}

std::string ScalingMarkdownHeader(const std::string& size, int frames)
{
  std::ostringstream md;
  md << "Scaling (`synthetic:cosmo`, " << size << ", " << frames << " frames per method)\n\n"
     << "| grids | levels | cells | kD nodes | paper dataset | tree [s] | encode [s] | pack [s] | "
        "method | build [s] | upload [s] | ms/frame (mean) | GPU memory [MB] |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  return md.str();
}

std::string ScalingMarkdownRow(const Json& row)
{
  std::ostringstream md;
  if (row.contains("error"))
  {
    md << "| " << row["dataset"].get<std::string>() << " | | | | | | | | | cannot run: "
       << row["error"].get<std::string>() << " | | | |\n";
    return md.str();
  }
  const Json& st = row["statistics"];
  const int paper = PaperDataset(st);
  const std::string head = "| " + Thousands(st["grids"].get<long long>()) + " | " +
    st["levels"].dump() + " | " + Thousands(st["cells"].get<long long>()) + " | " +
    Thousands(st["kd_nodes"].get<long long>()) + " | " + (paper ? std::to_string(paper) : "—") +
    " | " + Fixed(st["times_s"]["tree"].get<double>(), 3) + " | " +
    Fixed(st["times_s"]["encode"].get<double>(), 3) + " | " +
    Fixed(st["times_s"]["pack"].get<double>(), 3) + " | ";
  for (const auto& item : row["methods"].items())
  {
    const Json& r = item.value();
    md << head << item.key() << " | ";
    if (r.contains("error"))
    {
      md << "cannot run: " << r["error"].get<std::string>() << " | | | |\n";
      continue;
    }
    const Json& p = r["preprocess_s"];
    md << (p.contains("build") ? Fixed(p["build"].get<double>(), 3) : "—") << " | "
       << (p.contains("upload") ? Fixed(p["upload"].get<double>(), 3) : "—") << " | "
       << Fixed(r["ms_mean"].get<double>(), 1) << " | " << Mb(r["gpu_bytes"].get<double>())
       << " |\n";
  }
  return md.str();
}

std::string ScalingMarkdown(const Json& scaling)
{
  std::string md = ScalingMarkdownHeader(
    scaling["image"][0].dump() + "×" + scaling["image"][1].dump(), scaling["frames"].get<int>());
  for (const Json& row : scaling["rows"])
  {
    md += ScalingMarkdownRow(row);
  }
  return md;
}

} // namespace tool
} // namespace amrsp
