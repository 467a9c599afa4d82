// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperScopedBlendedDraw.h"

#include "vtkAMRMapperOpenGL.h"

//------------------------------------------------------------------------------
vtkAMRMapperScopedBlendedDraw::vtkAMRMapperScopedBlendedDraw(
  vtkOpenGLState* state, unsigned int cullFace, unsigned int source, unsigned int destination)
  : State(state)
  , Culls(cullFace != GL_NONE)
  , CullSaved(state, GL_CULL_FACE)
  , DepthTestSaved(state, GL_DEPTH_TEST)
  , BlendSaved(state, GL_BLEND)
  , DepthMaskSaved(state)
  , BlendFuncSaved(state)
{
  if (this->Culls)
  {
    state->vtkglEnable(GL_CULL_FACE);
    state->vtkglCullFace(cullFace);
  }
  else
  {
    state->vtkglDisable(GL_CULL_FACE);
  }
  state->vtkglDisable(GL_DEPTH_TEST);
  state->vtkglDepthMask(GL_FALSE);
  state->vtkglEnable(GL_BLEND);
  state->vtkglBlendFuncSeparate(source, destination, source, destination);
}

//------------------------------------------------------------------------------
vtkAMRMapperScopedBlendedDraw::~vtkAMRMapperScopedBlendedDraw()
{
  if (this->Culls)
  {
    this->State->vtkglCullFace(GL_BACK);
  }
}
