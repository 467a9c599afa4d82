// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRRenderSupport.h
 * @brief   whether a render window can run the AMR mappers (private to the module)
 *
 * The one capability probe behind vtkAMRKdTreeVolumeMapper::IsRenderSupported.
 */
#ifndef vtkSinglePassAMRRenderSupport_h
#define vtkSinglePassAMRRenderSupport_h

#include <string>

class vtkRenderWindow;

namespace vtkSinglePassAMRRenderSupport
{

/// Whether `window` offers an OpenGL 3.2 core context (integer and float textures, GLSL 1.50,
/// float colour attachments, depth clamping). When it does not, `why` says what is missing.
bool IsRenderSupported(vtkRenderWindow* window, std::string* why);

} // namespace vtkSinglePassAMRRenderSupport

#endif
