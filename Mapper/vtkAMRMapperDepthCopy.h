// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperDepthCopy.h
 * @brief   the opaque geometry's depth, copied for the ray caster (private to the module)
 *
 * Rays stop at the opaque geometry VTK drew before the volume: both mappers read its depth from
 * this copy.
 */
#ifndef vtkAMRMapperDepthCopy_h
#define vtkAMRMapperDepthCopy_h

#include "vtkAMRMapperViewGeometry.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

class vtkOpenGLRenderWindow;
class vtkWindow;

/// The depth of the opaque geometry drawn so far, copied for the ray caster: a depth texture of
/// the viewport's size and of the framebuffer's depth format (a depth blit needs the same format
/// on both sides), and the framebuffer object the blit writes into (multisampled windows, VTK's
/// default, can be read only by a blit, which resolves them).
struct vtkAMRMapperDepthCopy
{
  vtkSmartPointer<vtkTextureObject> Depth;
  vtkSmartPointer<vtkTextureObject> Colour; // completes the framebuffer object; never read
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  int Format = -1; // vtkTextureObject's depth format enum

  /// Copies the depth buffer of `view`'s viewport into Depth, (re)creating the textures when
  /// missing, of another context or size, or of another depth format. Leaves Depth active.
  void CopyFrom(vtkOpenGLRenderWindow* renWin, const vtkAMRMapperViewGeometry::ViewGeometry& view);
  void ReleaseGraphicsResources(vtkWindow* window);
};

#endif
