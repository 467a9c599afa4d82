// SPDX-License-Identifier: BSD-3-Clause
// `amrsp bench --interactive`: the single-pass mapper's interactive frames against its still
// frames, orbit frame by orbit frame (docs/command-line.md).
#include "AmrspJson.h"

#include "AmrspBench.h"

#include "AmrspSinglePass.h"

#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
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
/// vtkRenderWindow's default DesiredUpdateRate: every prop has far more than a second.
constexpr double StillUpdateRate = 0.0001;

double Mean(const std::vector<double>& v)
{
  double sum = 0.0;
  for (double x : v)
  {
    sum += x;
  }
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

} // namespace

void InteractiveFields(GpuRenderer& gpu, const Image& still0, const BenchOptions& o, BenchJson& r)
{
  SinglePassRenderer* singlePass = dynamic_cast<SinglePassRenderer*>(&gpu);
  if (!singlePass)
  {
    return; // only the single-pass mapper adapts interactive frames
  }
  vtkSinglePassAMRVolumeMapper* mapper = singlePass->GetMapper();
  vtkRenderWindow* window = gpu.GetRenderer()->GetRenderWindow();
  std::vector<double> interactiveMs, stillMs, rmse, distance, scale, budget;
  for (int f = 0; f < o.Frames; ++f)
  {
    const double angle = 360.0 * f / o.Frames;
    double ms = 0.0;
    window->SetDesiredUpdateRate(o.InteractiveRate);
    const Image interactive = gpu.Render(angle, ms);
    interactiveMs.push_back(ms);
    distance.push_back(mapper->GetLastImageSampleDistance());
    scale.push_back(mapper->GetLastSampleDistanceScale());
    budget.push_back(mapper->GetLastFrameBudget());
    window->SetDesiredUpdateRate(StillUpdateRate);
    const Image still = gpu.Render(angle, ms);
    stillMs.push_back(ms);
    rmse.push_back(Rmse(interactive, still));
  }
  double ms = 0.0;
  const Image again = gpu.Render(0.0, ms);
  BenchJson j;
  j["desired_update_rate"] = o.InteractiveRate;
  j["allocated_s"] = Mean(budget);
  j["fps"] = 1000.0 / Mean(interactiveMs);
  j["ms_mean"] = Mean(interactiveMs);
  j["still_ms_mean"] = Mean(stillMs);
  j["speedup"] = Mean(stillMs) / Mean(interactiveMs);
  j["rmse_mean"] = Mean(rmse);
  j["rmse_max"] = *std::max_element(rmse.begin(), rmse.end());
  j["image_sample_distance"] = distance;
  j["sample_distance_scale"] = scale;
  j["rmse"] = rmse;
  j["still_bit_identical"] = Rmse(again, still0) == 0.0;
  r["interactive"] = j;
}

std::string InteractiveMarkdown(const BenchJson& methods)
{
  std::ostringstream md;
  for (const auto& item : methods.items())
  {
    if (!item.value().contains("interactive"))
    {
      continue;
    }
    const BenchJson& j = item.value()["interactive"];
    if (md.tellp() == 0)
    {
      md << "\nInteractive frames (DesiredUpdateRate "
         << Fixed(j["desired_update_rate"].get<double>(), 1)
         << "; each orbit frame drawn interactively, then still at the same camera; RMSE 0-255 "
            "of the interactive frame against its still frame)\n\n"
         << "| method | allocated [s] | interactive ms/frame | still ms/frame | speedup | "
            "image sample distance | RMSE mean (max) | still frame unchanged |\n"
         << "|---|---|---|---|---|---|---|---|\n";
    }
    const std::vector<double> d = j["image_sample_distance"].get<std::vector<double>>();
    md << "| " << item.key() << " | " << Fixed(j["allocated_s"].get<double>(), 3) << " | "
       << Fixed(j["ms_mean"].get<double>(), 1) << " | "
       << Fixed(j["still_ms_mean"].get<double>(), 1) << " | "
       << Fixed(j["speedup"].get<double>(), 2) << " | "
       << Fixed(*std::min_element(d.begin(), d.end()), 1) << "–"
       << Fixed(*std::max_element(d.begin(), d.end()), 1) << " | "
       << Fixed(j["rmse_mean"].get<double>(), 2) << " (" << Fixed(j["rmse_max"].get<double>(), 2)
       << ") | " << (j["still_bit_identical"].get<bool>() ? "bit for bit" : "NO") << " |\n";
  }
  return md.str();
}

} // namespace tool
} // namespace amrsp
