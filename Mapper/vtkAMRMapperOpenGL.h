// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkAMRMapperOpenGL.h
 * @brief The one place where the mappers see which OpenGL loader their VTK has.
 *
 * VTK up to 9.3 loads OpenGL through GLEW (modules VTK::glew and VTK::opengl, `vtk_glew.h`);
 * VTK 9.4 and later through glad (module VTK::glad, `vtk_glad.h`), which has no
 * `glewIsSupported`. Mapper/vtk.module names all three as OPTIONAL_DEPENDS, so the VTK module
 * system defines `VTK_MODULE_ENABLE_VTK_glad` to 1 exactly when the VTK being built against has
 * glad. Both loaders declare the same core and ARB entry points (bindless textures included),
 * so everything else in the mappers is written once.
 */
#ifndef vtkAMRMapperOpenGL_h
#define vtkAMRMapperOpenGL_h

#if defined(VTK_MODULE_ENABLE_VTK_glad) && VTK_MODULE_ENABLE_VTK_glad
#include "vtk_glad.h"
#else
#include "vtk_glew.h"
#endif

#include <cstring>

namespace vtkAMRMapperOpenGL
{
/// Whether the current OpenGL (3.0+) context lists the extension `name` (e.g.
/// "GL_ARB_bindless_texture"). Reads GL_EXTENSIONS one by one, which both loaders provide.
inline bool HasExtension(const char* name)
{
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i)
  {
    const char* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
    if (extension && std::strcmp(extension, name) == 0)
    {
      return true;
    }
  }
  return false;
}
} // namespace vtkAMRMapperOpenGL

#endif
