// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `--driver` and `--backend`: which Mesa driver and which window system the tool's OpenGL
/// contexts use, and where a frame was rendered. Both selections must be applied before the first
/// context is created (Mesa reads its environment when it loads the driver; VTK >= 9.4 reads
/// VTK_DEFAULT_OPENGL_WINDOW when it creates a render window).

#include "vtkRenderingOpenGLConfigure.h"
#include "vtkVersionMacros.h"

#include <string>

class vtkRenderWindow;

/// 1 when this VTK chooses its window class at run time (VTK 9.4 and later: GLX where built with
/// X, EGL where built with it, OSMesa through a libOSMesa loaded at run time).
#define AMRSP_RUNTIME_WINDOW_CHOICE                                                                \
  (VTK_MAJOR_VERSION > 9 || (VTK_MAJOR_VERSION == 9 && VTK_MINOR_VERSION >= 4))

/// 1 when this VTK renders through GLX only (its windows abort the process when no X display
/// answers, so the tool probes the display first).
#if !AMRSP_RUNTIME_WINDOW_CHOICE && defined(VTK_USE_X) && !defined(VTK_OPENGL_HAS_EGL) &&          \
  !defined(VTK_OPENGL_HAS_OSMESA)
#define AMRSP_GLX_ONLY 1
#else
#define AMRSP_GLX_ONLY 0
#endif

namespace amrsp
{
namespace harness
{

/// "default" leaves the environment as it is (the system's driver: llvmpipe under Xvfb here, the
/// GPU's driver on a GPU machine). "zink" selects Mesa's zink on the Vulkan device (lavapipe on a
/// CPU-only machine), which offers GL_ARB_bindless_texture and GL_ARB_shader_ballot with Mesa 25:
/// it sets MESA_LOADER_DRIVER_OVERRIDE=zink and LIBGL_ALWAYS_SOFTWARE=1 (zink refuses a CPU
/// Vulkan device without it), and XDG_RUNTIME_DIR to a private folder when none exists.
/// @throws std::invalid_argument for another name or when the runtime folder cannot be made.
void SelectDriver(const std::string& name);

/// "auto", "glx", "egl" or "osmesa". VTK >= 9.4 chooses its window class at run time: the named
/// backend sets VTK_DEFAULT_OPENGL_WINDOW (vtkXOpenGLRenderWindow, vtkEGLRenderWindow,
/// vtkOSOpenGLRenderWindow); "auto" keeps a VTK_DEFAULT_OPENGL_WINDOW the user set, and
/// otherwise picks EGL when DISPLAY is unset or empty (VTK would first try X and print "bad X
/// server connection" on stderr). Older VTKs have the one backend they were built with; naming
/// another is an error. "osmesa" checks that libOSMesa.so.8 can be loaded (VTK would fall back to
/// an OpenGL 2 context that cannot run the mappers).
/// @throws std::invalid_argument with one line saying why the backend cannot be used.
void SelectBackend(const std::string& name);

/// "GLX", "EGL" or "OSMesa": the window system of a render window (its class), or the class name
/// for any other.
std::string BackendOf(vtkRenderWindow* window);

/// The backends this VTK build can render through ("GLX", or "GLX, EGL, OSMesa" for VTK >= 9.4).
std::string AvailableBackends();

/// "9.6.2": the VTK the tool runs with.
std::string VtkVersion();
/// "6.1.1": the ParaView whose VTK the tool was built against, or "none" (plain VTK).
std::string ParaViewVersion();

/// The options' help lines.
extern const char* const DriverHelp;

} // namespace harness
} // namespace amrsp
