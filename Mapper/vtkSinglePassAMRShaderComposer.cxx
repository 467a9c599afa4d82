// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRShaderComposer.h"

#include "vtkOpenGLShaderProperty.h"
#include "vtkShader.h"
#include "vtkShaderProgram.h"
#include "vtkVolume.h"

namespace vtkSinglePassAMRShaderComposer
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

} // namespace vtkSinglePassAMRShaderComposer
