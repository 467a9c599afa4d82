// SPDX-License-Identifier: BSD-3-Clause
// What every format's file checks share (AmrspFileCheckTools.h) and the HDF5 check; each format's
// own checks are in AmrspEnzoFileChecks.cxx, AmrspAMReXFileChecks.cxx, AmrspVTKXMLFileChecks.cxx.
#include "AmrspFileChecks.h"
#include "AmrspFileCheckTools.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace amrsp
{
namespace harness
{
namespace filechecks
{
namespace fs = std::filesystem;

std::string ReadWhole(const std::filesystem::path& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Bytes(unsigned long long n)
{
  std::string digits = std::to_string(n);
  for (int i = static_cast<int>(digits.size()) - 3; i > 0; i -= 3)
  {
    digits.insert(static_cast<std::size_t>(i), ",");
  }
  return digits + (n == 1 ? " byte" : " bytes");
}

unsigned long long FileSize(const std::filesystem::path& path)
{
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  return ec ? 0 : static_cast<unsigned long long>(size);
}

/// Little-endian unsigned integer of `n` bytes at `p`.
unsigned long long LittleEndian(const unsigned char* p, int n)
{
  unsigned long long v = 0;
  for (int i = n - 1; i >= 0; --i)
  {
    v = (v << 8) | p[i];
  }
  return v;
}

std::string Trim(const std::string& s)
{
  const std::size_t a = s.find_first_not_of(" \t\r");
  const std::size_t b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}
} // namespace filechecks

using namespace filechecks;

bool CheckHDF5File(const std::string& path, std::string& why)
{
  static const unsigned char signature[8] = { 0x89, 'H', 'D', 'F', '\r', '\n', 0x1a, '\n' };
  const unsigned long long size = FileSize(path);
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    why = "cannot be opened";
    return false;
  }
  // the superblock sits at 0 or after a user block of 512, 1024, 2048, ... bytes
  for (unsigned long long at = 0; at + 8 <= size; at = at == 0 ? 512 : 2 * at)
  {
    unsigned char head[64] = {};
    in.clear();
    in.seekg(static_cast<std::streamoff>(at));
    in.read(reinterpret_cast<char*>(head), sizeof(head));
    const std::streamsize got = in.gcount();
    if (got < 8 || !std::equal(signature, signature + 8, head))
    {
      continue;
    }
    const int version = head[8];
    int offsets = 0, eofAt = 0;
    if (version == 0 || version == 1)
    {
      offsets = head[13];
      eofAt = (version == 0 ? 24 : 28) + 2 * offsets;
    }
    else if (version == 2 || version == 3)
    {
      offsets = head[9];
      eofAt = 12 + 2 * offsets;
    }
    else
    {
      why = "has an HDF5 superblock of unknown version " + std::to_string(version);
      return false;
    }
    if ((offsets != 4 && offsets != 8) || eofAt + offsets > got)
    {
      why = "has a damaged HDF5 superblock (address size " + std::to_string(offsets) + ")";
      return false;
    }
    const int baseAt = version <= 1 ? eofAt - 2 * offsets : 12;
    const unsigned long long base = LittleEndian(head + baseAt, offsets);
    const unsigned long long end = base + LittleEndian(head + eofAt, offsets);
    if (end > size)
    {
      why = "is truncated: it has " + Bytes(size) + ", its HDF5 superblock says " + Bytes(end);
      return false;
    }
    return true;
  }
  why = "is not an HDF5 file (no HDF5 signature: its first bytes are damaged or it is "
        "another kind of file)";
  return false;
}
} // namespace harness
} // namespace amrsp
