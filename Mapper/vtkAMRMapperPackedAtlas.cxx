// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperPackedAtlas.h"

#include "vtkAMRMapperConversion.h"
#include "vtkAMRMapperTextures.h"

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/RayCastingData.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkOverlappingAMR.h"
#include "vtkAMRMapperOpenGL.h"

#include <algorithm>
#include <exception>
#include <future>
#include <sstream>
#include <utility>

namespace vtkAMRMapperPackedAtlas
{

//------------------------------------------------------------------------------
namespace
{
bool ConvertAndPack(vtkOverlappingAMR* amr, const std::string& array, int component, int packLimit,
  int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed, std::string& error)
{
  refreshed = false;
  amrsp::Hierarchy h;
  try
  {
    vtkAMRMapperConversion::ArraySelection selection;
    selection.Name = array;
    selection.Component = component;
    if (!vtkAMRMapperConversion::FromOverlappingAMR(amr, selection, h, error))
    {
      out = PackedHierarchy();
      return false;
    }
  }
  catch (const std::exception& e)
  {
    error = e.what();
    out = PackedHierarchy();
    return false;
  }
  return amrsp::PackHierarchy(
    std::move(h), packLimit, maxPageTexels, mayRefresh, out, refreshed, error);
}
} // namespace

bool BuildPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, PackedHierarchy& out, std::string& error)
{
  bool refreshed = false;
  return ConvertAndPack(
    amr, array, component, packLimit, maxPageTexels, false, out, refreshed, error);
}

bool RefreshPackedHierarchy(vtkOverlappingAMR* amr, const std::string& array, int component,
  int packLimit, int64_t maxPageTexels, bool mayRefresh, PackedHierarchy& out, bool& refreshed,
  std::string& error)
{
  return ConvertAndPack(
    amr, array, component, packLimit, maxPageTexels, mayRefresh, out, refreshed, error);
}

//------------------------------------------------------------------------------
bool AtlasFitsContext(
  vtkOpenGLRenderWindow* renWin, const glm::ivec3& dims, int atlasLimit, std::string& why)
{
  const int max3D = vtkTextureObject::GetMaximumTextureSize3D(renWin);
  const int limit = atlasLimit > 0 ? std::min(atlasLimit, max3D) : max3D;
  if (dims.x <= limit && dims.y <= limit && dims.z <= limit)
  {
    return true;
  }
  std::ostringstream msg;
  msg << "the packed atlas (" << dims.x << " x " << dims.y << " x " << dims.z
      << " texels) exceeds ";
  if (limit < max3D)
  {
    msg << "MaximumAtlasSize = " << limit << " (GL_MAX_3D_TEXTURE_SIZE is " << max3D << ")";
  }
  else
  {
    msg << "GL_MAX_3D_TEXTURE_SIZE = " << max3D << " of this OpenGL context";
  }
  why = msg.str();
  return false;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTextureObject> UploadAtlasBySlabs(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, const amrsp::AtlasLayout& layout, bool vertexCentred,
  const std::function<void(double)>& progress, vtkTextureObject* reuse)
{
  const glm::ivec3 d = layout.Dims;
  vtkSmartPointer<vtkTextureObject> atlas = reuse;
  if (!reuse || static_cast<int>(reuse->GetWidth()) != d.x ||
    static_cast<int>(reuse->GetHeight()) != d.y || static_cast<int>(reuse->GetDepth()) != d.z)
  {
    atlas = vtkAMRMapperTextures::MakeScalarTexture(renWin, d, nullptr, vertexCentred);
  }
  if (!atlas)
  {
    return nullptr;
  }
  const std::size_t layer = static_cast<std::size_t>(d.x) * static_cast<std::size_t>(d.y);
  const int slab = static_cast<int>(std::max<std::size_t>(
    1, std::min<std::size_t>(d.z, (std::size_t(16) << 20) / (layer * sizeof(float)))));
  const amrsp::AtlasSlabFiller filler(h, layout);
  atlas->Activate(); // bound to a texture unit of its own for the uploads
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  UploadInSlabs(
    d.z, slab, layer, [&filler](int z0, int z1, float* out) { filler.Fill(z0, z1, out); },
    [&d](int z0, int z1, const float* texels)
    { glTexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, z0, d.x, d.y, z1 - z0, GL_RED, GL_FLOAT, texels); },
    progress);
  atlas->Deactivate();
  return atlas;
}

//------------------------------------------------------------------------------
void UploadInSlabs(int units, int slab, std::size_t unitFloats,
  const std::function<void(int, int, float*)>& fill,
  const std::function<void(int, int, const float*)>& upload,
  const std::function<void(double)>& progress)
{
  slab = std::max(1, std::min(slab, units));
  std::vector<float> buffers[2] = { std::vector<float>(unitFloats * static_cast<std::size_t>(slab)),
    std::vector<float>(unitFloats * static_cast<std::size_t>(slab)) };
  const auto fillSlab = [&fill, units, slab](int first, std::vector<float>& texels)
  { fill(first, std::min(units, first + slab), texels.data()); };
  if (units > 0)
  {
    fillSlab(0, buffers[0]);
  }
  for (int first = 0, k = 0; first < units; first += slab, k ^= 1)
  {
    std::future<void> next;
    if (first + slab < units)
    {
      next = std::async(std::launch::async, fillSlab, first + slab, std::ref(buffers[k ^ 1]));
    }
    const int last = std::min(units, first + slab);
    upload(first, last, buffers[k].data());
    if (next.valid())
    {
      next.get(); // rethrows what the fill threw
    }
    if (progress)
    {
      progress(static_cast<double>(last) / units);
    }
  }
}

bool UploadAtlas(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
  const amrsp::AtlasLayout& layout, bool vertexCentred, int atlasLimit,
  vtkSmartPointer<vtkTextureObject>& texture, std::string& error,
  const std::function<void(double)>& progress, vtkTextureObject* reuse)
{
  texture = nullptr;
  const glm::ivec3 d = layout.Dims;
  if (!AtlasFitsContext(renWin, d, atlasLimit, error))
  {
    return false;
  }
  while (glGetError() != GL_NO_ERROR)
  {
  }
  texture = UploadAtlasBySlabs(renWin, h, layout, vertexCentred, progress, reuse);
  const bool ok = texture != nullptr;
  const GLenum glError = glGetError();
  if (!ok || glError != GL_NO_ERROR)
  {
    std::ostringstream msg;
    msg << "uploading the atlas texture ("
        << static_cast<double>(layout.TotalTexels) * sizeof(float) / (1024.0 * 1024.0)
        << " MiB) failed" << (glError == GL_OUT_OF_MEMORY ? ": out of GPU memory" : "")
        << (glError == GL_NO_ERROR ? ": the driver refused the texture allocation (out of GPU "
                                     "memory, or over one of its limits)"
                                   : "")
        << (glError != GL_NO_ERROR ? " (OpenGL error " + std::to_string(glError) + ")" : "");
    error = msg.str();
    texture = nullptr;
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<vtkSmartPointer<vtkTextureObject>> TakeReusablePages(
  std::vector<vtkSmartPointer<vtkTextureObject>>& pages, const amrsp::AtlasPages& layout)
{
  std::vector<vtkSmartPointer<vtkTextureObject>> old;
  old.swap(pages);
  std::vector<vtkSmartPointer<vtkTextureObject>> reusable(layout.Pages.size());
  for (std::size_t p = 0; p < old.size() && p < reusable.size(); ++p)
  {
    const glm::ivec3 d = layout.Pages[p].Dims;
    vtkTextureObject* t = old[p];
    if (t && t->GetReferenceCount() == 1 && static_cast<int>(t->GetWidth()) == d.x &&
      static_cast<int>(t->GetHeight()) == d.y && static_cast<int>(t->GetDepth()) == d.z)
    {
      reusable[p] = old[p];
    }
  }
  return reusable; // `old` releases the rest here
}

} // namespace vtkAMRMapperPackedAtlas
