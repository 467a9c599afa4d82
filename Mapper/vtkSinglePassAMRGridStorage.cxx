// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRGridStorage.h"

#include "vtkAMRMapperAtlasTextures.h"
#include "vtkSinglePassAMRBindlessBricks.h"
#include "vtkSinglePassAMRLinearBricks.h"
#include "vtkAMRMapperPackedAtlas.h"
#include "vtkAMRMapperTextures.h"

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkAMRMapperOpenGL.h"

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
  if (this->Caps.Update(renWin))
  {
    this->ReleasedBindlessTextures = 0; // a new context: no slots of earlier sets in it
  }
}

//------------------------------------------------------------------------------
vtkSinglePassAMRRayCasterFacts vtkSinglePassAMRGridStorage::RayCasterFacts(
  vtkOpenGLRenderWindow* renWin)
{
  this->QueryCapabilities(renWin);
  vtkSinglePassAMRRayCasterFacts facts;
  facts.Compute = !this->Caps.ComputeVersion.empty();
  facts.NoCompute = this->Caps.NoCompute;
  facts.CpuDriver = this->Caps.CpuDriver;
  return facts;
}

//------------------------------------------------------------------------------
amrsp::BindlessAccess vtkSinglePassAMRGridStorage::ResolveAccess(
  vtkOpenGLRenderWindow* renWin, amrsp::BindlessAccess access, std::string& why)
{
  this->QueryCapabilities(renWin);
  return this->Caps.ResolveAccess(access, why);
}

//------------------------------------------------------------------------------
vtkSinglePassAMRStorageChoice vtkSinglePassAMRGridStorage::Choose(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, const vtkSinglePassAMRStorageRequest& request, int atlasLimit)
{
  vtkSinglePassAMRStorageFacts facts;
  facts.Bindless = this->ResolveAccess(renWin, request.Access, facts.NoBindless);
  if (facts.Bindless != amrsp::BindlessAccess::None && this->Caps.MaxBindlessTextures >= 0 &&
    data.Grids > this->Caps.MaxBindlessTextures)
  {
    facts.NoBindless = "this driver (Mesa's zink) holds at most " +
      std::to_string(this->Caps.MaxBindlessTextures) + " bindless textures and the hierarchy has " +
      std::to_string(data.Grids) + " grids";
    facts.Bindless = amrsp::BindlessAccess::None;
  }
  else if (facts.Bindless != amrsp::BindlessAccess::None && this->Caps.MaxBindlessTextures >= 0 &&
    !(this->GetUploadedStorage() == amrsp::DataStorage::BindlessTextures &&
      this->Context == renWin && !request.NewTextures))
  {
    // the set in use is released before the new one is made, but its slots come back later
    const auto* bindless = dynamic_cast<const vtkSinglePassAMRBindlessBricks*>(this->Grid.get());
    const long long inUse = bindless && this->Context == renWin
      ? static_cast<long long>(bindless->GetHandles().size())
      : 0LL;
    const long long earlier = std::max({ this->ReleasedBindlessTextures, inUse,
      bindless && this->Context == this->Caps.Context ? bindless->GetLargestReleasedSet() : 0LL });
    if (data.Grids + earlier > this->Caps.MaxBindlessTextures)
    {
      facts.NoBindless = "this driver (Mesa's zink) holds at most " +
        std::to_string(this->Caps.MaxBindlessTextures) +
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
      vtkAMRMapperPackedAtlas::AtlasFitsContext(renWin, dims, atlasLimit, facts.NoAtlas);
  }
  facts.AtlasWaste = data.AtlasWaste;
  facts.BrickBytes = data.BrickBytes;
  facts.CpuDriver = this->Caps.CpuDriver;
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
  return this->GetUploadedStorage() == storage && this->Context == renWin &&
    this->UploadLimit == atlasLimit;
}

//------------------------------------------------------------------------------
std::unique_ptr<vtkSinglePassAMRGridData> vtkSinglePassAMRGridStorage::NewGridData(
  amrsp::DataStorage storage) const
{
  if (storage == amrsp::DataStorage::BindlessTextures)
  {
    return std::unique_ptr<vtkSinglePassAMRGridData>(new vtkSinglePassAMRBindlessBricks);
  }
  if (storage == amrsp::DataStorage::LinearBricks)
  {
    std::unique_ptr<vtkSinglePassAMRLinearBricks> linear(new vtkSinglePassAMRLinearBricks);
    linear->SetMaximumPageBytes(this->LinearPageBytes);
    return std::unique_ptr<vtkSinglePassAMRGridData>(linear.release());
  }
  std::unique_ptr<vtkAMRMapperAtlasTextures> atlas(new vtkAMRMapperAtlasTextures);
  atlas->SetAtlasLimit(this->UploadLimit);
  return std::unique_ptr<vtkSinglePassAMRGridData>(atlas.release());
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::DropGridData(vtkWindow* window)
{
  if (!this->Grid)
  {
    return;
  }
  if (window)
  {
    this->Grid->ReleaseGraphicsResources(window);
  }
  // zink gives a freed set's bindless slots back only later: count them for the next sets
  if (const auto* bindless = dynamic_cast<const vtkSinglePassAMRBindlessBricks*>(this->Grid.get()))
  {
    if (this->Context == this->Caps.Context)
    {
      this->ReleasedBindlessTextures =
        std::max(this->ReleasedBindlessTextures, bindless->GetLargestReleasedSet());
    }
  }
  this->Grid.reset();
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRGridStorage::GetNumberOfLinearPages() const
{
  const auto* linear = dynamic_cast<const vtkSinglePassAMRLinearBricks*>(this->Grid.get());
  return linear ? linear->GetNumberOfPages() : 0;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::DescribeGridData(vtkSinglePassAMRShaderVariant& variant) const
{
  if (this->Grid)
  {
    this->Grid->Describe(variant);
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::ActivateGridData(vtkShaderProgram* program)
{
  this->Grid->Activate(program);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRGridStorage::DeactivateGridData()
{
  this->Grid->Deactivate();
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::Upload(vtkOpenGLRenderWindow* renWin, amrsp::DataStorage storage,
  int atlasLimit, const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  this->UploadLimit = atlasLimit;
  std::unique_ptr<vtkSinglePassAMRGridData> grid = this->NewGridData(storage);
  const amrsp::UIntTexture3D& dataNodes = grid->GetDataNodeTexels(data);
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  for (const glm::ivec3& dims : { data.TreeTexels.Dims, dataNodes.Dims, data.RopeTexels.Dims })
  {
    if (dims.x > max3D || dims.y > max3D || dims.z > max3D)
    {
      error = "the kD-tree textures exceed GL_MAX_3D_TEXTURE_SIZE of this OpenGL context";
      return false;
    }
  }
  // the previous storage's textures go first (bindless handles are made non-resident)
  this->DropGridData(this->Context == renWin ? renWin : nullptr);
  this->TransparentFlags = nullptr; // the data nodes may have changed: flagged again per frame
  while (glGetError() != GL_NO_ERROR)
  {
  }

  this->Tree = vtkAMRMapperTextures::MakeIntegerTexture(renWin, data.TreeTexels);
  this->DataNodes = vtkAMRMapperTextures::MakeIntegerTexture(renWin, dataNodes);
  this->Ropes = data.RopeTexels.Texels.empty()
    ? nullptr
    : vtkAMRMapperTextures::MakeInteger4Texture(renWin, data.RopeTexels);
  bool ok = this->Tree && this->DataNodes && (this->Ropes || data.RopeTexels.Texels.empty());
  ok = ok && grid->Upload(renWin, data, error, progress);
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
    this->BrickBoxes = vtkAMRMapperTextures::MakeIntegerTexture(renWin, boxes);
    ok = this->BrickBoxes != nullptr;
  }
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    if (error.empty())
    {
      error = UploadFailure(std::string("the kD-tree and ") +
          (storage == amrsp::DataStorage::BindlessTextures  ? "brick"
              : storage == amrsp::DataStorage::LinearBricks ? "linear"
                                                            : "atlas"),
        storage == amrsp::DataStorage::BindlessTextures ? data.BindlessBytes
          : storage == amrsp::DataStorage::LinearBricks ? data.TreeBytes + grid->GetBytes()
                                                        : data.PackedBytes,
        glError);
    }
    this->Context = renWin;
    this->Grid = std::move(grid);
    this->DropGridData(renWin);
    this->Tree = nullptr;
    this->DataNodes = nullptr;
    this->Ropes = nullptr;
    this->BrickBoxes = nullptr;
    return false;
  }
  this->Grid = std::move(grid);
  this->TextureBytes = data.TreeBytes + this->Grid->GetBytes();
  this->Context = renWin;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRGridStorage::UploadValues(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  this->TransparentFlags = nullptr; // the node ranges are the new step's
  while (glGetError() != GL_NO_ERROR)
  {
  }
  const amrsp::DataStorage storage = this->GetUploadedStorage();
  bool ok = this->Grid && this->Grid->UploadValues(renWin, data, error, progress);
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    if (error.empty())
    {
      error = UploadFailure(std::string("the new time step's ") +
          (storage == amrsp::DataStorage::LinearBricks ? "linear" : "atlas"),
        data.PackedBytes, glError);
    }
    this->DropGridData(renWin);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::unique_ptr<vtkSinglePassAMRGridStorage> vtkSinglePassAMRGridStorage::ShareStructure() const
{
  std::unique_ptr<vtkSinglePassAMRGridData> grid =
    this->Grid ? this->Grid->NewForAnotherStep() : nullptr;
  if (!grid)
  {
    return nullptr;
  }
  std::unique_ptr<vtkSinglePassAMRGridStorage> shared(new vtkSinglePassAMRGridStorage);
  shared->Grid = std::move(grid);
  shared->Tree = this->Tree;
  shared->DataNodes = this->DataNodes;
  shared->BrickBoxes = this->BrickBoxes;
  shared->Ropes = this->Ropes;
  shared->TextureBytes = this->TextureBytes;
  shared->UploadLimit = this->UploadLimit;
  shared->LinearPageBytes = this->LinearPageBytes;
  shared->Context = this->Context;
  return shared;
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
void vtkSinglePassAMRGridStorage::ReleaseGraphicsResources(vtkWindow* window)
{
  this->DropGridData(window);
  for (vtkSmartPointer<vtkTextureObject>* t :
    { &this->Tree, &this->DataNodes, &this->BrickBoxes, &this->TransparentFlags, &this->Ropes })
  {
    if (*t)
    {
      (*t)->ReleaseGraphicsResources(window);
      *t = nullptr;
    }
  }
  this->Context = nullptr;
  this->Caps = vtkAMRMapperContextCapabilities();
}
