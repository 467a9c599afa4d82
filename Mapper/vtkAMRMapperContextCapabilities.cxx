// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperContextCapabilities.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkAMRMapperOpenGL.h"

//------------------------------------------------------------------------------
bool vtkAMRMapperContextCapabilities::IsRenderSupported(vtkRenderWindow* window, std::string* why)
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

//------------------------------------------------------------------------------
bool vtkAMRMapperContextCapabilities::Update(vtkOpenGLRenderWindow* renWin)
{
  if (this->Context == renWin)
  {
    return false;
  }
  renWin->MakeCurrent();
  this->Bindless = vtkAMRMapperOpenGL::HasExtension("GL_ARB_bindless_texture");
  this->NVShader5 = vtkAMRMapperOpenGL::HasExtension("GL_NV_gpu_shader5");
  this->Ballot = vtkAMRMapperOpenGL::HasExtension("GL_ARB_shader_ballot");
  this->ThreadBuiltins = vtkAMRMapperOpenGL::HasExtension("GL_NV_shader_thread_group");
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  this->MaxBindlessTextures = name.find("zink") != std::string::npos ? 1023 : -1;
  this->CpuDriver = name.find("llvmpipe") != std::string::npos ||
    name.find("softpipe") != std::string::npos || name.find("lavapipe") != std::string::npos;
  // compute shaders: core in OpenGL 4.3; an extension of 4.2 (which has the image stores); and
  // both extensions of an older core context that offers them (NVIDIA's EGL gives VTK a 3.2
  // context and lists every extension the GPU has there)
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const int version = 10 * major + minor;
  this->ComputeVersion.clear();
  this->NoCompute.clear();
  if (version >= 43)
  {
    this->ComputeVersion = "#version 430 core\n";
  }
  else if (version >= 42 && vtkAMRMapperOpenGL::HasExtension("GL_ARB_compute_shader"))
  {
    this->ComputeVersion = "#version 420 core\n#extension GL_ARB_compute_shader : require\n";
  }
  else if (vtkAMRMapperOpenGL::HasExtension("GL_ARB_compute_shader") &&
    vtkAMRMapperOpenGL::HasExtension("GL_ARB_shader_image_load_store"))
  {
    this->ComputeVersion = "#version 150 core\n#extension GL_ARB_compute_shader : require\n"
                           "#extension GL_ARB_shader_image_load_store : require\n";
  }
  else
  {
    this->NoCompute = "the OpenGL context (" + std::to_string(major) + "." + std::to_string(minor) +
      ") has no compute shaders (OpenGL 4.3, or GL_ARB_compute_shader with 4.2 or with "
      "GL_ARB_shader_image_load_store)";
  }
  this->Context = renWin;
  return true;
}

//------------------------------------------------------------------------------
amrsp::BindlessAccess vtkAMRMapperContextCapabilities::ResolveAccess(
  amrsp::BindlessAccess access, std::string& why) const
{
  using Access = amrsp::BindlessAccess;
  if (!this->Bindless)
  {
    why = "the OpenGL context lacks GL_ARB_bindless_texture";
    return Access::None;
  }
  if (access == Access::Direct || (access == Access::Auto && this->NVShader5))
  {
    return Access::Direct;
  }
  if (this->Ballot)
  {
    return Access::Waterfall;
  }
  why = access == Access::Waterfall
    ? "the waterfall access needs GL_ARB_shader_ballot, which the OpenGL context lacks"
    : "non-uniform bindless handles need GL_NV_gpu_shader5 or GL_ARB_shader_ballot, and the "
      "OpenGL context has neither";
  return Access::None;
}
