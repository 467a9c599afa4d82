// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperShaderComposer.h
 * @brief   a mapper's fragment shader from its template and the GLSL pieces (private)
 *
 * Both mappers compose their shaders here, so the pieces they share (the .glsl files of Shaders/)
 * and the user's vtkShaderProperty replacements apply to both alike.
 */
#ifndef vtkAMRMapperShaderComposer_h
#define vtkAMRMapperShaderComposer_h

#include <string>
#include <utility>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkVolume;

namespace vtkAMRMapperShaderComposer
{

/**
 * A fragment shader from its template `source`: `defines` replaces the line //AMRSP::Defines,
 * each (tag, code) of `pieces` replaces its line //AMRSP::<tag> (the shared .glsl pieces), and
 * the volume's vtkShaderProperty fragment replacements apply as VTK's own mappers apply them:
 * those marked "replace first" before these substitutions, the others after.
 */
std::string ComposeFragmentShader(const char* source, const std::string& defines,
  const std::vector<std::pair<std::string, const char*>>& pieces, vtkVolume* vol);

/**
 * The program of `vertex` and `fragment` from `renWin`'s shader cache (compiled once per source).
 * A fragment that failed before (`failedFragment`, updated here) is not compiled again. Null on
 * failure, with `error`: "the <name> shader failed to compile or link (see the error above)"
 * when it failed now, "(see the earlier error)" when it had failed before.
 */
vtkShaderProgram* ReadyProgram(vtkOpenGLRenderWindow* renWin, const char* vertex,
  const std::string& fragment, const char* name, std::string& failedFragment, std::string& error);

} // namespace vtkAMRMapperShaderComposer

#endif
