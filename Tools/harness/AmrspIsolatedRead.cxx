// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspIsolatedRead.h"

#include "AmrspProgress.h"

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
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <sstream>
#include <vector>

namespace amrsp
{
namespace harness
{
namespace
{
// ---- the hierarchy through a file descriptor ---------------------------------------------------
//
// Header, the levels' ratios (3 x int32 each), the grids (level, pad, lo, hi, source id), the
// array name and the format, then with values each grid's value count (uint64) and, from the next
// 64-byte boundary, every grid's floats back to back.

constexpr char Magic[8] = { 'A', 'M', 'R', 'S', 'P', 'H', 'I', '1' };

struct Header
{
  char Magic[8];
  uint32_t VertexCentred;
  uint32_t HasValues;
  double Origin[3];
  double Spacing0[3];
  uint64_t Levels;
  uint64_t Grids;
  uint64_t NameBytes;
  uint64_t FormatBytes;
};

struct GridRecord
{
  int32_t Level;
  int32_t Pad;
  int64_t Lo[3];
  int64_t Hi[3];
  int64_t SourceId;
};

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

std::size_t Align64(std::size_t n)
{
  return (n + 63) / 64 * 64;
}

/// Writes `r` to `fd` (from offset 0); false when a write fails (a full disk for the memfd).
bool WriteResult(int fd, const IsolatedResult& r)
{
  const Hierarchy& h = r.Data;
  Header header;
  std::memcpy(header.Magic, Magic, sizeof(Magic));
  header.VertexCentred = h.VertexCentred ? 1 : 0;
  header.HasValues = h.HasValues() ? 1 : 0;
  for (int a = 0; a < 3; ++a)
  {
    header.Origin[a] = h.Origin[a];
    header.Spacing0[a] = h.Spacing0[a];
  }
  header.Levels = h.RefinementRatio.size();
  header.Grids = h.Grids.size();
  header.NameBytes = h.ArrayName.size();
  header.FormatBytes = r.Format.size();
  std::string front(reinterpret_cast<const char*>(&header), sizeof(header));
  for (const glm::ivec3& ratio : h.RefinementRatio)
  {
    const int32_t v[3] = { ratio.x, ratio.y, ratio.z };
    front.append(reinterpret_cast<const char*>(v), sizeof(v));
  }
  for (const Grid& g : h.Grids)
  {
    GridRecord record{ g.Level, 0, { g.Cells.Lo.x, g.Cells.Lo.y, g.Cells.Lo.z },
      { g.Cells.Hi.x, g.Cells.Hi.y, g.Cells.Hi.z }, g.SourceId };
    front.append(reinterpret_cast<const char*>(&record), sizeof(record));
  }
  front += h.ArrayName;
  front += r.Format;
  if (header.HasValues)
  {
    for (const GridValues& v : h.Values)
    {
      const uint64_t count = v.size();
      front.append(reinterpret_cast<const char*>(&count), sizeof(count));
    }
    front.resize(Align64(front.size()), '\0');
  }
  if (!WriteAll(fd, front.data(), front.size()))
  {
    return false;
  }
  for (const GridValues& v : h.Values)
  {
    if (header.HasValues && !WriteAll(fd, v.data(), v.size() * sizeof(float)))
    {
      return false;
    }
  }
  return true;
}

/// The mapping of a finished read, unmapped when the last value borrowing from it goes.
struct Mapping
{
  void* Address = nullptr;
  std::size_t Bytes = 0;
  ~Mapping()
  {
    if (this->Address)
    {
      munmap(this->Address, this->Bytes);
    }
  }
};

/// Reads back what WriteResult wrote to `fd`; throws DatasetError when it is not whole.
IsolatedResult ReadResult(int fd, const std::string& what)
{
  struct stat st;
  if (fstat(fd, &st) != 0 || st.st_size < static_cast<off_t>(sizeof(Header)))
  {
    throw DatasetError(what + ": the reading process handed back no data");
  }
  auto mapping = std::make_shared<Mapping>();
  mapping->Bytes = static_cast<std::size_t>(st.st_size);
  mapping->Address = mmap(nullptr, mapping->Bytes, PROT_READ, MAP_SHARED, fd, 0);
  if (mapping->Address == MAP_FAILED)
  {
    mapping->Address = nullptr;
    throw DatasetError(what + ": cannot map the data the reading process handed back");
  }
  const char* base = static_cast<const char*>(mapping->Address);
  std::size_t at = 0;
  const auto take = [&](std::size_t bytes) -> const char*
  {
    if (bytes > mapping->Bytes - at)
    {
      throw DatasetError(what + ": the data the reading process handed back is cut short");
    }
    const char* p = base + at;
    at += bytes;
    return p;
  };
  Header header;
  std::memcpy(&header, take(sizeof(Header)), sizeof(Header));
  if (std::memcmp(header.Magic, Magic, sizeof(Magic)) != 0)
  {
    throw DatasetError(what + ": the data the reading process handed back is not a hierarchy");
  }
  IsolatedResult r;
  Hierarchy& h = r.Data;
  h.VertexCentred = header.VertexCentred != 0;
  for (int a = 0; a < 3; ++a)
  {
    h.Origin[a] = header.Origin[a];
    h.Spacing0[a] = header.Spacing0[a];
  }
  const std::size_t left = mapping->Bytes;
  if (header.Levels > left / 12 || header.Grids > left / sizeof(GridRecord) ||
    header.NameBytes > left || header.FormatBytes > left)
  {
    throw DatasetError(what + ": the data the reading process handed back is damaged");
  }
  h.RefinementRatio.clear();
  for (uint64_t l = 0; l < header.Levels; ++l)
  {
    int32_t v[3];
    std::memcpy(v, take(sizeof(v)), sizeof(v));
    h.RefinementRatio.push_back(glm::ivec3(v[0], v[1], v[2]));
  }
  for (uint64_t g = 0; g < header.Grids; ++g)
  {
    GridRecord record;
    std::memcpy(&record, take(sizeof(record)), sizeof(record));
    Grid grid;
    grid.Level = record.Level;
    grid.Cells.Lo = glm::i64vec3(record.Lo[0], record.Lo[1], record.Lo[2]);
    grid.Cells.Hi = glm::i64vec3(record.Hi[0], record.Hi[1], record.Hi[2]);
    grid.SourceId = record.SourceId;
    h.Grids.push_back(grid);
  }
  h.ArrayName.assign(take(header.NameBytes), header.NameBytes);
  r.Format.assign(take(header.FormatBytes), header.FormatBytes);
  if (header.HasValues)
  {
    std::vector<uint64_t> counts(header.Grids);
    for (uint64_t& c : counts)
    {
      std::memcpy(&c, take(sizeof(c)), sizeof(c));
    }
    take(Align64(at) - at);
    const std::shared_ptr<const void> owner = mapping;
    for (uint64_t c : counts)
    {
      if (c > (mapping->Bytes - at) / sizeof(float))
      {
        throw DatasetError(what + ": the data the reading process handed back is cut short");
      }
      const float* values = reinterpret_cast<const float*>(take(c * sizeof(float)));
      h.Values.push_back(GridValues::Borrow(values, c, owner));
    }
  }
  return r;
}

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

std::string TellingLine(const std::string& output)
{
  std::istringstream lines(output);
  std::string line, last, assertion;
  while (std::getline(lines, line))
  {
    line = PlainLogLine(line);
    const std::size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos)
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
  const std::function<IsolatedResult()>& read)
{
  ReadingChild = true;
  // the reader's own output (HDF5's error stack, assertions) goes to the output file; the
  // progress bar stays on the terminal
  SetProgressDescriptor(dup(2));
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
    const IsolatedResult r = read();
    code = WriteResult(dataFd, r) ? ChildRead : ChildNoSpace;
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

IsolatedResult ReadInChildProcess(const std::string& what, double timeoutSeconds,
  std::size_t memoryBytes, const std::function<IsolatedResult()>& read)
{
  const char* inProcess = std::getenv("AMRSP_READ_IN_PROCESS");
  if (inProcess && std::string(inProcess) == "1")
  {
    return read();
  }
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
    RunChild(dataFd, errorFd, outputFd, memoryBytes, read);
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
          "on; --read-timeout changes the limit)",
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
    IsolatedResult r = ReadResult(dataFd, what);
    closeAll(); // the mapping stays
    return r;
  }
  catch (...)
  {
    closeAll();
    throw;
  }
}

} // namespace harness
} // namespace amrsp
