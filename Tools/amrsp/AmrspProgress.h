// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A progress bar on the terminal for the tool's long steps (the mappers' build and upload, from
/// their ProgressEvents). It draws on stderr only when stderr is a terminal and `--quiet` was not
/// given, and only once a step has run for about a second (AMRSP_PROGRESS_AFTER seconds), so that
/// short steps print nothing.

#include <string>

namespace amrsp
{
namespace tool
{

/// `--quiet`: no progress bar whatever stderr is.
void SetProgressQuiet(bool quiet);

/// Reports that the step `step` (e.g. "build") is `fraction` (0 to 1) done, now at `detail`;
/// a fraction of 1 ends the step's line.
void ReportProgress(const std::string& step, const std::string& detail, double fraction);

} // namespace tool
} // namespace amrsp
