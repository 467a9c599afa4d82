// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A vtkOverlappingAMR handed from the checked reader's child process to the parent through a
/// file (vtkSinglePassAMRCheckedReader): the structure (levels, boxes, spacing, ratios) marshalled
/// by vtkCommunicator, then each image block's dimensions, origin, spacing and point and cell
/// arrays as raw bytes. Marshalling the whole AMR through VTK's legacy writer took 3.4 s for 4 M
/// cells in 2,666 blocks; the raw arrays take a copy. AMRs with other block types (VTK 9.6's
/// rectilinear blocks) go through vtkCommunicator whole.

#include "vtkSmartPointer.h"

#include <cstddef>

class vtkOverlappingAMR;

namespace vtkSinglePassAMRCheckedReaderTransfer
{
/// Writes `amr` to `fd` from its current offset; false when a write failed.
bool Write(vtkOverlappingAMR* amr, int fd);

/// The AMR that Write wrote, from `bytes` bytes at `data`; nullptr when they are not whole.
vtkSmartPointer<vtkOverlappingAMR> Read(const char* data, std::size_t bytes);
}
