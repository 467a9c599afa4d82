// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperTextures.h
 * @brief   the texture objects both AMR mappers create (private to the module)
 *
 * The integer 3D textures of the kD-tree encodings and the R32F textures of bricks and atlases,
 * all nearest or trilinear and clamped, as vtkTextureObjects. Not installed.
 */
#ifndef vtkAMRMapperTextures_h
#define vtkAMRMapperTextures_h

#include "amrsp/KdTreeEncoding.h"

#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

#include <glm/glm.hpp>

class vtkOpenGLRenderWindow;

namespace vtkAMRMapperTextures
{

/// An RG32UI 3D texture of a kD-tree encoding (nearest, clamped); null when OpenGL refused it.
/// An RGBA32UI 3D texture of `texels` (nearest filtering); null when the driver refuses it.
vtkSmartPointer<vtkTextureObject> MakeInteger4Texture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UInt4Texture3D& texels);
vtkSmartPointer<vtkTextureObject> MakeIntegerTexture(
  vtkOpenGLRenderWindow* renWin, const amrsp::UIntTexture3D& texels);

/// An R32F brick or atlas texture of `dims` texels: nearest for cell bricks, trilinear for vertex
/// bricks (the shaders never sample outside a brick), clamped; null when OpenGL refused it.
vtkSmartPointer<vtkTextureObject> MakeScalarTexture(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, const float* texels, bool vertexCentred);

} // namespace vtkAMRMapperTextures

#endif
