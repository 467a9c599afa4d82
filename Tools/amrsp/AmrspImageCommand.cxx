// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspImageCommand.h"

#include <algorithm>
#include <iostream>
#include <sstream>

namespace amrsp
{
namespace tool
{

std::vector<std::string> ImageValueOptions()
{
  std::vector<std::string> options =
    Concat({ DatasetOptions, RenderOptionNames, AtlasOptions, { "output" } });
  options.push_back("repeat");
  return options;
}

std::string ImageOptionsHelp(const std::string& name)
{
  return "  -o, --output FILE           PNG to write (default " + name +
    ".png)\n"
    "  --repeat N                  render N timed frames after the first (default\n"
    "                              1); prints their mean and minimum time\n"
    "  --stats                     print the work counters (CPU: samples, skipped\n"
    "                              segments and samples, terminated rays; packing:\n"
    "                              transparent data nodes)\n";
}

int RepeatCount(const Arguments& a)
{
  const int repeat = static_cast<int>(a.GetNumber("repeat", 1.0));
  if (repeat < 1)
  {
    throw UsageError{ "--repeat must be at least 1" };
  }
  return repeat;
}

std::string CpuStatsReport(const RenderStats& stats)
{
  std::ostringstream report;
  report << "stats: rays " << stats.Rays << ", samples " << stats.Samples << ", data segments "
         << stats.DataSegments << ", skipped segments " << stats.SkippedSegments << " ("
         << stats.SkippedSamples << " samples), rays terminated early " << stats.TerminatedRays;
  if (stats.Segments > 0)
  {
    report << ", traversal segments " << stats.Segments << " (tree levels descended "
           << "per segment " << double(stats.DescentLevels) / double(stats.Segments) << ")";
  }
  report << "\n";
  return report.str();
}

void WriteImageReport(const std::string& method, const LoadedDataset& d, const Arguments& a,
  const RenderSettings& s, const glm::dvec2& range, const std::string& output, int repeat,
  const ImageRun& run)
{
  const std::vector<double>& frameMs = run.FrameMs;
  double meanMs = 0.0, minMs = frameMs.empty() ? 0.0 : frameMs.front();
  for (double ms : frameMs)
  {
    meanMs += ms / static_cast<double>(frameMs.size());
    minMs = std::min(minMs, ms);
  }
  const double renderSeconds = meanMs / 1000.0;
  WritePng(run.Img, output);
  std::cout << "method: " << method << "\n"
            << "dataset: " << d.Spec << " (" << d.Format << "), array " << d.Data.ArrayName << ", "
            << d.Data.Grids.size() << " grids, " << d.Data.NumberOfLevels() << " levels\n"
            << "scalars: " << d.Data.ArrayName << " in [" << range.x << ", " << range.y
            << "], transfer function '"
            << (a.Has("view-json") && !a.Has("tf") ? "view-json" : a.Get("tf", "default")) << "'\n"
            << "image: " << output << " (" << s.Width << "x" << s.Height << ")\n"
            << run.DeviceReport << "times (s): load " << d.LoadSeconds << ", preprocess "
            << run.PreprocessSeconds << ", render " << renderSeconds << "\n";
  if (repeat > 1)
  {
    std::cout << "frames: " << repeat << ", ms mean " << meanMs << ", min " << minMs << "\n";
  }
  if (a.Has("stats"))
  {
    std::cout << run.StatsReport;
  }
}

void WarnIfNearlyEmpty(const Image& img)
{
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
}

} // namespace tool
} // namespace amrsp
