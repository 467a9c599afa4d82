// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// What this process holds now (Linux /proc/self): its resident memory and its open file
/// descriptors, for the series and soak commands that must show neither grows over a run.

namespace amrsp
{
namespace harness
{

/// Resident memory of this process in bytes (VmRSS of /proc/self/status); -1 where unknown.
long long ResidentBytes();

/// Peak resident memory of this process in bytes (VmHWM of /proc/self/status); -1 where unknown.
long long PeakResidentBytes();

/// Open file descriptors of this process (entries of /proc/self/fd, less the one that lists
/// them); -1 where unknown.
int OpenDescriptors();

} // namespace harness
} // namespace amrsp
