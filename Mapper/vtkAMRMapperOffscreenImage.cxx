// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperOffscreenImage.h"

#include "vtkOpenGLFramebufferObject.h"
#include "vtkOpenGLQuadHelper.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

#include "vtkAMRMapperOpenGL.h"
#include "vtkAMRMapperScopedBlendedDraw.h"

#include "amrsp_OffscreenComposite_frag_glsl.h"

//------------------------------------------------------------------------------
vtkAMRMapperOffscreenImage::vtkAMRMapperOffscreenImage() = default;

//------------------------------------------------------------------------------
vtkAMRMapperOffscreenImage::~vtkAMRMapperOffscreenImage() = default;

//------------------------------------------------------------------------------
bool vtkAMRMapperOffscreenImage::Ensure(
  vtkOpenGLRenderWindow* renWin, int width, int height, bool linear, std::string& error)
{
  if (this->Colour && this->Framebuffer && this->Colour->GetContext() == renWin &&
    this->Width == width && this->Height == height && this->Linear == linear)
  {
    return true;
  }
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(renWin);
  }
  this->Width = this->Height = 0;
  this->Linear = linear;
  this->Colour = vtkSmartPointer<vtkTextureObject>::New();
  this->Colour->SetContext(renWin);
  this->Colour->SetInternalFormat(GL_RGBA32F);
  this->Colour->SetFormat(GL_RGBA);
  this->Colour->SetDataType(GL_FLOAT);
  const int filter = linear ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  this->Colour->SetMinificationFilter(filter);
  this->Colour->SetMagnificationFilter(filter);
  this->Colour->SetWrapS(vtkTextureObject::ClampToEdge);
  this->Colour->SetWrapT(vtkTextureObject::ClampToEdge);
  bool ok = this->Colour->Allocate2D(
    static_cast<unsigned int>(width), static_cast<unsigned int>(height), 4, VTK_FLOAT);
  if (ok)
  {
    this->Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    this->Framebuffer->SetContext(renWin);
    this->Framebuffer->SaveCurrentBindingsAndBuffers();
    this->Framebuffer->Bind();
    this->Framebuffer->AddColorAttachment(0, this->Colour);
    this->Framebuffer->ActivateDrawBuffer(0);
    const char* description = nullptr;
    ok = vtkOpenGLFramebufferObject::GetFrameBufferStatus(GL_FRAMEBUFFER, description);
    this->Framebuffer->RestorePreviousBindingsAndBuffers();
    if (!ok)
    {
      error = std::string("the RGBA32F offscreen framebuffer is incomplete: ") +
        (description ? description : "unknown reason");
    }
  }
  else
  {
    error = "cannot allocate an RGBA32F offscreen image of " + std::to_string(width) + " x " +
      std::to_string(height) + " pixels";
  }
  if (!ok)
  {
    this->Colour = nullptr;
    this->Framebuffer = nullptr;
    return false;
  }
  this->Width = width;
  this->Height = height;
  return true;
}

//------------------------------------------------------------------------------
void vtkAMRMapperOffscreenImage::BeginDrawing(vtkOpenGLState* state)
{
  this->Framebuffer->SaveCurrentBindingsAndBuffers(GL_DRAW_FRAMEBUFFER);
  this->Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  this->Framebuffer->ActivateDrawBuffer(0);
  state->vtkglViewport(0, 0, this->Width, this->Height);
  state->vtkglDisable(GL_SCISSOR_TEST);
  state->vtkglClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  state->vtkglClear(GL_COLOR_BUFFER_BIT);
}

//------------------------------------------------------------------------------
void vtkAMRMapperOffscreenImage::EndDrawing()
{
  this->Framebuffer->RestorePreviousBindingsAndBuffers(GL_DRAW_FRAMEBUFFER);
}

//------------------------------------------------------------------------------
void vtkAMRMapperOffscreenImage::BindAsImage(int unit)
{
  glBindImageTexture(static_cast<GLuint>(unit), this->Colour->GetHandle(), 0, GL_FALSE, 0,
    GL_WRITE_ONLY, GL_RGBA32F);
}

//------------------------------------------------------------------------------
void vtkAMRMapperOffscreenImage::UnbindImage(int unit)
{
  glBindImageTexture(static_cast<GLuint>(unit), 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
}

//------------------------------------------------------------------------------
bool vtkAMRMapperOffscreenImage::CompositeOver(vtkOpenGLRenderWindow* renWin, std::string& error)
{
  if (!this->Composite)
  {
    this->Composite.reset(
      new vtkOpenGLQuadHelper(renWin, nullptr, amrsp_OffscreenComposite_frag_glsl, ""));
  }
  if (!this->Composite->Program)
  {
    this->Composite.reset();
    error = "the offscreen composite shader failed to compile or link (see the error above)";
    return false;
  }
  // premultiplied "over" the frame
  const vtkAMRMapperScopedBlendedDraw blended(
    renWin->GetState(), GL_NONE, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  renWin->GetShaderCache()->ReadyShaderProgram(this->Composite->Program);
  this->Colour->Activate();
  this->Composite->Program->SetUniformi("amrspImage", this->Colour->GetTextureUnit());
  this->Composite->Render();
  this->Colour->Deactivate();
  return true;
}

//------------------------------------------------------------------------------
void vtkAMRMapperOffscreenImage::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Colour)
  {
    this->Colour->ReleaseGraphicsResources(window);
    this->Colour = nullptr;
  }
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
    this->Framebuffer = nullptr;
  }
  if (this->Composite)
  {
    this->Composite->ReleaseGraphicsResources(window);
    this->Composite.reset();
  }
  this->Width = this->Height = 0;
}
