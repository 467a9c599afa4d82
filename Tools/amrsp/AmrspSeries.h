// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Time series in the amrsp tool: which datasets make up a series, which steps --time selects,
/// the numbered outputs, and the series commands (`render --time`, `bench --time-series`).
///
/// A series is
/// - `synthetic:cosmo:...,steps=T[,regrid=K]`: its T steps (amrsp::GenerateCosmoStep);
/// - a path pattern with `*` or `?` (quote it for the shell): the matching files or folders in
///   name order, numbers compared as numbers (plt9 before plt10), one step each;
/// - anything else: one step.

#include "AmrspCommands.h"
#include "AmrspDataset.h"
#include "AmrspMethods.h"
#include "AmrspRenderOptions.h"

#include <functional>

#include <string>
#include <vector>

namespace amrsp
{
namespace tool
{

/// The dataset argument of each step of the series `spec` (see above). Throws DatasetError for
/// a pattern that matches nothing and UsageError for bad synthetic parameters.
std::vector<std::string> SeriesSteps(const std::string& spec);

/// The steps `--time` selects among `count`: "all", "N" or "A:B" (inclusive), 0-based. Throws
/// UsageError naming the problem.
std::vector<int> SelectSteps(const std::string& time, int count);

/// The image path of step `step`: `pattern` with its printf field (%d, %04d, ...) filled in, or,
/// without one, "_NNNN" inserted before the extension.
std::string StepOutputPath(const std::string& pattern, int step);

/// What `render --compare` does for one image of a step (its dataset and settings).
using SeriesCompare =
  std::function<void(const Image&, const LoadedDataset&, const RenderSettings&)>;

/// `amrsp render SERIES --time T -o PATTERN`: the selected steps rendered in order by one
/// renderer of `method` (GPU: each step a new input of the same mapper, so that a step of the
/// same structure refreshes the values only), one line per step. The scale rule (--scale) and
/// the transfer function's range follow --range: `all` (default) the values of every step of
/// the series, read once before the first image, so that a step's frame does not depend on the
/// steps --time selects; `step` each step's own, as a single render; `LO:HI` as given. The
/// camera is the first selected step's (ResetCamera to its domain). With --compare, `compare`
/// runs on each step's image.
int RenderSeries(const Method& m, std::string method, const Arguments& a,
  BindlessAccess bindlessAccess, const SeriesCompare& compare);

/// `amrsp bench SERIES --time-series [--methods ...]`: per GPU method, every step after the
/// first rendered by one renderer; step_switch_s is the median time from the step's data in
/// memory (a new vtkOverlappingAMR) to its first image over the steps whose hierarchy did not
/// change, rebuild_s the same over those with a regrid. Prints a table, or JSON with --json.
int BenchSeries(const Arguments& a);

/// `amrsp bench SERIES --soak N [--methods M]`: N step changes, each step read again from its
/// files (or generated) as a reader hands it over, each with a camera move, through one
/// renderer of one GPU method (default packing); the colours span all steps. Prints the
/// resident memory and the open file descriptors at the start, after the warm-up (every step
/// twice, at least 10 changes) and at the end, or JSON with --json (with a trace of 20 samples).
int SoakSeries(const Arguments& a);

} // namespace tool
} // namespace amrsp
