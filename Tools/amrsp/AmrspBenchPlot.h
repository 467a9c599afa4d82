// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `amrsp bench --plot FILE.png`: bar charts of a bench result (fps, GPU memory, RMSE per
/// method), drawn on the CPU into a vtkImageData (text by vtkTextRenderer/FreeType) so that
/// no OpenGL context is needed.

#include "AmrspBench.h"

#include <string>

namespace amrsp
{
namespace tool
{

/// Writes a `width` x `height` RGB PNG with three horizontal bar charts, one bar per method
/// (methods that could not run are named with "cannot run"). Throws std::runtime_error when the
/// file cannot be written or the size is below 300 x 200.
void WriteBenchPlot(const BenchJson& bench, const std::string& path, int width, int height);

} // namespace tool
} // namespace amrsp
