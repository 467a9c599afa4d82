// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkAMRMapperPackedAtlas.h
 * @brief   the packed atlas: its CPU build and its upload (private to the module)
 *
 * The paper's packing storage (sections 4.1 and 5.1): every grid's brick packed into one R32F
 * 3D atlas (or a few pages of it). The multi-pass mapper's build from vtkOverlappingAMR (the
 * conversion, then amrsp::PackHierarchy), the atlas's size checks, and its upload slab by slab,
 * which vtkAMRMapperAtlasTextures holds for both mappers.
 */
#ifndef vtkAMRMapperPackedAtlas_h
#define vtkAMRMapperPackedAtlas_h

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/PackedHierarchy.h"

#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkOverlappingAMR;

namespace vtkAMRMapperPackedAtlas
{

using amrsp::PackedHierarchy;

/**
 * Converts `amr` (array `array`, component `component`), builds the kD-tree and packs the bricks
 * with the better packer within `packLimit` texels per axis (0: the 2048 the data-node offsets
 * address; a positive value lowers it), over atlas pages of at most `maxPageTexels` texels (0:
 * one atlas). Returns false with a one-line `error` (conversion, tree or packing failure).
 */
bool BuildPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, PackedHierarchy& out, std::string& error);

/**
 * A new time step for `out` built by BuildPackedHierarchy with the same array, component and
 * limits: when `mayRefresh` and `amr`'s hierarchy has `out`'s structure (amrsp::SameStructure),
 * `out` keeps its tree and atlas layout and takes the new values and their range (`refreshed`
 * true); otherwise it is built again as BuildPackedHierarchy does. Same errors.
 */
bool RefreshPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed,
  std::string& error);

/**
 * Whether an atlas of `dims` texels fits `renWin`'s GL_MAX_3D_TEXTURE_SIZE and `atlasLimit`
 * (> 0: a lower limit set by the user). When not, `why` names the limit it exceeds.
 */
bool AtlasFitsContext(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int atlasLimit, std::string& why);

/**
 * Hands `units` units (atlas layers, page rows) of `unitFloats` floats each to `upload` in slabs
 * of at most `slab` units, double-buffered: a worker thread fills the next slab (`fill(first,
 * last, out)`, units first <= u < last) while `upload(first, last, texels)` hands the current one
 * to the driver. `progress` gets the fraction of the units done after each slab. Rethrows what
 * `fill` threw.
 */
void UploadInSlabs(int units, int slab, std::size_t unitFloats,
  const std::function<void(int, int, float*)>& fill,
  const std::function<void(int, int, const float*)>& upload,
  const std::function<void(double)>& progress);

/**
 * The atlas of `h`'s bricks placed by `layout` as an R32F 3D texture (MakeScalarTexture's
 * filtering), allocated empty and filled slab by slab (amrsp::AtlasSlabFiller, about 16 MiB per
 * glTexSubImage3D, the next slab filled on a worker thread meanwhile): the whole atlas never
 * exists in host memory. `progress` gets the fraction of the layers uploaded after each slab.
 * `reuse`, when given with the layout's dimensions, is overwritten in place instead of allocating
 * a new texture (a time step's new values in the same layout: no allocation, no first-touch of
 * fresh driver memory). Null when OpenGL refused the allocation.
 */
vtkSmartPointer<vtkTextureObject> UploadAtlasBySlabs(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, const amrsp::AtlasLayout& layout, bool vertexCentred,
  const std::function<void(double)>& progress = nullptr, vtkTextureObject* reuse = nullptr);

/**
 * UploadAtlasBySlabs with checks: fails with a one-line `error` when an edge exceeds
 * GL_MAX_3D_TEXTURE_SIZE or `atlasLimit` (> 0), or when OpenGL reports an error (e.g. out of
 * memory); `texture` is then null. `reuse` as for UploadAtlasBySlabs.
 */
bool UploadAtlas(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
  const amrsp::AtlasLayout& layout, bool vertexCentred, int atlasLimit,
  vtkSmartPointer<vtkTextureObject>& texture, std::string& error,
  const std::function<void(double)>& progress = nullptr, vtkTextureObject* reuse = nullptr);

/**
 * Takes `pages` (emptying it) and returns, page by page of `layout`, the texture that page may
 * overwrite in place: the old page of the same index and dimensions when nothing but `pages` held
 * it (no kept time step draws from it), else null. The others are released here, before the new
 * pages are allocated, so that a changed layout never holds two atlases at once.
 */
std::vector<vtkSmartPointer<vtkTextureObject>> TakeReusablePages(
  std::vector<vtkSmartPointer<vtkTextureObject>>& pages, const amrsp::AtlasPages& layout);

} // namespace vtkAMRMapperPackedAtlas

#endif
