// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspDriver.h"

#include <cstdlib>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace amrsp
{
namespace tool
{

const char* const DriverHelp =
  "  --driver D                  default (the system's OpenGL driver) or zink (Mesa's zink on\n"
  "                              the Vulkan device; with Mesa 25 it offers bindless textures\n"
  "                              even on the CPU, through lavapipe)\n";

void SelectDriver(const std::string& name)
{
  if (name == "default")
  {
    return;
  }
  if (name != "zink")
  {
    throw std::invalid_argument("unknown --driver '" + name + "' (default or zink)");
  }
  setenv("MESA_LOADER_DRIVER_OVERRIDE", "zink", 1);
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 1);
  const char* runtime = std::getenv("XDG_RUNTIME_DIR");
  struct stat info;
  if (runtime && stat(runtime, &info) == 0 && S_ISDIR(info.st_mode))
  {
    return;
  }
  const std::string folder = "/tmp/amrsp-runtime-" + std::to_string(getuid());
  if (mkdir(folder.c_str(), 0700) != 0 && !(stat(folder.c_str(), &info) == 0 && S_ISDIR(info.st_mode)))
  {
    throw std::invalid_argument("--driver zink: cannot create the runtime folder " + folder);
  }
  setenv("XDG_RUNTIME_DIR", folder.c_str(), 1);
}

} // namespace tool
} // namespace amrsp
