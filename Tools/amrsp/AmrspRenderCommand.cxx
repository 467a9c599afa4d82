// SPDX-License-Identifier: BSD-3-Clause
// `amrsp render`: one image with one of the kD-tree raycasters (AmrspMethods.h).
// first: see AmrspJson.h
#include "AmrspImageCommand.h"

#include "AmrspDriver.h"
#include "AmrspMethods.h"
#include "AmrspMultipass.h"
#include "AmrspSinglePass.h"
#include "AmrspProgress.h"
#include "AmrspSeries.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

namespace
{

const char* const RenderIntro =
  "usage: amrsp render [DATASET] [-o FILE.png] [view options] [dataset options]\n"
  "Renders the dataset with one of the kD-tree raycasters and prints which method\n"
  "rendered. Methods:\n";

/// The GPU methods: a warm-up frame (conversion, build, packing, upload, shader compile), then
/// `repeat` timed frames; `method` becomes "packing" where bindless fell back to the atlas.
ImageRun RenderGpu(const Method& m, std::string& method, const LoadedDataset& d,
  const RenderSettings& s, const Arguments& a, BindlessAccess bindlessAccess, int repeat)
{
  ImageRun run;
  std::unique_ptr<GpuRenderer> gpu =
    m.Make(method, MethodRequest{ d.Data, s, ViewOf(a), bindlessAccess });
  GpuRenderer& r = *gpu;
  auto* singlePass = dynamic_cast<SinglePassRenderer*>(gpu.get());
  auto* multipass = dynamic_cast<MultipassRenderer*>(gpu.get());
  double firstMs = 0.0, ms = 0.0;
  r.Render(0.0, firstMs); // converts, builds, packs, uploads and compiles
  for (int k = 0; k < repeat; ++k)
  {
    run.Img = r.Render(0.0, ms);
    run.FrameMs.push_back(ms);
  }
  run.PreprocessSeconds = r.BuildSeconds() + r.UploadSeconds();
  std::ostringstream stats, report;
  if (singlePass)
  {
    vtkSinglePassAMRVolumeMapper* mapper = singlePass->GetMapper();
    stats << "stats: transparent data nodes " << mapper->GetNumberOfTransparentDataNodes() << " of "
          << mapper->GetNumberOfDataNodes() << " (skipping "
          << (mapper->GetEmptySpaceSkipping() ? "on" : "off") << ", opacity threshold "
          << mapper->GetOpacityThreshold() << ")\n";
  }
  const double cameraDifference = CameraDifference(r.LastCamera(), s.View);
  if (singlePass)
  {
    if (m.Kind == MethodKind::Bindless &&
      singlePass->StorageUsed() != DataStorage::BindlessTextures)
    {
      std::cerr << "amrsp: note: bindless textures cannot be used here ("
                << singlePass->BindlessFallbackReason()
                << "; on a CPU try --driver zink); rendered with the packed atlas\n";
      method = "packing";
    }
    // the linear storage's build does not pack: no atlas figure then
    report << "storage: " << singlePass->StorageUsedInWords() << "; textures for packing "
           << (singlePass->PackedBytes() > 0
                  ? std::to_string(singlePass->PackedBytes() / (1024.0 * 1024.0)) + " MiB"
                  : std::string("not built"))
           << ", for bindless " << singlePass->BindlessBytes() / (1024.0 * 1024.0) << " MiB\n"
           << "ray loop: " << RayLoopName(singlePass->LoopUsed()) << "\n"
           << "caster: " << RayCasterName(singlePass->CasterUsed());
    const std::string casterFallback = singlePass->GetMapper()->GetRayCasterFallbackReason();
    report << (casterFallback.empty() ? "" : " (" + casterFallback + ")") << "\n";
  }
  report << "device: " << r.Device() << "\n"
         << "opengl: " << r.OpenGLVersion() << "\n"
         << "backend: " << r.Backend() << " (VTK " << VtkVersion() << ", ParaView "
         << ParaViewVersion() << ")\n"
         << "atlas: "
         << (singlePass && method == "bindless"    ? "not used (bindless)"
                : singlePass && method == "linear" ? "not used (linear)"
                                                   : r.AtlasDimensions() + " texels")
         << ", textures " << r.TextureBytes() / (1024.0 * 1024.0) << " MiB\n"
         << "mapper (s): build " << r.BuildSeconds() << " (conversion, kD-tree, packing"
         << (multipass ? "" : ", encoding") << "; done in GetBounds), upload " << r.UploadSeconds()
         << "; first frame " << firstMs / 1000.0 << " (upload, shader compile, render)\n";
  if (multipass)
  {
    report << "passes: " << multipass->Passes()
           << " draws (data nodes, front to back), ordering on the CPU "
           << multipass->OrderSeconds() * 1000.0 << " ms\n";
  }
  report << "camera: VTK's camera and the tool's conventions "
         << (cameraDifference < 1e-6 ? "agree" : "DIFFER") << " (relative difference "
         << cameraDifference << ")\n";
  run.DeviceReport = report.str();
  run.StatsReport = stats.str();
  return run;
}

/// The CPU methods: the tree and its encoding (cpu-packing: through the packed atlas, printed)
/// and the data-node ranges, then `repeat` timed frames.
ImageRun RenderCpu(const Method& m, const LoadedDataset& d, RenderSettings s,
  const AtlasRequest& atlasRequest, int repeat)
{
  ImageRun run;
  RenderStats stats;
  s.Stats = &stats;
  auto t0 = Clock::now();
  std::unique_ptr<BrickAtlas> atlas;
  if (m.Kind == MethodKind::CpuPacking)
  {
    atlas.reset(new BrickAtlas(BuildBrickAtlas(
      d.Data, atlasRequest.Algorithm, atlasRequest.MaxDims, atlasRequest.MaxBytes)));
  }
  const EncodedKdTree enc =
    EncodeKdTree(d.Data, BuildKdTree(d.Data), atlas ? &atlas->Layout.Origins : nullptr);
  const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(d.Data, enc);
  s.DataNodeRanges = &ranges;
  run.PreprocessSeconds = Seconds(t0);
  if (atlas)
  {
    std::cout << "atlas: " << AtlasJson(atlas->Layout).dump() << "\n";
  }
  for (int k = 0; k < repeat; ++k)
  {
    t0 = Clock::now();
    RenderSettings frame = s;
    frame.Progress = ProgressOf("cpu-kdtree");
    run.Img = RenderKdTree(d.Data, enc, frame, atlas.get());
    run.FrameMs.push_back(1000.0 * Seconds(t0));
  }
  run.StatsReport = CpuStatsReport(stats);
  return run;
}

/// --compare: the RMSE against the CPU reference, the CPU kD-tree integrator and (multipass)
/// packing.
void Compare(const Method& m, const Image& img, const LoadedDataset& d, const RenderSettings& s,
  const Arguments& a)
{
  RenderSettings referenceSettings = s;
  referenceSettings.Progress = ProgressOf("reference");
  std::cout << "rmse (0-255) vs cpu-reference: "
            << Rmse(img, RenderReference(d.Data, referenceSettings));
  if (m.Kind != MethodKind::CpuKdTree)
  {
    const Image kd = RenderKdTree(d.Data, EncodeKdTree(d.Data, BuildKdTree(d.Data)), s);
    std::cout << ", vs cpu-kdtree: " << Rmse(img, kd);
  }
  if (m.Kind == MethodKind::Multipass)
  {
    // the single-pass mapper samples the same segments: the images should agree closely
    double ms = 0.0;
    const Image packing =
      MakeGpuRenderer("packing", RenderCommand, MethodRequest{ d.Data, s, ViewOf(a) })
        ->Render(0.0, ms);
    std::cout << ", vs packing: " << Rmse(img, packing);
  }
  std::cout << "\n";
}

} // namespace

int RunRender(int argc, char** argv)
{
  const std::string name = "render";
  try
  {
    std::vector<std::string> valueOptions = ImageValueOptions();
    valueOptions.insert(
      valueOptions.end(), { "method", "bindless-access", "driver", "backend", "time" });
    const Arguments a =
      ParseArguments(argc, argv, 1, valueOptions, Concat({ DatasetFlags, { "compare", "stats" } }));
    if (WantsHelp(a))
    {
      std::cout << RenderIntro;
      PrintMethodHelp(std::cout, RenderCommand);
      std::cout << "  --method M                  auto (default: packing where an OpenGL context "
                   "can be\n"
                   "                              had, else cpu-packing) or one of the above:\n"
                   "                              "
                << MethodList(RenderCommand)
                << "\n"
                   "  --bindless-access A         auto (default), direct or waterfall (see "
                   "docs/design.md)\n"
                   "  --compare                   also render the CPU reference and the CPU "
                   "kD-tree\n"
                   "                              image and print the RMSE (0-255) against them\n"
                   "  --time all|N|A:B            a time series (synthetic:cosmo:...,steps=T,\n"
                   "                              regrid=K, or a quoted pattern such as\n"
                   "                              'run/plt*'): render these steps (0-based) in\n"
                   "                              order into numbered images (-o frame_%04d.png);\n"
                   "                              a step with the previous one's hierarchy only\n"
                   "                              uploads its values; --range says which\n"
                   "                              values the colours span (default: all\n"
                   "                              steps', so a frame does not depend on the\n"
                   "                              steps chosen), --compare compares each step\n"
                << ImageOptionsHelp(name) << ViewHelp << AtlasHelp << DriverHelp << DatasetHelp;
      return 0;
    }
    if (a.Positional.size() > 2)
    {
      throw UsageError{ "unexpected argument '" + a.Positional[2] + "'" };
    }
    std::string method = a.Get("method", "auto");
    if (method != "auto" && !FindMethod(method, RenderCommand))
    {
      throw UsageError{ "unknown --method '" + method + "' (available in this build: auto, " +
        MethodList(RenderCommand) + ")" };
    }
    BindlessAccess bindlessAccess = BindlessAccess::Auto;
    const std::string access = a.Get("bindless-access", "auto");
    if (!ParseIn(BindlessAccessNames, access.c_str(), bindlessAccess))
    {
      throw UsageError{ "unknown --bindless-access '" + access + "' (" +
        WordsOf(BindlessAccessNames) + ")" };
    }
    SelectDriver(a.Get("driver", "default"));
    SelectBackend(a.Get("backend", "auto"));
    if (method == "auto")
    {
      // the GPU mapper where an OpenGL context can be had, else its CPU mirror (said once)
      std::string why;
      method = GpuRenderer::Available(why) ? "packing" : "cpu-packing";
      if (method != "packing")
      {
        std::cerr << "amrsp: note: no OpenGL context for the GPU mapper (" << why
                  << "); rendering with cpu-packing\n";
      }
    }
    const Method& m = *FindMethod(method, RenderCommand);
    if (a.Has("time"))
    {
      if (a.Has("repeat"))
      {
        throw UsageError{ "--time renders each step once: no --repeat" };
      }
      return RenderSeries(m, method, a, bindlessAccess,
        [&m, &a](const Image& img, const LoadedDataset& d, const RenderSettings& s)
        { Compare(m, img, d, s, a); });
    }
    const AtlasRequest atlasRequest = ParseAtlasRequest(a);
    const std::string output = a.Get("output", name + ".png");
    LoadedDataset d = Load(a, true, false);
    glm::dvec2 range;
    const RenderSettings s = MakeSettings(d.Data, a, &range);
    const int repeat = RepeatCount(a);
    const ImageRun run = m.NeedsGpu ? RenderGpu(m, method, d, s, a, bindlessAccess, repeat)
                                    : RenderCpu(m, d, s, atlasRequest, repeat);
    WriteImageReport(method, d, a, s, range, output, repeat, run);
    if (a.Has("compare"))
    {
      Compare(m, run.Img, d, s, a);
    }
    WarnIfNearlyEmpty(run.Img);
    return 0;
  }
  catch (const UsageError& e)
  {
    return Fail(e.Message + " (see amrsp " + name + " --help)");
  }
  catch (const std::exception& e)
  {
    return Fail(e);
  }
}

} // namespace tool
} // namespace amrsp
