// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `amrsp bench`: runs the rendering methods (AmrspMethods.h) on one hierarchy in one process,
/// and writes the results as JSON, as Markdown next to the paper's Tables 1 and 2
/// (AmrspBenchMarkdown.cxx), and as a bar-chart PNG (AmrspBenchPlot.h).

#include "AmrspGpuRenderer.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/Image.h"
#include "amrsp/RenderSettings.h"

#include "AmrspJson.h"

#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{
using namespace harness; // the datasets, renderers and checks the commands use

using BenchJson = nlohmann::ordered_json;

struct BenchOptions
{
  std::vector<std::string> Methods;
  int Frames = 8;
  ViewAngles View;
  /// false: timings only, no image comparison (no rmse, psnr, rmse_vs_* fields).
  bool CompareImages = true;
  /// Not empty: frame 0 of every method that ran is written there as METHOD.png (and the CPU
  /// reference as reference.png).
  std::string ImageFolder;
  /// > 1: after the first pass over the methods, the GPU methods' renderers stay alive and render
  /// Rounds - 1 more orbits each, interleaved (the order reversed every round), so that ratios
  /// between methods are taken from orbits rendered close in time: rounds_ms_mean, and
  /// fps_vs_packing (median over rounds of packing's ms / the method's ms).
  int Rounds = 1;
  /// > 0 (--interactive): after its orbit, every single-pass method draws each orbit frame with
  /// the render window's DesiredUpdateRate at this value (interactive), then still at the same
  /// camera: "interactive" {fps, ms_mean, still_ms_mean, speedup, rmse_mean, rmse_max, ...}.
  double InteractiveRate = 0.0;
  /// --counters: every GPU method that renders the kD-tree gets a "work" object (the cost model
  /// of amrsp/WorkCounters.h for frame 0, and the shader's own counts: AmrspBenchWork.h).
  bool Counters = false;
  /// --occupancy: every single-pass method gets an "occupancy" object, where the rays of frame 0
  /// ran (vtkSinglePassAMRVolumeMapper::OccupancyProbe; NVIDIA's GL_NV_shader_thread_group):
  /// {available, caster, rays, sms, sm_count, warps, most_warps_on_one_sm} or {available: false,
  /// why}.
  bool Occupancy = false;
};

/// Writes `img` as an 8-bit RGB PNG; throws std::runtime_error when it cannot.
void WriteImagePng(const Image& img, const std::string& path);

/// Table-1 statistics of `h` (grids, levels, cells, kd_nodes, kd_data_nodes) and the CPU seconds
/// of the tree, the encoding and the packing layout (`times_s` {tree, encode, pack}), measured
/// with the core functions the mappers call.
BenchJson DatasetStatistics(const Hierarchy& h);

/// Renders an orbit of `o.Frames` frames per method (after one untimed warm-up frame; every
/// frame ends with glFinish before the clock is read) and returns the "methods" object: per
/// method fps, ms_mean, ms_median, rmse and psnr of frame 0 against `reference` (0-255 units),
/// gpu_bytes, preprocess_s {...}, or {"error": why} when the method cannot run here. `stats` is
/// DatasetStatistics(h) (its times go into the methods' preprocess_s).
BenchJson RunBenchMethods(const Hierarchy& h, const RenderSettings& s, const Image& reference,
  const BenchOptions& o, const BenchJson& stats);

/// The "interactive" object of a single-pass method's result (BenchOptions::InteractiveRate),
/// after its orbit; `still0` is the orbit's frame 0 (still_bit_identical compares a still frame
/// drawn after the interactive ones with it). Does nothing for the other methods.
void InteractiveFields(GpuRenderer& gpu, const Image& still0, const BenchOptions& o, BenchJson& r);
/// `v` with `digits` decimals (the Markdown tables' figures).
std::string Fixed(double v, int digits);
/// The interactive frames' table of a "methods" object (empty without --interactive).
std::string InteractiveMarkdown(const BenchJson& methods);

/// 1, 2 or 3 when `stats` has the grid and level counts of the paper's dataset 1, 2 or 3
/// (Table 1), else 0.
int PaperDataset(const BenchJson& stats);

/// Table 1 (dataset statistics) and Table 2 (GPU memory, preprocessing, fps per method) of a
/// bench result, as Markdown, with the paper's figures beside ours where the dataset has a
/// paper size.
std::string BenchMarkdown(const BenchJson& bench);
/// The interleaved rounds' table of a "methods" object (empty without rounds).
std::string RoundsMarkdown(const BenchJson& methods);

/// The scaling table (one row per dataset size and method) of `amrsp bench --scaling`; its
/// header (`size` as "W×H") and the rows of one dataset size, printed as each size finishes.
std::string ScalingMarkdown(const BenchJson& scaling);
std::string ScalingMarkdownHeader(const std::string& size, int frames);
std::string ScalingMarkdownRow(const BenchJson& row);

} // namespace tool
} // namespace amrsp
