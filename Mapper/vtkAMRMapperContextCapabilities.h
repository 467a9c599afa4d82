// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAMRMapperContextCapabilities
 * @brief   what an OpenGL context offers the AMR mappers, queried once per context
 *
 * Private to the module: the one place that asks a context what it can do. IsRenderSupported
 * answers whether a window can run the mappers at all (vtkAMRKdTreeVolumeMapper::
 * IsRenderSupported); Update reads, once per context, the extensions and limits the single pass
 * decides on (bindless textures and their access modes, compute shaders, the occupancy probe's
 * builtins, a CPU driver, Mesa's zink handle limit), which vtkSinglePassAMRGridStorage hands to
 * vtkSinglePassAMRStorageChoice and vtkSinglePassAMRChooseRayCaster.
 */
#ifndef vtkAMRMapperContextCapabilities_h
#define vtkAMRMapperContextCapabilities_h

#include "amrsp/DataStorage.h"

#include <string>

class vtkOpenGLRenderWindow;
class vtkRenderWindow;

struct vtkAMRMapperContextCapabilities
{
  /// Whether `window` offers an OpenGL 3.2 core context (integer and float textures, GLSL 1.50,
  /// float colour attachments, depth clamping); creates its context when it has none. When it
  /// does not, `why` says what is missing.
  static bool IsRenderSupported(vtkRenderWindow* window, std::string* why);

  /// Reads the facts of `renWin` (made current) unless they are already its; returns true when
  /// it read them now (a new context).
  bool Update(vtkOpenGLRenderWindow* renWin);

  /// The bindless access `access` resolves to here (Auto: direct with GL_NV_gpu_shader5, else
  /// waterfall), or None with `why`.
  amrsp::BindlessAccess ResolveAccess(amrsp::BindlessAccess access, std::string& why) const;

  vtkOpenGLRenderWindow* Context = nullptr; ///< whose facts these are; null before Update
  bool Bindless = false;                    ///< GL_ARB_bindless_texture
  bool NVShader5 = false;                   ///< GL_NV_gpu_shader5: non-uniform handles
  bool Ballot = false;                      ///< GL_ARB_shader_ballot: the waterfall access
  bool ThreadBuiltins = false;              ///< GL_NV_shader_thread_group: the probe
  /// A driver that renders on the CPU and keeps its textures linear in host memory (Mesa's
  /// llvmpipe, softpipe, lavapipe under zink).
  bool CpuDriver = false;
  /// Bindless textures the driver can hold (-1: no known limit). Mesa's zink crashes when more
  /// than 1023 handles are made resident (its bindless descriptor array has 1024 slots); checked
  /// with Mesa 25.0.7: 1023 grids render, 1024 crash inside glMakeTextureHandleResidentARB.
  long long MaxBindlessTextures = -1;
  std::string ComputeVersion; ///< the compute shader's #version lines; empty: no compute shaders
  std::string NoCompute;      ///< why not
};

#endif
