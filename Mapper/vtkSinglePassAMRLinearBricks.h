// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRLinearBricks
 * @brief   the linear storage: the bricks back to back in 2D R32F pages, and their table
 *
 * Private to the module; behind the vtkSinglePassAMRGridData interface, its GLSL piece
 * Shaders/StorageLinearBricks.glsl. The layout is amrsp::LinearBrickLayout: rows of 2^WidthLog2
 * texels (the largest power of two within GL_MAX_TEXTURE_SIZE, at most 16384), at most
 * GL_MAX_TEXTURE_SIZE rows and 2^28 texels (1 GiB) per page, or fewer rows where the mapper's
 * MaximumAtlasPageBytes asks for smaller pages. The table is the RG32UI texture
 * of amrsp::LinearBrickTable. Pages are uploaded by slabs of rows, each filled by a worker
 * thread while the previous one is handed to the driver, as the packed atlas is.
 */
#ifndef vtkSinglePassAMRLinearBricks_h
#define vtkSinglePassAMRLinearBricks_h

#include "vtkSinglePassAMRGridData.h"

#include "amrsp/Hierarchy.h"

#include "vtkSmartPointer.h"

#include <functional>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkWindow;

class vtkSinglePassAMRLinearBricks : public vtkSinglePassAMRGridData
{
public:
  /// Replaces the textures with the bricks of `h` (cells, or vertices when `vertexCentred`) in
  /// `renWin`, its context current. Returns false with a one-line `error` when the bricks do not
  /// fit the layout's limits or the driver refuses a texture; nothing is kept then.
  /// `maxPageBytes` (> 0) lowers the page size (MaximumAtlasPageBytes). `progress` gets the
  /// fraction of the texels uploaded (0 to 1). A previous page of the same shape that nothing
  /// else holds is overwritten in place.
  bool UploadBricks(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h, bool vertexCentred,
    long long maxPageBytes, std::string& error, const std::function<void(double)>& progress);

  /// Whether the bricks of `h` surely fit the pages `renWin` allows (with `maxPageBytes` as in
  /// Upload): a sufficient test, O(grids), without laying them out.
  static bool Fits(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h, bool vertexCentred,
    long long maxPageBytes);

  /// The largest page the uploads make, in bytes (the mapper's MaximumAtlasPageBytes; 0: as
  /// large as the context allows).
  void SetMaximumPageBytes(long long bytes) { this->MaximumPageBytes = bytes; }

  ///@{
  /// vtkSinglePassAMRGridData: UploadBricks of RayCastingData::Data (new pages; UploadValues
  /// overwrites the previous ones in place). Activate points amrspLinear, amrspLinear1.. and
  /// amrspBrickTable at their units. GetBytes: the pages (whole rows) and the table.
  amrsp::DataStorage GetStorage() const override { return amrsp::DataStorage::LinearBricks; }
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
  int GetNumberOfPages() const { return static_cast<int>(this->Pages.size()); }
  /// Base-2 logarithm of a page's row length in texels (the shader's AMRSP_LINEAR_WIDTH_LOG2).
  int GetWidthLog2() const { return this->WidthLog2; }
  bool IsUploaded() const { return !this->Pages.empty(); }

  void Clear();

private:
  /// Rows of 2^widthLog2 texels (the largest power of two within GL_MAX_TEXTURE_SIZE, at most
  /// 2^14) and at most maxRows of them per page; returns GL_MAX_TEXTURE_SIZE.
  static int PageShape(
    vtkOpenGLRenderWindow* renWin, long long maxPageBytes, int& widthLog2, int& maxRows);

  std::vector<vtkSmartPointer<vtkTextureObject>> Pages;
  vtkSmartPointer<vtkTextureObject> Table;
  int WidthLog2 = 0;
  long long Bytes = 0;
  long long MaximumPageBytes = 0;
};

#endif
