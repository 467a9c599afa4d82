// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRGridStorage
 * @brief   the single-pass mapper's GPU data: the tree textures, and the grid data of one storage
 *
 * Private to the module (the header exposes core types), as vtkVolumeTexture is to VTK's GPU ray
 * caster. It holds, for one OpenGL context:
 * - the kD-tree (RG32UI) and its data nodes (RG32UI) of amrsp::RayCastingData, the one owner of
 *   the tree textures;
 * - the grid data in one storage behind vtkSinglePassAMRGridData: the packed atlas
 *   (vtkAMRMapperAtlasTextures), bindless textures (vtkSinglePassAMRBindlessBricks) or linear
 *   bricks (vtkSinglePassAMRLinearBricks);
 * - the grids' cell boxes (RG32UI, 3 texels per grid) for the smooth-cell reconstruction;
 * - the empty-space flags (R8, one per data node) for the current transfer-function table.
 * It also answers what the context can do (vtkAMRMapperContextCapabilities, queried once per
 * context), the facts vtkSinglePassAMRStorageChoice and the ray-caster rule decide on.
 */
#ifndef vtkSinglePassAMRGridStorage_h
#define vtkSinglePassAMRGridStorage_h

#include "amrsp/RayCastingData.h"

#include "vtkAMRMapperContextCapabilities.h"
#include "vtkSinglePassAMRGridData.h"
#include "vtkSinglePassAMRRayCasterChoice.h"
#include "vtkSinglePassAMRShaderVariant.h"
#include "vtkSinglePassAMRStorageChoice.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <functional> // for UpdateTransparentFlags and Upload
#include <memory>     // for ShareStructure
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class vtkSinglePassAMRGridStorage
{
public:
  /// The storage for `data` in `renWin` (vtkSinglePassAMRStorageChoice::Choose on what the
  /// context and the build allow), the packed atlas held to `atlasLimit` texels per edge (> 0)
  /// and GL_MAX_3D_TEXTURE_SIZE.
  vtkSinglePassAMRStorageChoice Choose(vtkOpenGLRenderWindow* renWin,
    const amrsp::RayCastingData& data, const vtkSinglePassAMRStorageRequest& request,
    int atlasLimit);

  /// The bindless access `access` resolves to in `renWin` (Auto: direct with GL_NV_gpu_shader5,
  /// else waterfall), or None with `why`.
  amrsp::BindlessAccess ResolveAccess(
    vtkOpenGLRenderWindow* renWin, amrsp::BindlessAccess access, std::string& why);

  /// What `renWin` offers the ray casters (compute shaders, a CPU driver).
  vtkSinglePassAMRRayCasterFacts RayCasterFacts(vtkOpenGLRenderWindow* renWin);
  /// Whether `renWin` has GL_NV_shader_thread_group (gl_SMIDNV, gl_WarpIDNV: the occupancy
  /// probe).
  bool HasThreadBuiltins(vtkOpenGLRenderWindow* renWin)
  {
    this->QueryCapabilities(renWin);
    return this->Caps.ThreadBuiltins;
  }
  /// The compute shader's first lines in `renWin` (#version, and the extension on OpenGL 4.2);
  /// empty without compute shaders.
  const std::string& GetComputeVersion(vtkOpenGLRenderWindow* renWin)
  {
    this->QueryCapabilities(renWin);
    return this->Caps.ComputeVersion;
  }

  /// Whether the textures of `storage` in `renWin` are up to date for the data built last.
  bool IsUploaded(vtkOpenGLRenderWindow* renWin, amrsp::DataStorage storage, int atlasLimit) const;
  /// Whether anything is uploaded (a storage and a context).
  bool HasUpload() const { return this->Grid != nullptr; }

  /// Uploads the tree and the grid data of `data` in `storage`; the previous textures are freed
  /// first. Returns false with a one-line `error` (a texture over GL_MAX_3D_TEXTURE_SIZE, the
  /// driver refusing an allocation); the caller keeps `data` to try again.
  /// `progress` gets the fraction of the grid data uploaded (0 to 1).
  bool Upload(vtkOpenGLRenderWindow* renWin, amrsp::DataStorage storage, int atlasLimit,
    const amrsp::RayCastingData& data, std::string& error,
    const std::function<void(double)>& progress = nullptr);

  /// A new time step of the uploaded structure (amrsp::RefreshValues): uploads the grid data of
  /// `data` into the storage uploaded last (IsUploaded), keeping the tree, data-node, rope and
  /// brick-box textures and the atlas layout; the transparency flags are computed again. Same
  /// errors as Upload; on failure nothing is left uploaded.
  bool UploadValues(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data,
    std::string& error, const std::function<void(double)>& progress = nullptr);

  /// A storage that shares this one's tree, data-node, rope and brick-box textures and holds no
  /// grid data yet: UploadValues fills it with another time step's values of the same structure,
  /// while this one keeps its own (a step kept for playback). Null for the bindless storage (its
  /// resident handles are limited) and when nothing is uploaded.
  std::unique_ptr<vtkSinglePassAMRGridStorage> ShareStructure() const;

  /// Flags the data nodes whose value range (`nodeRanges`, entry 0 unused) is transparent under
  /// the tabulated opacities `opacity` over [tableRange[0], tableRange[0] + 1 / tableRange[1]]
  /// (amrsp::TableRangeTransparent), when `tableTime` differs from the last call's or the flags
  /// are missing. Returns false when the flag texture cannot be created.
  /// `toTable` maps a scalar to the table's units (identity, or log10 for a log-scaled table).
  bool UpdateTransparentFlags(vtkOpenGLRenderWindow* renWin,
    const std::vector<glm::vec2>& nodeRanges, const std::vector<float>& opacity,
    const float tableRange[2], vtkMTimeType tableTime, const std::function<float(float)>& toTable);
  /// Data nodes flagged transparent by the last UpdateTransparentFlags.
  long long GetFlaggedDataNodes() const { return this->FlaggedDataNodes; }

  /// The grid data of the last upload as the single-pass shader reads it: its storage and the
  /// atlas pages, or the linear pages and rows.
  void DescribeGridData(vtkSinglePassAMRShaderVariant& variant) const;
  /// Activates the grid data's textures of the last upload and sets their samplers and sizes in
  /// `program` (amrspAtlas.., amrspAtlasSize, amrspAtlasPageSize; amrspHandles; amrspLinear..,
  /// amrspBrickTable); DeactivateGridData undoes it.
  void ActivateGridData(vtkShaderProgram* program);
  void DeactivateGridData();

  ///@{
  /// The textures of the last upload (null before it).
  vtkTextureObject* GetTree() const { return this->Tree; }
  vtkTextureObject* GetDataNodes() const { return this->DataNodes; }
  /// Linear storage: its pages (0 unless it was uploaded last).
  int GetNumberOfLinearPages() const;
  vtkTextureObject* GetBrickBoxes() const { return this->BrickBoxes; }
  /// The tree's neighbour links and node boxes; null where the build has none.
  vtkTextureObject* GetRopes() const { return this->Ropes; }
  vtkTextureObject* GetTransparentFlags() const { return this->TransparentFlags; }
  ///@}

  /// Bytes of the textures of the last upload (tree + data nodes + atlas, or + bricks + handles,
  /// or + linear pages + brick table).
  long long GetTextureBytes() const { return this->TextureBytes; }
  /// The storage of the last upload, None when none is on the GPU.
  amrsp::DataStorage GetUploadedStorage() const
  {
    return this->Grid ? this->Grid->GetStorage() : amrsp::DataStorage::None;
  }

  /// The largest linear page the next uploads make, in bytes (the mapper's MaximumAtlasPageBytes;
  /// 0: as large as the context allows).
  void SetLinearPageBytes(long long bytes) { this->LinearPageBytes = bytes; }

  /// Frees every texture of `window` (making the bindless handles non-resident first).
  void ReleaseGraphicsResources(vtkWindow* window);

private:
  void QueryCapabilities(vtkOpenGLRenderWindow* renWin);
  /// An empty grid-data object of `storage` with this object's limits.
  std::unique_ptr<vtkSinglePassAMRGridData> NewGridData(amrsp::DataStorage storage) const;
  /// Frees the grid data (its textures in `window` when given) and forgets it.
  void DropGridData(vtkWindow* window);

  vtkSmartPointer<vtkTextureObject> Tree;
  vtkSmartPointer<vtkTextureObject> DataNodes;
  std::unique_ptr<vtkSinglePassAMRGridData> Grid; // the storage uploaded last; null: none
  vtkSmartPointer<vtkTextureObject> BrickBoxes;   // RG32UI, per brick and axis: grid cells lo, hi
  vtkSmartPointer<vtkTextureObject> Ropes;        // RGBA32UI, three per kD node (KdTreeLayout.glsl)
  // R8, indexed like the data nodes: 255 where the node's value range is transparent under the
  // table of FlagsTableTime
  vtkSmartPointer<vtkTextureObject> TransparentFlags;
  vtkMTimeType FlagsTableTime = 0;
  long long FlaggedDataNodes = 0;
  long long TextureBytes = 0;
  int UploadLimit = 0; // atlasLimit of the last upload
  long long LinearPageBytes = 0;
  vtkOpenGLRenderWindow* Context = nullptr;

  vtkAMRMapperContextCapabilities Caps; // of the context last asked
  // zink frees a deleted texture's bindless slot only when the batch that deleted it is
  // recycled, not at glFinish: a regridded series of 600 grids crashed its driver thread (600 old
  // and 600 new handles). So where MaxBindlessTextures applies, a new set must also leave room for
  // the largest set released in this context (a conservative bound: the slots do come back).
  long long ReleasedBindlessTextures = 0;
};

#endif
