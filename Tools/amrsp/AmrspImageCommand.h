// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What `amrsp render` (AmrspRenderCommand.cxx) and `amrsp reference`
/// (AmrspReferenceCommand.cxx) share: their common options, the timed frames and the report
/// they print.

// first: see AmrspJson.h
#include "AmrspCommandShared.h"

#include "amrsp/Image.h"
#include "amrsp/RenderSettings.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{

/// The value options both commands take: the dataset, view and atlas options, --output and
/// --repeat.
std::vector<std::string> ImageValueOptions();

/// The help lines of --output (default NAME.png), --repeat and --stats.
std::string ImageOptionsHelp(const std::string& name);

/// --repeat N (default 1); throws UsageError below 1.
int RepeatCount(const Arguments& a);

/// The frames one command rendered and what it reports about them.
struct ImageRun
{
  Image Img;                   ///< the last frame
  std::vector<double> FrameMs; ///< the timed frames, milliseconds
  double PreprocessSeconds = 0.0;
  std::string DeviceReport; ///< lines on the GPU method's device, storage and build
  std::string StatsReport;  ///< the --stats lines
};

/// "stats: rays ..., samples ..., ..." of a CPU integrator's work counters (one line).
std::string CpuStatsReport(const RenderStats& stats);

/// Writes run.Img to `output` and prints the report: method, dataset, scalars, image, the device
/// lines, times, the frames when --repeat > 1 and the --stats lines.
void WriteImageReport(const std::string& method, const LoadedDataset& d, const Arguments& a,
  const RenderSettings& s, const glm::dvec2& range, const std::string& output, int repeat,
  const ImageRun& run);

/// A warning on stderr when fewer than 0.1 % of the pixels have an opacity above 0.02.
void WarnIfNearlyEmpty(const Image& img);

} // namespace tool
} // namespace amrsp
