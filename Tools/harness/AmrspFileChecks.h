// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What a dataset's own files say should be there, checked before VTK's reader opens them:
/// damaged or partial output (an interrupted copy, a missing processor file, a truncated write)
/// must end in one line that names the file and what is wrong with it, not in a reader that
/// loops, a bad_alloc, or a picture of part of the data. Each check throws DatasetError.

#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

/// The blocks a dataset's files describe, in the reader's block order (level by level), with
/// the file that holds each block's data, so that a block the reader could not load can be
/// named with its file.
struct ExpectedBlocks
{
  std::vector<std::string> Files;
  /// The variables the files list (AMReX Header), for a message when a reader finds none.
  std::vector<std::string> Variables;
  std::size_t Count() const { return Files.size(); }
};

/// Whether a box index read from a file lies strictly within +-2^30, so that extents and
/// indices refined by a few levels stay within int.
inline bool WithinIndexRange(long long v)
{
  return v > -(1LL << 30) && v < (1LL << 30);
}

/// An Enzo .hierarchy file: every grid entry complete (the file is not cut inside one), every
/// grid the entries point to described, and each grid's HDF5 file present, an HDF5 file, and as
/// long as its superblock says.
ExpectedBlocks CheckEnzoFiles(const std::string& hierarchy);

/// An AMReX plotfile folder: the Header complete, each level's multifab header (Cell_H) present,
/// agreeing with the Header on boxes and components, and each box's FAB in its Cell_D file
/// with a FAB header and all the bytes its box and components need.
ExpectedBlocks CheckAMReXFiles(const std::string& folder);

/// A VTK XML AMR file (.vthb/.vth/.vtm, version 1.x): its XML parses, and every block's piece
/// file exists. The blocks in level, then index, order.
ExpectedBlocks CheckVTKXMLAMRFiles(const std::string& path);

/// A VTK XML image piece (.vti) of an AMR file, before VTK's reader allocates for it: not empty,
/// an ImageData with a WholeExtent (each upper index not below its lower one), a finite origin, a
/// finite positive spacing, every NumberOfComponents 1 to 64, at least one DataArray. `role`
/// names the piece in messages ("block 3 of level 1 in FILE"). Returns its cells per axis (the
/// extent's points minus one).
std::vector<long long> CheckVTIPiece(const std::string& piece, const std::string& role);

/// Whether the file at `path` is an HDF5 file whose length is at least the end-of-file address
/// its superblock records; `why` says what is wrong otherwise.
bool CheckHDF5File(const std::string& path, std::string& why);

} // namespace harness
} // namespace amrsp
