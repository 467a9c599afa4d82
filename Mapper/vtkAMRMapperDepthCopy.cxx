// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperDepthCopy.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkAMRMapperOpenGL.h"

//------------------------------------------------------------------------------
namespace
{
/// The vtkTextureObject depth format of the bound read framebuffer's depth buffer. A depth blit
/// needs the same format on both sides; a multisampled framebuffer (vtkRenderWindow's default of
/// 8 samples) often has a 24-bit one where a single-sampled one has 32-bit floats.
int ReadFramebufferDepthFormat()
{
  GLint type = GL_NONE, bits = 0;
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
  glGetFramebufferAttachmentParameteriv(
    GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &bits);
  while (glGetError() != GL_NO_ERROR)
  {
    // the default framebuffer names its depth differently: keep the float format
    type = GL_FLOAT;
  }
  if (type == GL_FLOAT)
  {
    return vtkTextureObject::Float32;
  }
  return bits <= 16 ? vtkTextureObject::Fixed16
                    : (bits <= 24 ? vtkTextureObject::Fixed24 : vtkTextureObject::Fixed32);
}
} // namespace

void vtkAMRMapperDepthCopy::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Framebuffer)
  {
    this->Framebuffer->ReleaseGraphicsResources(window);
  }
  for (vtkTextureObject* t : { this->Depth.Get(), this->Colour.Get() })
  {
    if (t)
    {
      t->ReleaseGraphicsResources(window);
    }
  }
  *this = vtkAMRMapperDepthCopy();
}

void vtkAMRMapperDepthCopy::CopyFrom(
  vtkOpenGLRenderWindow* renWin, const vtkAMRMapperViewGeometry::ViewGeometry& view)
{
  vtkAMRMapperDepthCopy& copy = *this;
  const int format = ReadFramebufferDepthFormat();
  const unsigned int width = static_cast<unsigned int>(view.Width);
  const unsigned int height = static_cast<unsigned int>(view.Height);
  vtkOpenGLState* state = renWin->GetState();
  if (!copy.Depth || copy.Depth->GetContext() != renWin || copy.Depth->GetWidth() != width ||
    copy.Depth->GetHeight() != height || copy.Format != format)
  {
    copy.Format = format;
    copy.Depth = vtkSmartPointer<vtkTextureObject>::New();
    copy.Depth->SetContext(renWin);
    copy.Depth->SetMinificationFilter(vtkTextureObject::Nearest);
    copy.Depth->SetMagnificationFilter(vtkTextureObject::Nearest);
    copy.Depth->SetWrapS(vtkTextureObject::ClampToEdge);
    copy.Depth->SetWrapT(vtkTextureObject::ClampToEdge);
    copy.Depth->AllocateDepth(width, height, format);
    copy.Colour = vtkSmartPointer<vtkTextureObject>::New();
    copy.Colour->SetContext(renWin);
    copy.Colour->Allocate2D(width, height, 4, VTK_UNSIGNED_CHAR);
    copy.Framebuffer = vtkSmartPointer<vtkOpenGLFramebufferObject>::New();
    copy.Framebuffer->SetContext(renWin);
    state->PushDrawFramebufferBinding();
    copy.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
    copy.Framebuffer->AddDepthAttachment(copy.Depth);
    copy.Framebuffer->AddColorAttachment(0U, copy.Colour);
    state->PopDrawFramebufferBinding();
  }
  state->PushDrawFramebufferBinding();
  copy.Framebuffer->Bind(GL_DRAW_FRAMEBUFFER);
  state->vtkglBlitFramebuffer(view.X0, view.Y0, view.X0 + view.Width, view.Y0 + view.Height, 0, 0,
    view.Width, view.Height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  state->PopDrawFramebufferBinding();
  copy.Depth->Activate();
}
