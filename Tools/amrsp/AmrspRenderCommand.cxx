// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspCommandShared.h"

#include "AmrspDriver.h"
#include "AmrspLighting.h"
#include "AmrspMultipass.h"
#include "AmrspPacking.h"
#include "AmrspUniform.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/KdTree.h"
#include "amrsp/VertexData.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace amrsp
{
namespace tool
{

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

} // namespace tool
} // namespace amrsp
