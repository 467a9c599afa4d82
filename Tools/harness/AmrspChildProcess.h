// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Work that may kill its process, run in a forked child: VTK's readers assert (SIGABRT), crash,
/// loop or allocate what a damaged header asks for. The parent bounds the child's time and
/// address space and turns every way it can end into one line (AmrspDatasetError.h). Used by
/// the tool's reads (AmrspIsolatedRead.h) and by the ParaView plugin's checked reader.

#include "AmrspDatasetError.h"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace amrsp
{
namespace harness
{

/// Runs `work` in a child process. `work` writes what it hands back to the file descriptor it is
/// given (an anonymous file, from offset 0) and returns false when a write failed. `what` names
/// the work in messages ("reading the Enzo hierarchy FILE"). The child may use at most
/// `memoryBytes` of address space (RLIMIT_AS; not under AddressSanitizer) and `timeoutSeconds`
/// of time (then it is killed, and the message names `timeoutSetting`, where the user changes
/// the limit). `inChild`, when set, runs first in the child, while its standard error is still
/// the parent's. Returns the anonymous file (the caller closes it) when `work` returned true.
/// Throws DatasetError with `work`'s own message when it threw (a std::bad_alloc becomes "ran
/// out of memory ..."); ReaderFailure (exit code 70) when the child died by a signal or an
/// abort, naming the signal and the line the child printed that says most (an assertion's text,
/// else its last); (75) when it did not finish in time.
int RunInChildProcess(const std::string& what, double timeoutSeconds,
  const std::string& timeoutSetting, std::size_t memoryBytes,
  const std::function<bool(int resultFd)>& work, const std::function<void()>& inChild = {});

/// Writes all `bytes` at `data` to `fd`, retrying short writes; false when a write fails.
bool WriteAll(int fd, const void* data, std::size_t bytes);

/// Whether this process is a child of RunInChildProcess (the parent bounds its time, memory and
/// signals, so in-process guards stand aside).
bool InReadingChild();

/// The address space a read of `paths` (files or folders, counted with their contents) may use:
/// 2 GiB for the libraries and the reader, plus 8 times the bytes on disk (the reader's copies,
/// the conversion, the values handed back), at most the machine's physical memory plus 1 GiB.
std::size_t ReadMemoryLimit(const std::vector<std::string>& paths);

} // namespace harness
} // namespace amrsp
