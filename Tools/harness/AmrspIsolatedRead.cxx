// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspIsolatedRead.h"

#include "AmrspProgress.h"

#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
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
} // namespace

IsolatedResult ReadInChildProcess(const std::string& what, double timeoutSeconds,
  std::size_t memoryBytes, const std::function<IsolatedResult()>& read)
{
  const char* inProcess = std::getenv("AMRSP_READ_IN_PROCESS");
  if (inProcess && std::string(inProcess) == "1")
  {
    return read();
  }
  const int dataFd = RunInChildProcess(
    what, timeoutSeconds, "--read-timeout", memoryBytes,
    [&read](int fd) { return WriteResult(fd, read()); },
    // the progress bar stays on the terminal, not in the reader's captured output
    [] { SetProgressDescriptor(dup(2)); });
  try
  {
    IsolatedResult r = ReadResult(dataFd, what);
    close(dataFd); // the mapping stays
    return r;
  }
  catch (...)
  {
    close(dataFd);
    throw;
  }
}

} // namespace harness
} // namespace amrsp
