// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspBenchWork.h"

#include "AmrspSinglePass.h"
#include "AmrspProgress.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include "amrsp/KdTree.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

using Json = nlohmann::ordered_json;

nlohmann::ordered_json WorkJson(const WorkSummary& w)
{
  Json j;
  j["source"] = "cpu mirror of the shader (amrsp/WorkCounters.h)";
  j["rays"] = w.Rays;
  j["pixels"] = w.Pixels;
  j["tiles"] = w.Tiles;
  const auto both = [&j](const char* name, const WorkDistribution& d)
  {
    j[std::string(name) + "_per_ray"] = d.Mean;
    j[std::string(name) + "_per_ray_p95"] = d.P95;
  };
  both("segments", w.Segments);
  both("descent_steps", w.DescentSteps);
  both("samples", w.Samples);
  both("texel_fetches", w.TexelFetches);
  both("steps", w.Steps);
  j["steps_per_pixel"] = w.StepsPerPixel;
  j["lockstep_steps_per_pixel"] = w.LockstepStepsPerPixel;
  j["lockstep_efficiency"] = w.LockstepEfficiency;
  if (w.FlatLoopStepsPerPixel > 0.0)
  {
    j["flat_loop_lockstep_steps_per_pixel"] = w.FlatLoopStepsPerPixel; // a prediction
  }
  return j;
}

BenchWork::BenchWork(const Hierarchy& h, const RenderSettings& s)
  : H(h)
  , S(s)
{
  S.Stats = nullptr;
}

BenchWork::~BenchWork() = default;

const EncodedKdTree& BenchWork::Tree()
{
  if (!Encoded)
  {
    Encoded = std::make_unique<EncodedKdTree>(EncodeKdTree(H, BuildKdTree(H)));
  }
  return *Encoded;
}

namespace
{
/// The fetch model of the storage a single-pass renderer used.
FetchModel FetchModelOf(DataStorage storage, const Hierarchy& h, const RenderSettings& s)
{
  FetchModel m;
  m.Storage = storage;
  m.VertexCentred = h.VertexCentred;
  m.SkipFlags = s.SkipEmptySpace && s.Blend == BlendMode::Composite;
  m.TransferPerSample = s.Blend == BlendMode::Composite || s.Blend == BlendMode::IsoSurface;
  return m;
}

/// The GPU's total agrees with the mirror's: within 1 % plus 2 per million rays.
bool Agrees(long long gpu, double mirror, long long rays)
{
  return std::fabs(static_cast<double>(gpu) - mirror) <= 0.01 * mirror + 2e-6 * rays + 0.5;
}
} // namespace

nlohmann::ordered_json BenchWork::SinglePass(GpuRenderer& gpu)
{
  SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(&gpu);
  if (!singlePass)
  {
    return { { "error", "not a single-pass renderer" } };
  }
  const DataStorage storage = singlePass->StorageUsed();
  auto found = SinglePassByStorage.find(storage);
  if (found == SinglePassByStorage.end())
  {
    RenderSettings s = S;
    s.Progress = ProgressOf("work model");
    found = SinglePassByStorage
              .emplace(storage, MeasureSinglePassWork(H, Tree(), s, FetchModelOf(storage, H, S)))
              .first;
  }
  const WorkSummary& w = found->second;
  Json j = WorkJson(w);
  j["storage"] = singlePass->StorageUsedInWords();
  using M = vtkSinglePassAMRVolumeMapper;
  double ms = 0.0;
  singlePass->Render(0.0, ms); // frame 0's camera, which the mirror counted
  const long long segments = singlePass->RenderWorkCount(M::SEGMENT_COUNT);
  const long long descent = singlePass->RenderWorkCount(M::DESCENT_STEP_COUNT);
  const long long samples = singlePass->RenderWorkCount(M::SAMPLE_COUNT);
  const double rays = static_cast<double>(w.Rays);
  if (S.GpuAblation != 0)
  {
    // an ablated frame does other work than the mirror counts: the shader's counts alone
    j["gpu"] = { { "segments", segments }, { "descent_steps", descent }, { "samples", samples },
      { "ablation", S.GpuAblation == 1 ? "traversal-only" : "sampling-only" } };
    return j;
  }
  const bool agrees = Agrees(segments, w.Segments.Mean * rays, w.Rays) &&
    Agrees(descent, w.DescentSteps.Mean * rays, w.Rays) &&
    Agrees(samples, w.Samples.Mean * rays, w.Rays);
  j["gpu"] = { { "segments", segments }, { "descent_steps", descent }, { "samples", samples },
    { "mirror_segments", std::llround(w.Segments.Mean * rays) },
    { "mirror_descent_steps", std::llround(w.DescentSteps.Mean * rays) },
    { "mirror_samples", std::llround(w.Samples.Mean * rays) }, { "agrees", agrees } };
  return j;
}

nlohmann::ordered_json BenchWork::Multipass()
{
  RenderSettings s = S;
  s.Progress = ProgressOf("work model");
  const WorkSummary w = MeasureMultipassWork(H, Tree(), s);
  Json j = WorkJson(w);
  j["draws"] = w.Draws;
  j["fragments_per_pixel"] = w.FragmentsPerPixel; // each one shaded and blended
  return j;
}

} // namespace tool
} // namespace amrsp
