// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspProcessResources.h"

#include <dirent.h>

#include <fstream>
#include <string>

namespace amrsp
{
namespace harness
{

long long ResidentBytes()
{
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
  {
    if (line.rfind("VmRSS:", 0) == 0)
    {
      return 1024LL * std::stoll(line.substr(6)); // "VmRSS:   1234 kB"
    }
  }
  return -1;
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
