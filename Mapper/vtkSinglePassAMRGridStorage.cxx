// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRGridStorage.h"

#include "vtkSinglePassAMRBindlessBricks.h"
#include "vtkSinglePassAMRPackedAtlas.h"
#include "vtkSinglePassAMRTextures.h"

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkSinglePassAMROpenGL.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace
{
/// One line on a failed upload of `what` textures of `bytes` bytes, `glError` the OpenGL error
/// after it (GL_NO_ERROR: the driver refused an allocation without one).
std::string UploadFailure(const std::string& what, long long bytes, GLenum glError)
{
  std::ostringstream msg;
  msg << "uploading " << what << " textures (" << bytes / (1024.0 * 1024.0) << " MiB) failed"
      << (glError == GL_OUT_OF_MEMORY ? ": out of GPU memory" : "")
      << (glError == GL_NO_ERROR ? ": the driver refused a texture allocation (out of GPU "
                                   "memory, or over one of its limits)"
                                 : "")
      << (glError != GL_NO_ERROR ? " (OpenGL error " + std::to_string(glError) + ")" : "");
  return msg.str();
}
} // namespace

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::QueryCapabilities(vtkOpenGLRenderWindow* renWin)
{
  if (this->CapsContext == renWin)
  {
    return;
  }
  renWin->MakeCurrent();
  this->HasBindless = vtkSinglePassAMROpenGL::HasExtension("GL_ARB_bindless_texture");
  this->HasNVShader5 = vtkSinglePassAMROpenGL::HasExtension("GL_NV_gpu_shader5");
  this->HasBallot = vtkSinglePassAMROpenGL::HasExtension("GL_ARB_shader_ballot");
  this->ThreadBuiltins = vtkSinglePassAMROpenGL::HasExtension("GL_NV_shader_thread_builtins");
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  const std::string name = renderer ? renderer : "";
  this->MaxBindlessTextures = name.find("zink") != std::string::npos ? 1023 : -1;
  this->ReleasedBindlessTextures = 0;
  this->CpuDriver = name.find("llvmpipe") != std::string::npos ||
    name.find("softpipe") != std::string::npos || name.find("lavapipe") != std::string::npos;
  // compute shaders: core in OpenGL 4.3, an extension of 4.2 (which has the image stores)
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  const int version = 10 * major + minor;
  this->ComputeVersion.clear();
  this->NoCompute.clear();
  if (version >= 43)
  {
    this->ComputeVersion = "#version 430 core\n";
  }
  else if (version >= 42 && vtkSinglePassAMROpenGL::HasExtension("GL_ARB_compute_shader"))
  {
    this->ComputeVersion = "#version 420 core\n#extension GL_ARB_compute_shader : require\n";
  }
  else
  {
    this->NoCompute = "the OpenGL context (" + std::to_string(major) + "." + std::to_string(minor) +
      ") has no compute shaders (OpenGL 4.3, or 4.2 with " + "GL_ARB_compute_shader)";
  }
  this->CapsContext = renWin;
}

//------------------------------------------------------------------------------
vtkSinglePassAMRRayCasterFacts vtkSinglePassAMRGridStorage::RayCasterFacts(
  vtkOpenGLRenderWindow* renWin)
{
  this->QueryCapabilities(renWin);
  vtkSinglePassAMRRayCasterFacts facts;
  facts.Compute = !this->ComputeVersion.empty();
  facts.NoCompute = this->NoCompute;
  facts.CpuDriver = this->CpuDriver;
  return facts;
}

//------------------------------------------------------------------------------
amrsp::BindlessAccess vtkSinglePassAMRGridStorage::ResolveAccess(
  vtkOpenGLRenderWindow* renWin, amrsp::BindlessAccess access, std::string& why)
{
  using Access = amrsp::BindlessAccess;
  this->QueryCapabilities(renWin);
  if (!this->HasBindless)
  {
    why = "the OpenGL context lacks GL_ARB_bindless_texture";
    return Access::None;
  }
  if (access == Access::Direct || (access == Access::Auto && this->HasNVShader5))
  {
    return Access::Direct;
  }
  if (this->HasBallot)
  {
    return Access::Waterfall;
  }
  why = access == Access::Waterfall
    ? "the waterfall access needs GL_ARB_shader_ballot, which the OpenGL context lacks"
    : "non-uniform bindless handles need GL_NV_gpu_shader5 or GL_ARB_shader_ballot, and the "
      "OpenGL context has neither";
  return Access::None;
}

//------------------------------------------------------------------------------
vtkSinglePassAMRStorageChoice vtkSinglePassAMRGridStorage::Choose(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, const vtkSinglePassAMRStorageRequest& request, int atlasLimit)
{
  vtkSinglePassAMRStorageFacts facts;
  facts.Bindless = this->ResolveAccess(renWin, request.Access, facts.NoBindless);
  if (facts.Bindless != amrsp::BindlessAccess::None && this->MaxBindlessTextures >= 0 &&
    data.Grids > this->MaxBindlessTextures)
  {
    facts.NoBindless = "this driver (Mesa's zink) holds at most " +
      std::to_string(this->MaxBindlessTextures) + " bindless textures and the hierarchy has " +
      std::to_string(data.Grids) + " grids";
    facts.Bindless = amrsp::BindlessAccess::None;
  }
  else if (facts.Bindless != amrsp::BindlessAccess::None && this->MaxBindlessTextures >= 0 &&
    !(this->UploadedStorage == amrsp::DataStorage::BindlessTextures && this->Context == renWin &&
      !request.NewTextures))
  {
    // the set in use is released before the new one is made, but its slots come back later
    const long long earlier = std::max(this->ReleasedBindlessTextures,
      this->Context == renWin ? static_cast<long long>(this->Bricks.GetHandles().size()) : 0LL);
    if (data.Grids + earlier > this->MaxBindlessTextures)
    {
      facts.NoBindless = "this driver (Mesa's zink) holds at most " +
        std::to_string(this->MaxBindlessTextures) +
        " bindless textures and frees those of an earlier set only later: " +
        std::to_string(data.Grids) + " grids now and " + std::to_string(earlier) +
        " of an earlier set in this context";
      facts.Bindless = amrsp::BindlessAccess::None;
    }
  }
  facts.NoAtlas = data.PackingError;
  facts.AtlasFits = facts.NoAtlas.empty();
  for (const glm::ivec3& dims : data.PageDims)
  {
    facts.AtlasFits = facts.AtlasFits &&
      vtkSinglePassAMRPackedAtlas::AtlasFitsContext(renWin, dims, atlasLimit, facts.NoAtlas);
  }
  facts.AtlasWaste = data.AtlasWaste;
  facts.BrickBytes = data.BrickBytes;
  facts.CpuDriver = this->CpuDriver;
  facts.LinearFits = [this, renWin, &data]
  {
    return vtkSinglePassAMRLinearBricks::Fits(
      renWin, data.Data, data.VertexCentred, this->LinearPageBytes);
  };
  return vtkSinglePassAMRStorageChoice::Choose(request, facts);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::IsUploaded(
  vtkOpenGLRenderWindow* renWin, amrsp::DataStorage storage, int atlasLimit) const
{
  return this->UploadedStorage == storage && this->Context == renWin &&
    this->UploadLimit == atlasLimit;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::DescribeGridData(vtkSinglePassAMRShaderVariant& variant) const
{
  if (this->UploadedStorage == amrsp::DataStorage::BindlessTextures)
  {
    variant.Storage = amrsp::DataStorage::BindlessTextures;
  }
  else if (this->UploadedStorage == amrsp::DataStorage::LinearBricks)
  {
    variant.Storage = amrsp::DataStorage::LinearBricks;
    variant.LinearPages = this->Linear.GetNumberOfPages();
    variant.LinearWidthLog2 = this->Linear.GetWidthLog2();
  }
  else
  {
    variant.Storage = amrsp::DataStorage::PackedAtlas;
    variant.AtlasPages = static_cast<int>(this->AtlasPages.size());
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::ActivateGridData(vtkShaderProgram* program)
{
  if (this->UploadedStorage == amrsp::DataStorage::BindlessTextures)
  {
    this->HandlesTexture->Activate();
    program->SetUniformi("amrspHandles", this->HandlesTexture->GetTextureUnit());
    return;
  }
  if (this->UploadedStorage == amrsp::DataStorage::LinearBricks)
  {
    this->Linear.Activate(program);
    return;
  }
  // the atlas pages: amrspAtlas, then amrspAtlas1, amrspAtlas2, ...
  std::vector<float> sizes;
  for (std::size_t p = 0; p < this->AtlasPages.size(); ++p)
  {
    vtkTextureObject* page = this->AtlasPages[p];
    page->Activate();
    program->SetUniformi(
      (p == 0 ? std::string("amrspAtlas") : "amrspAtlas" + std::to_string(p)).c_str(),
      page->GetTextureUnit());
    sizes.insert(
      sizes.end(), { float(page->GetWidth()), float(page->GetHeight()), float(page->GetDepth()) });
  }
  program->SetUniform3f("amrspAtlasSize", sizes.data());
  if (this->AtlasPages.size() > 1)
  {
    program->SetUniform3fv(
      "amrspAtlasPageSize", static_cast<int>(this->AtlasPages.size()), sizes.data());
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::DeactivateGridData()
{
  if (this->UploadedStorage == amrsp::DataStorage::BindlessTextures)
  {
    this->HandlesTexture->Deactivate();
  }
  else if (this->UploadedStorage == amrsp::DataStorage::LinearBricks)
  {
    this->Linear.Deactivate();
  }
  for (vtkTextureObject* page : this->AtlasPages)
  {
    page->Deactivate();
  }
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::Upload(vtkOpenGLRenderWindow* renWin, amrsp::DataStorage storage,
  int atlasLimit, const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  this->UploadLimit = atlasLimit;
  const bool bindless = storage == amrsp::DataStorage::BindlessTextures;
  const bool linear = storage == amrsp::DataStorage::LinearBricks;
  // bindless and linear bricks: each data node holds its offset inside its own brick
  const amrsp::UIntTexture3D& dataNodes =
    bindless || linear ? data.BrickLocalDataNodeTexels : data.PackedDataNodeTexels;
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  for (const glm::ivec3& dims : { data.TreeTexels.Dims, dataNodes.Dims, data.RopeTexels.Dims })
  {
    if (dims.x > max3D || dims.y > max3D || dims.z > max3D)
    {
      error = "the kD-tree textures exceed GL_MAX_3D_TEXTURE_SIZE of this OpenGL context";
      return false;
    }
  }
  // the previous storage's textures go first (their handles are made non-resident)
  if (this->Context == renWin)
  {
    this->ReleaseBindless(renWin);
  }
  this->HandlesTexture = nullptr;
  this->AtlasPages.clear();
  this->Linear.Clear();
  this->TransparentFlags = nullptr; // the data nodes may have changed: flagged again per frame
  this->UploadedStorage = amrsp::DataStorage::None;
  while (glGetError() != GL_NO_ERROR)
  {
  }

  this->Tree = vtkSinglePassAMRTextures::MakeIntegerTexture(renWin, data.TreeTexels);
  this->DataNodes = vtkSinglePassAMRTextures::MakeIntegerTexture(renWin, dataNodes);
  this->Ropes = data.RopeTexels.Texels.empty()
    ? nullptr
    : vtkSinglePassAMRTextures::MakeInteger4Texture(renWin, data.RopeTexels);
  bool ok = this->Tree && this->DataNodes && (this->Ropes || data.RopeTexels.Texels.empty());
  long long bytes = bindless ? data.BindlessBytes : data.PackedBytes;
  if (ok && bindless)
  {
    ok = this->UploadBindless(renWin, data, error);
  }
  else if (ok && linear)
  {
    ok = this->Linear.Upload(
      renWin, data.Data, data.VertexCentred, this->LinearPageBytes, error, progress);
    bytes = data.TreeBytes + this->Linear.GetBytes();
  }
  else if (ok)
  {
    ok = this->UploadAtlas(renWin, data, progress);
  }
  if (ok)
  {
    // grid boxes for the smooth reconstruction: texel 3 g + axis holds grid g's (lo, hi) cells
    // on that axis, signed values bit for bit
    amrsp::UIntTexture3D boxes;
    boxes.Dims = amrsp::TextureDimsFor(3 * data.Data.Grids.size());
    boxes.Texels.assign(
      static_cast<std::size_t>(boxes.Dims.x) * boxes.Dims.y * boxes.Dims.z, glm::uvec2(0u));
    for (std::size_t g = 0; g < data.Data.Grids.size(); ++g)
    {
      const amrsp::Box& box = data.Data.Grids[g].Cells;
      for (int a = 0; a < 3; ++a)
      {
        boxes.Texels[3 * g + a] = glm::uvec2(static_cast<uint32_t>(static_cast<int32_t>(box.Lo[a])),
          static_cast<uint32_t>(static_cast<int32_t>(box.Hi[a])));
      }
    }
    this->BrickBoxes = vtkSinglePassAMRTextures::MakeIntegerTexture(renWin, boxes);
    ok = this->BrickBoxes != nullptr;
  }
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    if (error.empty())
    {
      error = UploadFailure(std::string("the kD-tree and ") +
          (bindless    ? "brick"
              : linear ? "linear"
                       : "atlas"),
        bytes, glError);
    }
    this->ReleaseBindless(renWin);
    this->Tree = nullptr;
    this->DataNodes = nullptr;
    this->Ropes = nullptr;
    this->AtlasPages.clear();
    this->Linear.Clear();
    this->BrickBoxes = nullptr;
    return false;
  }
  this->TextureBytes = bytes;
  this->UploadedStorage = storage;
  this->Context = renWin;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::UploadValues(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  const amrsp::DataStorage storage = this->UploadedStorage;
  this->TransparentFlags = nullptr; // the node ranges are the new step's
  while (glGetError() != GL_NO_ERROR)
  {
  }
  bool ok = false;
  if (storage == amrsp::DataStorage::BindlessTextures)
  {
    // the same bricks: new texels into the resident textures, the handle table unchanged
    ok = this->HandlesTexture &&
      this->Bricks.Overwrite(renWin, amrsp::BrickExtents(data.Data, data.VertexCentred),
        [&data](std::size_t g) { return data.Data.Values[g].data(); });
    if (!ok)
    {
      this->ReleaseBindless(renWin);
      this->HandlesTexture = nullptr;
      ok = this->UploadBindless(renWin, data, error);
    }
  }
  else if (storage == amrsp::DataStorage::LinearBricks)
  {
    ok = this->Linear.Upload(
      renWin, data.Data, data.VertexCentred, this->LinearPageBytes, error, progress);
  }
  else
  {
    // the previous step's pages, overwritten in place where no kept step holds them
    ok = this->UploadAtlas(renWin, data, progress,
      vtkSinglePassAMRPackedAtlas::TakeReusablePages(this->AtlasPages, data.Atlas));
  }
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    if (error.empty())
    {
      error = UploadFailure(std::string("the new time step's ") +
          (storage == amrsp::DataStorage::LinearBricks ? "linear" : "atlas"),
        data.PackedBytes, glError);
    }
    this->ReleaseBindless(renWin);
    this->AtlasPages.clear();
    this->Linear.Clear();
    this->UploadedStorage = amrsp::DataStorage::None;
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::unique_ptr<vtkSinglePassAMRGridStorage> vtkSinglePassAMRGridStorage::ShareStructure() const
{
  if (this->UploadedStorage == amrsp::DataStorage::None ||
    this->UploadedStorage == amrsp::DataStorage::BindlessTextures)
  {
    return nullptr;
  }
  std::unique_ptr<vtkSinglePassAMRGridStorage> shared(new vtkSinglePassAMRGridStorage);
  shared->Tree = this->Tree;
  shared->DataNodes = this->DataNodes;
  shared->BrickBoxes = this->BrickBoxes;
  shared->Ropes = this->Ropes;
  shared->TextureBytes = this->TextureBytes;
  shared->UploadedStorage = this->UploadedStorage;
  shared->UploadLimit = this->UploadLimit;
  shared->LinearPageBytes = this->LinearPageBytes;
  shared->Context = this->Context;
  return shared;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::UploadAtlas(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, const std::function<void(double)>& progress,
  const std::vector<vtkSmartPointer<vtkTextureObject>>& reusable)
{
  const amrsp::AtlasPages& atlas = data.Atlas;
  for (std::size_t p = 0; p < atlas.Pages.size(); ++p)
  {
    vtkTextureObject* reuse = p < reusable.size() ? reusable[p].Get() : nullptr;
    vtkSmartPointer<vtkTextureObject> page = vtkSinglePassAMRPackedAtlas::UploadAtlasBySlabs(
      renWin,
      atlas.Pages.size() == 1 ? data.Data
                              : amrsp::PageHierarchy(data.Data, atlas, static_cast<int>(p)),
      atlas.Pages[p], data.VertexCentred,
      [&progress, &atlas, p](double f)
      {
        if (progress)
        {
          progress((static_cast<double>(p) + f) / static_cast<double>(atlas.Pages.size()));
        }
      },
      reuse);
    if (!page)
    {
      return false;
    }
    this->AtlasPages.push_back(page);
  }
  return !this->AtlasPages.empty();
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::UploadBindless(
  vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data, std::string& error)
{
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
  if (!this->Bricks.Create(
        renWin, extents, [&data](std::size_t g) { return data.Data.Values[g].data(); },
        data.VertexCentred, error))
  {
    return false;
  }
  amrsp::UIntTexture3D handles;
  handles.Dims = amrsp::TextureDimsFor(extents.size());
  handles.Texels.assign(
    static_cast<std::size_t>(handles.Dims.x) * handles.Dims.y * handles.Dims.z, glm::uvec2(0u));
  const std::vector<std::uint64_t>& resident = this->Bricks.GetHandles();
  for (std::size_t g = 0; g < resident.size(); ++g)
  {
    handles.Texels[g] = glm::uvec2(
      static_cast<uint32_t>(resident[g] & 0xffffffffu), static_cast<uint32_t>(resident[g] >> 32));
  }
  this->HandlesTexture = vtkSinglePassAMRTextures::MakeIntegerTexture(renWin, handles);
  return this->HandlesTexture != nullptr;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::UpdateTransparentFlags(vtkOpenGLRenderWindow* renWin,
  const std::vector<glm::vec2>& nodeRanges, const std::vector<float>& opacity,
  const float tableRange[2], vtkMTimeType tableTime, const std::function<float(float)>& toTable)
{
  if (this->TransparentFlags && this->TransparentFlags->GetContext() == renWin &&
    this->FlagsTableTime == tableTime)
  {
    return true;
  }
  const std::vector<float> prefix = amrsp::OpacityPrefixCounts(opacity);
  // texel k at the data node's own texel; texel 0 and padding texels are never read
  const glm::ivec3 dims = amrsp::TextureDimsFor(nodeRanges.size());
  std::vector<unsigned char> flags(static_cast<std::size_t>(dims.x) * dims.y * dims.z, 0);
  this->FlaggedDataNodes = 0;
  for (std::size_t k = 1; k < nodeRanges.size(); ++k)
  {
    // the table index grows with the scalar, so the range's ends bound it
    if (amrsp::TableRangeTransparent(
          prefix, tableRange, toTable(nodeRanges[k].x), toTable(nodeRanges[k].y)))
    {
      flags[k] = 255;
      ++this->FlaggedDataNodes;
    }
  }
  // R8 rows need no unpack padding: a texture row is 256 texels, or the only row
  this->TransparentFlags = vtkSmartPointer<vtkTextureObject>::New();
  this->TransparentFlags->SetContext(renWin);
  this->TransparentFlags->SetInternalFormat(GL_R8);
  this->TransparentFlags->SetFormat(GL_RED);
  this->TransparentFlags->SetDataType(GL_UNSIGNED_BYTE);
  this->TransparentFlags->SetMinificationFilter(vtkTextureObject::Nearest);
  this->TransparentFlags->SetMagnificationFilter(vtkTextureObject::Nearest);
  if (!this->TransparentFlags->Create3DFromRaw(static_cast<unsigned int>(dims.x),
        static_cast<unsigned int>(dims.y), static_cast<unsigned int>(dims.z), 1, VTK_UNSIGNED_CHAR,
        flags.data()))
  {
    this->TransparentFlags = nullptr;
    return false;
  }
  this->FlagsTableTime = tableTime;
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::ReleaseBindless(vtkWindow* window)
{
  if (window == this->CapsContext)
  {
    this->ReleasedBindlessTextures = std::max(
      this->ReleasedBindlessTextures, static_cast<long long>(this->Bricks.GetHandles().size()));
  }
  this->Bricks.ReleaseGraphicsResources(window);
  if (this->HandlesTexture)
  {
    this->HandlesTexture->ReleaseGraphicsResources(window);
    this->HandlesTexture = nullptr;
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Context == window)
  {
    this->ReleaseBindless(window);
  }
  this->UploadedStorage = amrsp::DataStorage::None;
  for (vtkSmartPointer<vtkTextureObject>& page : this->AtlasPages)
  {
    page->ReleaseGraphicsResources(window);
  }
  this->AtlasPages.clear();
  this->Linear.ReleaseGraphicsResources(window);
  for (vtkSmartPointer<vtkTextureObject>* t : { &this->Tree, &this->DataNodes,
         &this->HandlesTexture, &this->BrickBoxes, &this->TransparentFlags, &this->Ropes })
  {
    if (*t)
    {
      (*t)->ReleaseGraphicsResources(window);
      *t = nullptr;
    }
  }
  this->Context = nullptr;
  this->CapsContext = nullptr;
}
