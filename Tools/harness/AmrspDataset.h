// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Dataset arguments of the amrsp tool: a path (Enzo .hierarchy, AMReX plotfile folder,
/// VTK XML AMR .vthb/.vth/.vtm), `synthetic:pulse`, or
/// `synthetic:cosmo[:grids=N,levels=L,cells=C,seed=S]`.

#include "AmrspDatasetError.h"

#include "amrsp/Hierarchy.h"

#include "vtkOverlappingAMR.h"
#include "vtkSmartPointer.h"

#include <stdexcept>
#include <string>

namespace amrsp
{
namespace harness
{

struct DatasetRequest
{
  std::string Spec;
  std::string Array;  ///< empty: the first cell array
  int Component = -1; ///< -1: magnitude of multi-component arrays
  /// "auto" keeps the array's own centring (cell data: cell-centred, point data:
  /// vertex-centred); "vertex" converts cell data to vertices; "cell" refuses point data.
  std::string Centering = "auto";
  bool NeedValues = true;
  bool NeedVTK = true; ///< false: synthetic:cosmo may skip building a vtkOverlappingAMR
  /// A file read that yields fewer blocks with the array than the dataset's own files describe
  /// is an error unless this is set (then a warning on stderr says how many were read).
  bool AllowPartial = false;
  /// A VTK reader that has not finished after this many seconds ends the process with one line
  /// (exit code 75): some readers loop forever on damaged files.
  double ReadTimeoutSeconds = 120.0;
};

struct LoadedDataset
{
  std::string Spec;
  std::string Format; ///< enzo, amrex, vtk-xml-amr, synthetic:pulse, synthetic:cosmo
  vtkSmartPointer<vtkOverlappingAMR> Amr; ///< null only when NeedVTK was false
  Hierarchy Data;
  double LoadSeconds = 0.0;
};

/// Loads the dataset. Throws DatasetError with one line naming the problem: missing path,
/// unknown format, a damaged, truncated or missing file (checked before VTK's reader opens the
/// files: AmrspFileChecks.h), reader failure (with the reader's own message), missing array, no
/// blocks, fewer blocks read than the files describe.
LoadedDataset LoadDataset(const DatasetRequest& request);
/// LoadDataset without applying DatasetRequest::Centering.
LoadedDataset LoadDatasetAsStored(const DatasetRequest& request);

} // namespace harness
} // namespace amrsp
