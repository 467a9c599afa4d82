// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperScopedBlendedDraw.h
 * @brief   the OpenGL state of one blended draw of the proxy box (private to the module)
 *
 * Set on construction, restored on destruction.
 */
#ifndef vtkAMRMapperScopedBlendedDraw_h
#define vtkAMRMapperScopedBlendedDraw_h

#include "vtkOpenGLState.h"

/**
 * The OpenGL state of a blended draw of the volume's proxy geometry, for the lifetime of the
 * object: no depth test and no depth writes, blending on with the factors `source` and
 * `destination` for colour and alpha alike, and faces of `cullFace` (GL_FRONT or GL_BACK) culled,
 * or culling off (GL_NONE). Restores culling, depth test, blending, depth mask and blend factors
 * as they were, and the culled face to GL_BACK (VTK's default, which vtkOpenGLState does not
 * save).
 */
class vtkAMRMapperScopedBlendedDraw
{
public:
  vtkAMRMapperScopedBlendedDraw(
    vtkOpenGLState* state, unsigned int cullFace, unsigned int source, unsigned int destination);
  ~vtkAMRMapperScopedBlendedDraw();
  vtkAMRMapperScopedBlendedDraw(const vtkAMRMapperScopedBlendedDraw&) = delete;
  vtkAMRMapperScopedBlendedDraw& operator=(const vtkAMRMapperScopedBlendedDraw&) = delete;

private:
  vtkOpenGLState* State;
  bool Culls;
  vtkOpenGLState::ScopedglEnableDisable CullSaved;
  vtkOpenGLState::ScopedglEnableDisable DepthTestSaved;
  vtkOpenGLState::ScopedglEnableDisable BlendSaved;
  vtkOpenGLState::ScopedglDepthMask DepthMaskSaved;
  vtkOpenGLState::ScopedglBlendFuncSeparate BlendFuncSaved;
};

#endif
