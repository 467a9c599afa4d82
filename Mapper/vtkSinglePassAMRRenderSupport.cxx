// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRRenderSupport.h"

#include "vtkOpenGLRenderWindow.h"

#include <string>

namespace vtkSinglePassAMRRenderSupport
{

//------------------------------------------------------------------------------
bool IsRenderSupported(vtkRenderWindow* window, std::string* why)
{
  vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window);
  auto fail = [why](const std::string& reason)
  {
    if (why)
    {
      *why = reason;
    }
    return false;
  };
  if (!renWin)
  {
    return fail("the render window is not an OpenGL render window");
  }
  if (!renWin->SupportsOpenGL())
  {
    return fail("the OpenGL context cannot be created or is older than VTK's minimum (3.2 core)");
  }
  renWin->Initialize(); // creates the context if the window has none yet
  renWin->MakeCurrent();
  int major = 0, minor = 0;
  renWin->GetOpenGLVersion(major, minor);
  if (major < 3 || (major == 3 && minor < 2))
  {
    return fail("OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
      " lacks GLSL 1.50 integer textures (3.2 core needed)");
  }
  return true;
}

} // namespace vtkSinglePassAMRRenderSupport
