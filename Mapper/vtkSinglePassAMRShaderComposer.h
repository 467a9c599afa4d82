// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRShaderComposer.h
 * @brief   a mapper's fragment shader from its template and the GLSL pieces (private)
 *
 * Both mappers compose their shaders here, so the pieces they share (the .glsl files of Shaders/)
 * and the user's vtkShaderProperty replacements apply to both alike.
 */
#ifndef vtkSinglePassAMRShaderComposer_h
#define vtkSinglePassAMRShaderComposer_h

#include <string>
#include <utility>
#include <vector>

class vtkVolume;

namespace vtkSinglePassAMRShaderComposer
{

/**
 * A fragment shader from its template `source`: `defines` replaces the line //AMRSP::Defines,
 * each (tag, code) of `pieces` replaces its line //AMRSP::<tag> (the shared .glsl pieces), and
 * the volume's vtkShaderProperty fragment replacements apply as VTK's own mappers apply them:
 * those marked "replace first" before these substitutions, the others after.
 */
std::string ComposeFragmentShader(const char* source, const std::string& defines,
  const std::vector<std::pair<std::string, const char*>>& pieces, vtkVolume* vol);

} // namespace vtkSinglePassAMRShaderComposer

#endif
