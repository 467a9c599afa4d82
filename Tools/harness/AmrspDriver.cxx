// SPDX-License-Identifier: BSD-3-Clause
#include "AmrspDriver.h"

#include "amrsp/TextCase.h"

#include "vtkRenderWindow.h"
#include "vtkVersion.h"

#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace amrsp
{
namespace harness
{

const char* const DriverHelp =
  "  --driver D                  default (the system's OpenGL driver) or zink (Mesa's zink on\n"
  "                              the Vulkan device; with Mesa 25 it offers bindless textures\n"
  "                              even on the CPU, through lavapipe)\n"
  "  --backend B                 the window system: auto (default), glx (an X server), egl\n"
  "                              (no X server needed) or osmesa (libOSMesa, no X server);\n"
  "                              egl and osmesa need VTK >= 9.4 (auto picks egl when DISPLAY\n"
  "                              is unset there)\n";

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
  if (mkdir(folder.c_str(), 0700) != 0 &&
    !(stat(folder.c_str(), &info) == 0 && S_ISDIR(info.st_mode)))
  {
    throw std::invalid_argument("--driver zink: cannot create the runtime folder " + folder);
  }
  setenv("XDG_RUNTIME_DIR", folder.c_str(), 1);
}

std::string AvailableBackends()
{
#if AMRSP_RUNTIME_WINDOW_CHOICE
  std::string backends;
#ifdef VTK_USE_X
  backends += "GLX, ";
#endif
#ifdef VTK_OPENGL_HAS_EGL
  backends += "EGL, ";
#endif
  return backends + "OSMesa";
#elif defined(VTK_OPENGL_HAS_OSMESA)
  return "OSMesa";
#elif defined(VTK_OPENGL_HAS_EGL)
  return "EGL";
#else
  return "GLX";
#endif
}

void SelectBackend(const std::string& name)
{
  if (name != "auto" && name != "glx" && name != "egl" && name != "osmesa")
  {
    throw std::invalid_argument("unknown --backend '" + name + "' (auto, glx, egl or osmesa)");
  }
#if AMRSP_RUNTIME_WINDOW_CHOICE
  const char* display = std::getenv("DISPLAY");
  const bool haveDisplay = display && *display;
  if (name == "auto")
  {
    const char* chosen = std::getenv("VTK_DEFAULT_OPENGL_WINDOW");
    if ((!chosen || !*chosen) && !haveDisplay)
    {
      setenv("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow", 1);
    }
    return;
  }
  if (name == "glx" && !haveDisplay)
  {
    throw std::invalid_argument("--backend glx needs an X server, and DISPLAY is not set");
  }
  if (name == "osmesa" && !dlopen("libOSMesa.so.8", RTLD_LAZY | RTLD_GLOBAL))
  {
    throw std::invalid_argument("--backend osmesa: libOSMesa.so.8 cannot be loaded (Debian 13's "
                                "libosmesa6 provides it; or set LD_LIBRARY_PATH to its folder)");
  }
  setenv("VTK_DEFAULT_OPENGL_WINDOW",
    name == "glx" ? "vtkXOpenGLRenderWindow"
                  : (name == "egl" ? "vtkEGLRenderWindow" : "vtkOSOpenGLRenderWindow"),
    1);
#else
  const std::string only = LowerAscii(AvailableBackends());
  if (name != "auto" && name != only)
  {
    throw std::invalid_argument("--backend " + name + ": VTK " + VtkVersion() +
      " chooses its window system when it is built, and this one renders through " +
      AvailableBackends() + " only (VTK >= 9.4 can choose at run time)");
  }
#endif
}

std::string BackendOf(vtkRenderWindow* window)
{
  const std::string name = window ? window->GetClassName() : "";
  if (name == "vtkXOpenGLRenderWindow")
  {
    return "GLX";
  }
  if (name == "vtkEGLRenderWindow")
  {
    return "EGL";
  }
  if (name == "vtkOSOpenGLRenderWindow")
  {
    return "OSMesa";
  }
  return name;
}

std::string VtkVersion()
{
  return vtkVersion::GetVTKVersion();
}

std::string ParaViewVersion()
{
#ifdef AMRSP_PARAVIEW_VERSION
  return AMRSP_PARAVIEW_VERSION;
#else
  return "none";
#endif
}

} // namespace harness
} // namespace amrsp
