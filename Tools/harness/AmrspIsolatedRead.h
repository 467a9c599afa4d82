// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A dataset read in a child process: VTK's readers assert (SIGABRT), crash, loop or allocate what
/// a damaged header asks for, and none of that may take the tool down or leave it with a
/// half-read reader's state. The child runs the file checks, the reader and the conversion, and
/// hands the hierarchy back through shared memory (a memfd the parent maps and borrows from);
/// the parent bounds its time and memory and turns every way it can end into one line.

#include "AmrspChildProcess.h"
#include "AmrspDataset.h"

#include "amrsp/Hierarchy.h"

#include <cstddef>
#include <functional>
#include <string>

namespace amrsp
{
namespace harness
{

/// What a child's read hands back.
struct IsolatedResult
{
  Hierarchy Data;     ///< values borrowed from the shared memory (kept alive by the values)
  std::string Format; ///< as LoadedDataset::Format
};

/// Runs `read` in a child process and returns what it returned. `what` names the read in
/// messages ("reading the Enzo hierarchy FILE"). The child may use at most `memoryBytes` of
/// address space (RLIMIT_AS) and `timeoutSeconds` of time (then it is killed). Throws:
/// DatasetError with the child's own message when `read` threw (a std::bad_alloc becomes "ran out
/// of memory reading ..."); ReaderFailure (exit code 70) when the child died by a signal or an
/// abort, naming the signal and the last line the reader printed (an assertion's text); (75)
/// when it did not finish in time. AMRSP_READ_IN_PROCESS=1 runs `read` in this process instead
/// (for debuggers). Runs through RunInChildProcess (AmrspChildProcess.h).
IsolatedResult ReadInChildProcess(const std::string& what, double timeoutSeconds,
  std::size_t memoryBytes, const std::function<IsolatedResult()>& read);

} // namespace harness
} // namespace amrsp
