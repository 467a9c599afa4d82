// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRBindlessBricks.h"

#include "vtkSinglePassAMRShaderVariant.h"
#include "vtkAMRMapperTextures.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkAMRMapperOpenGL.h"
#include "vtkTextureUnitManager.h"

#include <algorithm>

//------------------------------------------------------------------------------
vtkSinglePassAMRBindlessBricks::~vtkSinglePassAMRBindlessBricks()
{
  this->Clear();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::Clear()
{
  if (!this->Names.empty() && this->Context)
  {
    this->Context->PushContext();
    this->Release();
    this->Context->PopContext();
  }
  // without a context the textures died with it
  this->Names.clear();
  this->Handles.clear();
  this->Extents.clear();
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRBindlessBricks::Create(vtkOpenGLRenderWindow* renWin,
  const std::vector<glm::ivec3>& extents, const std::function<const float*(std::size_t)>& texels,
  bool linear, std::string& error)
{
  this->Clear();
  this->Context = renWin;
  this->Names.assign(extents.size(), 0u);
  this->Handles.clear();
  this->Handles.reserve(extents.size());
  if (extents.empty())
  {
    return true;
  }
  glGenTextures(static_cast<GLsizei>(this->Names.size()), this->Names.data());

  // one texture unit of VTK's, so that no texture bound by VTK is replaced
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  const int unit = units->Allocate();
  renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  const GLint filter = linear ? GL_LINEAR : GL_NEAREST;
  for (std::size_t g = 0; g < extents.size() && error.empty(); ++g)
  {
    const glm::ivec3 e = extents[g];
    glBindTexture(GL_TEXTURE_3D, this->Names[g]);
    // the handle freezes this sampling state
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R32F, e.x, e.y, e.z, 0, GL_RED, GL_FLOAT, texels(g));
    const GLenum glError = glGetError();
    const GLuint64 handle = glError == GL_NO_ERROR ? glGetTextureHandleARB(this->Names[g]) : 0;
    if (handle == 0)
    {
      error = "the driver refused brick " + std::to_string(g) + " (" + std::to_string(e.x) + " x " +
        std::to_string(e.y) + " x " + std::to_string(e.z) + " texels)" +
        (glError == GL_OUT_OF_MEMORY ? ": out of GPU memory"
            : glError != GL_NO_ERROR ? " (OpenGL error " + std::to_string(glError) + ")"
                                     : ": glGetTextureHandleARB returned no handle");
      break;
    }
    this->Handles.push_back(handle);
  }
  glBindTexture(GL_TEXTURE_3D, 0);
  units->Free(unit);
  if (!error.empty())
  {
    // no handle is resident yet
    this->Handles.clear();
    this->Release();
    return false;
  }
  // resident after every texture exists: on an H100 making 280,000 handles resident took 1.4 s
  // so against 3.3 s interleaved with the texture creation
  for (const GLuint64 handle : this->Handles)
  {
    glMakeTextureHandleResidentARB(handle);
  }
  this->Extents = extents;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRBindlessBricks::Overwrite(vtkOpenGLRenderWindow* renWin,
  const std::vector<glm::ivec3>& extents, const std::function<const float*(std::size_t)>& texels)
{
  if (this->Context != renWin || this->Names.empty() || this->Extents != extents)
  {
    return false;
  }
  vtkTextureUnitManager* units = renWin->GetTextureUnitManager();
  const int unit = units->Allocate();
  renWin->GetState()->vtkglActiveTexture(GL_TEXTURE0 + unit);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (std::size_t g = 0; g < extents.size(); ++g)
  {
    const glm::ivec3 e = extents[g];
    glBindTexture(GL_TEXTURE_3D, this->Names[g]);
    glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, e.x, e.y, e.z, GL_RED, GL_FLOAT, texels(g));
  }
  glBindTexture(GL_TEXTURE_3D, 0);
  units->Free(unit);
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRBindlessBricks::Upload(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error, const std::function<void(double)>&)
{
  this->HandlesTexture = nullptr;
  this->Bytes = 0;
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  const std::vector<glm::ivec3> extents = amrsp::BrickExtents(data.Data, data.VertexCentred);
  for (std::size_t g = 0; g < extents.size(); ++g)
  {
    const glm::ivec3 e = extents[g];
    if (e.x > max3D || e.y > max3D || e.z > max3D)
    {
      error = "grid " + std::to_string(g) + " (" + std::to_string(e.x) + " x " +
        std::to_string(e.y) + " x " + std::to_string(e.z) +
        " texels) exceeds GL_MAX_3D_TEXTURE_SIZE = " + std::to_string(max3D);
      return false;
    }
  }
  if (!this->Create(
        renWin, extents, [&data](std::size_t g) { return data.Data.Values[g].data(); },
        data.VertexCentred, error))
  {
    return false;
  }
  amrsp::UIntTexture3D handles;
  handles.Dims = amrsp::TextureDimsFor(extents.size());
  handles.Texels.assign(
    static_cast<std::size_t>(handles.Dims.x) * handles.Dims.y * handles.Dims.z, glm::uvec2(0u));
  for (std::size_t g = 0; g < this->Handles.size(); ++g)
  {
    handles.Texels[g] = glm::uvec2(static_cast<uint32_t>(this->Handles[g] & 0xffffffffu),
      static_cast<uint32_t>(this->Handles[g] >> 32));
  }
  this->HandlesTexture = vtkAMRMapperTextures::MakeIntegerTexture(renWin, handles);
  if (!this->HandlesTexture)
  {
    return false;
  }
  this->Bytes = data.BindlessBytes - data.TreeBytes;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRBindlessBricks::UploadValues(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  // the same bricks: new texels into the resident textures, the handle table unchanged
  if (this->HandlesTexture &&
    this->Overwrite(renWin, amrsp::BrickExtents(data.Data, data.VertexCentred),
      [&data](std::size_t g) { return data.Data.Values[g].data(); }))
  {
    return true;
  }
  this->ReleaseGraphicsResources(renWin);
  return this->Upload(renWin, data, error, progress);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::Describe(vtkSinglePassAMRShaderVariant& variant) const
{
  variant.Storage = amrsp::DataStorage::BindlessTextures;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::Activate(vtkShaderProgram* program)
{
  this->HandlesTexture->Activate();
  program->SetUniformi("amrspHandles", this->HandlesTexture->GetTextureUnit());
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::Deactivate()
{
  this->HandlesTexture->Deactivate();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::ReleaseGraphicsResources(vtkWindow* window)
{
  if (!this->Context || window == this->Context.GetPointer())
  {
    this->Clear();
  }
  if (this->HandlesTexture)
  {
    this->HandlesTexture->ReleaseGraphicsResources(window);
    this->HandlesTexture = nullptr;
  }
  this->Bytes = 0;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRBindlessBricks::Release()
{
  this->LargestReleased =
    std::max(this->LargestReleased, static_cast<long long>(this->Names.size()));
  for (const std::uint64_t handle : this->Handles)
  {
    glMakeTextureHandleNonResidentARB(handle);
  }
  if (!this->Names.empty())
  {
    glDeleteTextures(static_cast<GLsizei>(this->Names.size()), this->Names.data());
  }
  this->Names.clear();
  this->Handles.clear();
  this->Extents.clear();
}
