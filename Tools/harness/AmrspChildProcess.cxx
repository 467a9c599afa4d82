// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspChildProcess.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>
#include <sstream>

namespace amrsp
{
namespace harness
{
bool WriteAll(int fd, const void* data, std::size_t bytes)
{
  const char* p = static_cast<const char*>(data);
  while (bytes > 0)
  {
    const ssize_t n = write(fd, p, std::min<std::size_t>(bytes, std::size_t(1) << 30));
    if (n < 0 && errno == EINTR)
    {
      continue;
    }
    if (n <= 0)
    {
      return false;
    }
    p += n;
    bytes -= static_cast<std::size_t>(n);
  }
  return true;
}

namespace
{
// ---- the child process ----------------------------------------------------------------------

/// A memfd (anonymous file), or -1.
int AnonymousFile(const char* name)
{
  return memfd_create(name, MFD_CLOEXEC);
}

/// The text of `fd` from its start (at most the last `most` bytes).
std::string ReadText(int fd, std::size_t most)
{
  struct stat st;
  if (fstat(fd, &st) != 0 || st.st_size <= 0)
  {
    return "";
  }
  const std::size_t size = static_cast<std::size_t>(st.st_size);
  const std::size_t from = size > most ? size - most : 0;
  std::string text(size - from, '\0');
  const ssize_t n = pread(fd, &text[0], text.size(), static_cast<off_t>(from));
  text.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
  return text;
}

/// The one line of what a dead reader printed that says most: an assertion's text, else the last
/// line; empty when it printed nothing.
/// A line of VTK's log without its terminal colours ("\x1b[31m") and its loguru prefix
/// ("2026-11-28 03:30:16.051 (   0.069s) [  D6021DC0]  file.txx:389  ERR| ").
std::string PlainLogLine(std::string line)
{
  for (std::size_t e = line.find('\x1b'); e != std::string::npos; e = line.find('\x1b', e))
  {
    const std::size_t m = line.find('m', e);
    line.erase(e, m == std::string::npos ? std::string::npos : m - e + 1);
  }
  const std::size_t bar = line.find("| ");
  if (bar != std::string::npos && bar < 120 && line.find(") [") < bar)
  {
    line = line.substr(bar + 2);
  }
  return line;
}

/// Whether `line` is what Open MPI's signal handler prints ("[host:01234] [ 5] /usr/lib/...",
/// "[host:01234] *** Process received signal ***"): a reader in an MPI program (ParaView 6.1's
/// pvpython) dies with a backtrace that says nothing about the file.
bool MPISignalReport(const std::string& line)
{
  const std::size_t close = line.find("] ");
  const std::size_t colon = line.find(':');
  return !line.empty() && line[0] == '[' && close != std::string::npos &&
    colon != std::string::npos && colon < close &&
    line.find_first_not_of("0123456789", colon + 1) == close;
}

std::string TellingLine(const std::string& output)
{
  std::istringstream lines(output);
  std::string line, last, assertion;
  while (std::getline(lines, line))
  {
    line = PlainLogLine(line);
    const std::size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || MPISignalReport(line.substr(a)))
    {
      continue;
    }
    line = line.substr(a);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' '))
    {
      line.pop_back();
    }
    last = line;
    if (line.find("Assertion") != std::string::npos || line.find("assert") != std::string::npos)
    {
      assertion = line;
    }
  }
  std::string telling = assertion.empty() ? last : assertion;
  if (telling.size() > 300)
  {
    telling = telling.substr(0, 297) + "...";
  }
  return telling;
}

std::string SignalName(int signal)
{
  switch (signal)
  {
    case SIGABRT:
      return "SIGABRT, an abort";
    case SIGSEGV:
      return "SIGSEGV, a segmentation fault";
    case SIGBUS:
      return "SIGBUS, a bus error";
    case SIGFPE:
      return "SIGFPE, an arithmetic error";
    case SIGILL:
      return "SIGILL, an illegal instruction";
    case SIGKILL:
      return "SIGKILL";
    default:
      return "signal " + std::to_string(signal);
  }
}

/// The exit codes of the child.
enum ChildExit : int
{
  ChildRead = 0,
  // not 1: the sanitizers' and many libraries' own exit code
  ChildError = 101,       ///< `read` threw: the message is in the error file
  ChildOutOfMemory = 102, ///< std::bad_alloc
  ChildNoSpace = 103      ///< the result could not be written
};

bool ReadingChild = false;

[[noreturn]] void RunChild(int dataFd, int errorFd, int outputFd, std::size_t memoryBytes,
  const std::function<bool(int)>& work, const std::function<void()>& inChild)
{
  ReadingChild = true;
  if (inChild)
  {
    inChild();
  }
  // the reader's own output (HDF5's error stack, assertions) goes to the output file
  dup2(outputFd, 2);
#if !defined(__SANITIZE_ADDRESS__)
  struct rlimit limit;
  limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(memoryBytes);
  setrlimit(RLIMIT_AS, &limit);
#else
  (void)memoryBytes; // AddressSanitizer reserves terabytes of address space: its own limits apply
#endif
  int code = ChildRead;
  std::string message;
  try
  {
    code = work(dataFd) ? ChildRead : ChildNoSpace;
  }
  catch (const std::bad_alloc&)
  {
    code = ChildOutOfMemory;
  }
  catch (const std::exception& e)
  {
    code = ChildError;
    message = e.what();
  }
  if (!message.empty())
  {
    WriteAll(errorFd, message.data(), message.size());
  }
  // no destructors, no atexit handlers: the parent's X and OpenGL connections are shared
  _exit(code);
}
} // namespace

bool InReadingChild()
{
  return ReadingChild;
}

std::size_t ReadMemoryLimit(const std::vector<std::string>& paths)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  unsigned long long bytes = 0;
  for (const std::string& p : paths)
  {
    if (fs::is_directory(p, ec))
    {
      for (auto it = fs::recursive_directory_iterator(p, ec);
           !ec && it != fs::recursive_directory_iterator(); it.increment(ec))
      {
        if (it->is_regular_file(ec))
        {
          bytes += it->file_size(ec);
        }
      }
    }
    else
    {
      bytes += fs::file_size(p, ec);
    }
  }
  const unsigned long long gib = 1ULL << 30;
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  const unsigned long long physical = pages > 0 && pageSize > 0
    ? static_cast<unsigned long long>(pages) * static_cast<unsigned long long>(pageSize)
    : 64 * gib;
  return static_cast<std::size_t>(std::min(2 * gib + 8 * bytes, physical + gib));
}

int RunInChildProcess(const std::string& what, double timeoutSeconds,
  const std::string& timeoutSetting, std::size_t memoryBytes,
  const std::function<bool(int resultFd)>& work, const std::function<void()>& inChild)
{
  const int dataFd = AnonymousFile("amrsp-read-data");
  const int errorFd = AnonymousFile("amrsp-read-error");
  const int outputFd = AnonymousFile("amrsp-read-output");
  if (dataFd < 0 || errorFd < 0 || outputFd < 0)
  {
    for (int fd : { dataFd, errorFd, outputFd })
    {
      if (fd >= 0)
      {
        close(fd);
      }
    }
    throw DatasetError(what + ": cannot create the shared files of a reading process (" +
      std::strerror(errno) + ")");
  }
  const auto closeAll = [&]
  {
    close(dataFd);
    close(errorFd);
    close(outputFd);
  };
  // the child holds the write end of `ended` until it exits: the parent's poll wakes then
  int ended[2] = { -1, -1 };
  if (pipe2(ended, O_CLOEXEC) != 0)
  {
    closeAll();
    throw DatasetError(what + ": cannot start a reading process (" + std::strerror(errno) + ")");
  }
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0)
  {
    close(ended[0]);
    close(ended[1]);
    closeAll();
    throw DatasetError(what + ": cannot start a reading process (" + std::strerror(errno) + ")");
  }
  if (child == 0)
  {
    close(ended[0]);
    RunChild(dataFd, errorFd, outputFd, memoryBytes, work, inChild);
  }
  close(ended[1]);
  // wait, at most timeoutSeconds
  int status = 0;
  bool timedOut = false, reaped = false;
  const auto start = std::chrono::steady_clock::now();
  for (;;)
  {
    const double left = timeoutSeconds -
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (left <= 0.0)
    {
      kill(child, SIGKILL);
      timedOut = true;
      break;
    }
    pollfd end{ ended[0], POLLIN, 0 };
    const int waitMs = static_cast<int>(std::min(left * 1000.0 + 1.0, 1000.0));
    if (poll(&end, 1, waitMs) > 0)
    {
      break; // the child exited
    }
    // a process the reader started may hold the end still: look at the child itself too
    if (waitpid(child, &status, WNOHANG) == child)
    {
      reaped = true;
      break;
    }
  }
  close(ended[0]);
  while (!reaped && waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  const std::string said = TellingLine(ReadText(outputFd, 1 << 16));
  std::ostringstream timeout;
  timeout << timeoutSeconds;
  try
  {
    if (timedOut)
    {
      throw ReaderFailure(what + " did not finish within " + timeout.str() +
          " s: VTK's reader is stuck on this file (a damaged or unusual file the reader loops "
          "on; " +
          timeoutSetting + " changes the limit)",
        75);
    }
    if (WIFSIGNALED(status))
    {
      const int signal = WTERMSIG(status);
      if (signal == SIGKILL)
      {
        throw DatasetError(what +
          ": the reading process was killed (SIGKILL): the system ran "
          "out of memory, or a size in a damaged file is wrong");
      }
      throw ReaderFailure(what + " crashed inside VTK's reader (" + SignalName(signal) +
          (said.empty() ? std::string() : ": " + said) +
          "): a damaged file the checks do not know of, or a reader bug",
        70);
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    const std::string thrown = code == ChildError ? ReadText(errorFd, 1 << 16) : std::string();
    if (code == ChildError && !thrown.empty())
    {
      throw DatasetError(thrown);
    }
    if (code == ChildOutOfMemory)
    {
      throw DatasetError("ran out of memory " + what +
        ": the data is larger than this machine's memory, or a size in a damaged file is wrong");
    }
    if (code == ChildNoSpace)
    {
      throw DatasetError(what + ": cannot hand the data back (no space for the shared file)");
    }
    if (code != ChildRead)
    {
      throw ReaderFailure(what + ": the reading process ended with exit code " +
          std::to_string(code) + (said.empty() ? std::string() : ": " + said),
        70);
    }
    close(errorFd);
    close(outputFd);
    return dataFd;
  }
  catch (...)
  {
    closeAll();
    throw;
  }
}

} // namespace harness
} // namespace amrsp
