// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspProcessResources.h"

#include <dirent.h>

#include <fstream>
#include <string>

namespace amrsp
{
namespace harness
{

namespace
{
/// A "Field:   1234 kB" line of /proc/self/status in bytes; -1 where unknown.
long long StatusBytes(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
  {
    if (line.rfind(field + ":", 0) == 0)
    {
      return 1024LL * std::stoll(line.substr(field.size() + 1));
    }
  }
  return -1;
}
} // namespace

long long ResidentBytes()
{
  return StatusBytes("VmRSS");
}

long long PeakResidentBytes()
{
  return StatusBytes("VmHWM");
}

int OpenDescriptors()
{
  DIR* fds = opendir("/proc/self/fd");
  if (!fds)
  {
    return -1;
  }
  int count = 0;
  while (const dirent* entry = readdir(fds))
  {
    count += entry->d_name[0] != '.';
  }
  closedir(fds);
  return count - 1; // the listing's own descriptor
}

} // namespace harness
} // namespace amrsp
