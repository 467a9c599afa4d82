// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRComputeProgram.h"

#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"

#include "vtkAMRMapperOpenGL.h"

#include <vector>

vtkStandardNewMacro(vtkSinglePassAMRComputeProgram);

namespace
{
/// The info log of a shader (`isProgram` false) or program object.
std::string InfoLog(GLuint object, bool isProgram)
{
  GLint length = 0;
  if (isProgram)
  {
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  }
  else
  {
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  }
  if (length <= 1)
  {
    return "no log";
  }
  std::vector<char> log(static_cast<std::size_t>(length));
  if (isProgram)
  {
    glGetProgramInfoLog(object, length, nullptr, log.data());
  }
  else
  {
    glGetShaderInfoLog(object, length, nullptr, log.data());
  }
  return std::string(log.data());
}
} // namespace

//------------------------------------------------------------------------------
bool vtkSinglePassAMRComputeProgram::Build(
  vtkOpenGLRenderWindow* renWin, const std::string& source, std::string& error)
{
  this->Free(renWin);
  const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  if (shader == 0)
  {
    error = "the OpenGL context cannot create a compute shader";
    return false;
  }
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE)
  {
    error = "compiling: " + InfoLog(shader, false);
    glDeleteShader(shader);
    return false;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDetachShader(program, shader);
  glDeleteShader(shader); // the linked program keeps its code
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE)
  {
    error = "linking: " + InfoLog(program, true);
    glDeleteProgram(program);
    return false;
  }
  this->ClearMaps();
  this->Handle = static_cast<int>(program);
  this->Linked = true;
  this->ComputeSource = source;
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRComputeProgram::Use(vtkOpenGLRenderWindow* renWin)
{
  renWin->GetShaderCache()->ReleaseCurrentShader();
  this->Bind();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRComputeProgram::Dispatch(unsigned int groupsX, unsigned int groupsY)
{
  glDispatchCompute(groupsX, groupsY, 1);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRComputeProgram::Free(vtkWindow* window)
{
  if (vtkOpenGLRenderWindow* renWin = vtkOpenGLRenderWindow::SafeDownCast(window))
  {
    renWin->GetShaderCache()->ReleaseCurrentShader();
  }
  this->ReleaseGraphicsResources(window);
  this->ComputeSource.clear();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRComputeProgram::Unuse()
{
  this->Release();
}
