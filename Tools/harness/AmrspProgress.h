// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A progress bar on the terminal for the tool's long steps (the mappers' build and upload, from
/// their ProgressEvents). It draws on stderr only when stderr is a terminal and `--quiet` was not
/// given, and only once a step has run for about a second (AMRSP_PROGRESS_AFTER seconds), so that
/// short steps print nothing.

#include "amrsp/Progress.h"

#include <string>

namespace amrsp
{
namespace harness
{

/// `--quiet`: no progress bar whatever stderr is.
void SetProgressQuiet(bool quiet);

/// The file descriptor the bar is drawn on (default 2, stderr): a step that redirects stderr
/// (the readers' message capture) keeps the bar on the terminal by naming the saved one.
void SetProgressDescriptor(int fd);

/// Reports that the step `step` (e.g. "build") is `fraction` (0 to 1) done, now at `detail`;
/// a fraction of 1 ends the step's line.
void ReportProgress(const std::string& step, const std::string& detail, double fraction);

/// A core progress callback (amrsp/Progress.h) that reports to the bar as step `step`.
ProgressCallback ProgressOf(const std::string& step, const std::string& detail = "");

} // namespace harness
} // namespace amrsp
