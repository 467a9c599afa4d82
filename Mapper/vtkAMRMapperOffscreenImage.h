// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAMRMapperOffscreenImage
 * @brief   an offscreen RGBA32F image of premultiplied colour, composited over the viewport
 *
 * Private to the module. The multi-pass mapper accumulates its node draws in one of the
 * viewport's size (nearest filtering); the single-pass mapper draws an interactive frame's rays
 * into a smaller one (ImageSampleDistance > 1) that the composite magnifies bilinearly. The
 * composite is one full-screen quad (vtkOpenGLQuadHelper, Shaders/OffscreenComposite.frag.glsl)
 * blended premultiplied "over" (ONE, ONE_MINUS_SRC_ALPHA) onto the current framebuffer's
 * viewport, as the single-pass mapper blends its own rays.
 */
#ifndef vtkAMRMapperOffscreenImage_h
#define vtkAMRMapperOffscreenImage_h

#include "vtkSmartPointer.h"

#include <memory>
#include <string>

class vtkOpenGLFramebufferObject;
class vtkOpenGLQuadHelper;
class vtkOpenGLRenderWindow;
class vtkOpenGLState;
class vtkTextureObject;
class vtkWindow;

class vtkAMRMapperOffscreenImage
{
public:
  vtkAMRMapperOffscreenImage();
  ~vtkAMRMapperOffscreenImage();
  vtkAMRMapperOffscreenImage(const vtkAMRMapperOffscreenImage&) = delete;
  vtkAMRMapperOffscreenImage& operator=(const vtkAMRMapperOffscreenImage&) = delete;

  /// (Re)creates the image and its framebuffer for `width` x `height` pixels of `renWin` when
  /// missing, of another context, size or filtering (`linear`: bilinear magnification, else
  /// nearest). Returns false with `error` when the driver refuses them.
  bool Ensure(
    vtkOpenGLRenderWindow* renWin, int width, int height, bool linear, std::string& error);

  /// Binds the image for drawing (saving the draw-framebuffer binding), sets the viewport to the
  /// whole image, turns the scissor test off and clears it to transparent black. The caller
  /// keeps the viewport, scissor test and clear colour in scoped vtkOpenGLState guards.
  void BeginDrawing(vtkOpenGLState* state);
  /// Restores the draw-framebuffer binding BeginDrawing saved.
  void EndDrawing();

  /// Composites the image over the current framebuffer's viewport. Returns false with `error`
  /// when the composite shader does not compile or link.
  bool CompositeOver(vtkOpenGLRenderWindow* renWin, std::string& error);

  /// Binds the image to image unit `unit` for writes of RGBA32F texels (a compute shader's
  /// `layout(rgba32f) writeonly image2D`); UnbindImage undoes it.
  void BindAsImage(int unit);
  void UnbindImage(int unit);

  int GetWidth() const { return this->Width; }
  int GetHeight() const { return this->Height; }

  void ReleaseGraphicsResources(vtkWindow* window);

private:
  vtkSmartPointer<vtkTextureObject> Colour;
  vtkSmartPointer<vtkOpenGLFramebufferObject> Framebuffer;
  std::unique_ptr<vtkOpenGLQuadHelper> Composite;
  int Width = 0;
  int Height = 0;
  bool Linear = false;
};

#endif
