// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAMRMapperAtlasTextures
 * @brief   the packed-atlas storage on the GPU: one R32F 3D texture per atlas page
 *
 * Private to the module. The paper's packing storage (sections 4.1 and 5.1): every grid's brick
 * packed into one atlas, or a few pages of it (amrsp::AtlasPages), each uploaded slab by slab
 * (vtkAMRMapperPackedAtlas::UploadAtlas). Both mappers hold their atlas in one of these: the
 * single pass through the vtkSinglePassAMRGridData interface, the multi-pass mapper through
 * UploadPages and GetPage. Its GLSL piece is Shaders/StoragePackedAtlas.glsl.
 *
 * Invariant: Pages[p] holds page p of the layout uploaded last; empty when nothing is uploaded.
 */
#ifndef vtkAMRMapperAtlasTextures_h
#define vtkAMRMapperAtlasTextures_h

#include "vtkSinglePassAMRGridData.h"

#include "amrsp/AtlasPages.h"
#include "amrsp/Hierarchy.h"

#include "vtkSmartPointer.h"

#include <vector>

class vtkTextureObject;

class vtkAMRMapperAtlasTextures : public vtkSinglePassAMRGridData
{
public:
  /// Uploads the bricks of `h` (cells, or vertices when `vertexCentred`) placed by `pages`, each
  /// page within GL_MAX_3D_TEXTURE_SIZE and `atlasLimit` (> 0: the user's MaximumAtlasSize).
  /// With `reuse`, a page of the same index and dimensions that nothing else holds (no kept time
  /// step draws from it) is overwritten in place. Returns false with a one-line `error`; nothing
  /// is kept then. `progress` gets the fraction of the pages uploaded.
  bool UploadPages(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
    const amrsp::AtlasPages& pages, bool vertexCentred, int atlasLimit, bool reuse,
    std::string& error, const std::function<void(double)>& progress);

  int GetNumberOfPages() const { return static_cast<int>(this->Pages.size()); }
  /// Activates every page on a texture unit of its own (Deactivate undoes it).
  void ActivatePages();
  vtkTextureObject* GetPage(int page) const { return this->Pages[static_cast<std::size_t>(page)]; }

  /// The MaximumAtlasSize the single pass's uploads hold to (0: GL_MAX_3D_TEXTURE_SIZE only).
  void SetAtlasLimit(int limit) { this->AtlasLimit = limit; }

  ///@{
  /// vtkSinglePassAMRGridData: the atlas of RayCastingData::Atlas, addressed through
  /// PackedDataNodeTexels; Activate sets amrspAtlas, amrspAtlas1.., amrspAtlasSize and, with
  /// pages, amrspAtlasPageSize.
  amrsp::DataStorage GetStorage() const override { return amrsp::DataStorage::PackedAtlas; }
  const amrsp::UIntTexture3D& GetDataNodeTexels(const amrsp::RayCastingData& data) const override
  {
    return data.PackedDataNodeTexels;
  }
  bool Upload(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data, std::string& error,
    const std::function<void(double)>& progress) override;
  bool UploadValues(vtkOpenGLRenderWindow* renWin, const amrsp::RayCastingData& data,
    std::string& error, const std::function<void(double)>& progress) override;
  std::unique_ptr<vtkSinglePassAMRGridData> NewForAnotherStep() const override;
  void Describe(vtkSinglePassAMRShaderVariant& variant) const override;
  void Activate(vtkShaderProgram* program) override;
  void Deactivate() override;
  long long GetBytes() const override { return this->Bytes; }
  void ReleaseGraphicsResources(vtkWindow* window) override;
  ///@}

private:
  std::vector<vtkSmartPointer<vtkTextureObject>> Pages;
  int AtlasLimit = 0;
  long long Bytes = 0; ///< 4 bytes per texel of every page
};

#endif
