// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A dataset read in a child process: VTK's readers assert (SIGABRT), crash, loop or allocate what
/// a damaged header asks for, and none of that may take the tool down or leave it with a
/// half-read reader's state. The child runs the file checks, the reader and the conversion, and
/// hands the hierarchy back through shared memory (a memfd the parent maps and borrows from);
/// the parent bounds its time and memory and turns every way it can end into one line.

#include "AmrspDataset.h"

#include "amrsp/Hierarchy.h"

#include <cstddef>
#include <functional>
#include <string>

namespace amrsp
{
namespace harness
{

/// A read that ended the child process abnormally: the message is one line, ExitCode what the
/// tool exits with (70 the reader crashed or aborted, 75 it did not finish in time).
class ReaderFailure : public DatasetError
{
public:
  ReaderFailure(const std::string& message, int exitCode)
    : DatasetError(message)
    , ExitCode(exitCode)
  {
  }
  int ExitCode;
};

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
/// (for debuggers).
IsolatedResult ReadInChildProcess(const std::string& what, double timeoutSeconds,
  std::size_t memoryBytes, const std::function<IsolatedResult()>& read);

/// Whether this process is a reading child of ReadInChildProcess (the parent bounds its time,
/// memory and signals, so in-process guards stand aside).
bool InReadingChild();

/// The address space a read of `paths` (files or folders, counted with their contents) may use:
/// 2 GiB for the libraries and the reader, plus 8 times the bytes on disk (the reader's copies,
/// the conversion, the values handed back), at most the machine's physical memory plus 1 GiB.
std::size_t ReadMemoryLimit(const std::vector<std::string>& paths);

} // namespace harness
} // namespace amrsp
