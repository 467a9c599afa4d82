// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperShaderComposer.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLShaderProperty.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"
#include "vtkVolume.h"

namespace vtkAMRMapperShaderComposer
{

//------------------------------------------------------------------------------
std::string ComposeFragmentShader(const char* source, const std::string& defines,
  const std::vector<std::pair<std::string, const char*>>& pieces, vtkVolume* vol)
{
  vtkOpenGLShaderProperty* shaderProperty =
    vtkOpenGLShaderProperty::SafeDownCast(vol ? vol->GetShaderProperty() : nullptr);
  auto applyUserReplacements = [&](std::string& code, bool first)
  {
    if (!shaderProperty)
    {
      return;
    }
    for (const auto& r : shaderProperty->GetAllShaderReplacements())
    {
      if (r.first.ShaderType == vtkShader::Fragment && r.first.ReplaceFirst == first)
      {
        vtkShaderProgram::Substitute(
          code, r.first.OriginalValue, r.second.Replacement, r.second.ReplaceAll);
      }
    }
  };
  std::string fragment = source;
  applyUserReplacements(fragment, true);
  vtkShaderProgram::Substitute(fragment, "//AMRSP::Defines", defines);
  for (const auto& piece : pieces)
  {
    vtkShaderProgram::Substitute(fragment, "//AMRSP::" + piece.first, piece.second);
  }
  applyUserReplacements(fragment, false);
  return fragment;
}

//------------------------------------------------------------------------------
vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* renWin, const char* vertex,
  const std::string& fragment, const char* name, std::string& failedFragment, std::string& error)
{
  const std::string failed = std::string("the ") + name + " shader failed to compile or link";
  if (fragment == failedFragment)
  {
    error = failed + " (see the earlier error)";
    return nullptr;
  }
  vtkShaderProgram* program =
    renWin->GetShaderCache()->ReadyShaderProgram(vertex, fragment.c_str(), "");
  if (!program)
  {
    failedFragment = fragment;
    error = failed + " (see the error above)";
  }
  return program;
}

} // namespace vtkAMRMapperShaderComposer
