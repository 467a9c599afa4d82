// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperTextures.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkAMRMapperOpenGL.h"

namespace vtkAMRMapperTextures
{

//------------------------------------------------------------------------------
namespace
{
/// A 3D texture of unsigned integers with 2 (RG32UI) or 4 (RGBA32UI) components, nearest
/// filtering; null when the driver refuses it.
vtkSmartPointer<vtkTextureObject> MakeUIntTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int components, const void* texels)
{
  auto tex = vtkSmartPointer<vtkTextureObject>::New();
  tex->SetContext(renWin);
  tex->SetInternalFormat(components == 4 ? GL_RGBA32UI : GL_RG32UI);
  tex->SetFormat(components == 4 ? GL_RGBA_INTEGER : GL_RG_INTEGER);
  tex->SetDataType(GL_UNSIGNED_INT);
  tex->SetMinificationFilter(vtkTextureObject::Nearest);
  tex->SetMagnificationFilter(vtkTextureObject::Nearest);
  tex->SetWrapS(vtkTextureObject::ClampToEdge);
  tex->SetWrapT(vtkTextureObject::ClampToEdge);
  tex->SetWrapR(vtkTextureObject::ClampToEdge);
  const bool ok =
    tex->Create3DFromRaw(static_cast<unsigned int>(dims.x), static_cast<unsigned int>(dims.y),
      static_cast<unsigned int>(dims.z), components, VTK_UNSIGNED_INT, const_cast<void*>(texels));
  return ok ? tex : nullptr;
}
} // namespace

vtkSmartPointer<vtkTextureObject> MakeIntegerTexture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UIntTexture3D& texels)
{
  return MakeUIntTexture(renWin, texels.Dims, 2, texels.Texels.data());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> MakeInteger4Texture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UInt4Texture3D& texels)
{
  return MakeUIntTexture(renWin, texels.Dims, 4, texels.Texels.data());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> MakeScalarTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, const float* texels, bool vertexCentred)
{
  auto tex = vtkSmartPointer<vtkTextureObject>::New();
  tex->SetContext(renWin);
  tex->SetInternalFormat(GL_R32F);
  tex->SetFormat(GL_RED);
  tex->SetDataType(GL_FLOAT);
  const int filter = vertexCentred ? vtkTextureObject::Linear : vtkTextureObject::Nearest;
  tex->SetMinificationFilter(filter);
  tex->SetMagnificationFilter(filter);
  tex->SetWrapS(vtkTextureObject::ClampToEdge);
  tex->SetWrapT(vtkTextureObject::ClampToEdge);
  tex->SetWrapR(vtkTextureObject::ClampToEdge);
  const bool ok =
    tex->Create3DFromRaw(static_cast<unsigned int>(dims.x), static_cast<unsigned int>(dims.y),
      static_cast<unsigned int>(dims.z), 1, VTK_FLOAT, const_cast<float*>(texels));
  return ok ? tex : nullptr;
}

} // namespace vtkAMRMapperTextures
