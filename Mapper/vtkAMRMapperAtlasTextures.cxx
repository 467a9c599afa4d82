// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperAtlasTextures.h"

#include "vtkAMRMapperPackedAtlas.h"
#include "vtkSinglePassAMRShaderVariant.h"

#include "amrsp/BrickAtlas.h"

#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"

//------------------------------------------------------------------------------
bool vtkAMRMapperAtlasTextures::UploadPages(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, const amrsp::AtlasPages& pages, bool vertexCentred, int atlasLimit,
  bool reuse, std::string& error, const std::function<void(double)>& progress)
{
  std::vector<vtkSmartPointer<vtkTextureObject>> reusable;
  if (reuse)
  {
    reusable = vtkAMRMapperPackedAtlas::TakeReusablePages(this->Pages, pages);
  }
  this->Pages.clear();
  this->Bytes = 0;
  const double share = 1.0 / static_cast<double>(std::max<std::size_t>(1, pages.Pages.size()));
  for (std::size_t p = 0; p < pages.Pages.size(); ++p)
  {
    vtkSmartPointer<vtkTextureObject> page;
    vtkTextureObject* old = p < reusable.size() ? reusable[p].Get() : nullptr;
    if (!vtkAMRMapperPackedAtlas::UploadAtlas(
          renWin, pages.Pages.size() == 1 ? h : amrsp::PageHierarchy(h, pages, static_cast<int>(p)),
          pages.Pages[p], vertexCentred, atlasLimit, page, error,
          [&progress, p, share](double f)
          {
            if (progress)
            {
              progress((static_cast<double>(p) + f) * share);
            }
          },
          old))
    {
      this->Pages.clear();
      return false;
    }
    this->Pages.push_back(page);
  }
  if (this->Pages.empty())
  {
    error = "the packed atlas has no page";
    return false;
  }
  this->Bytes =
    static_cast<long long>(pages.TotalTexels()) * static_cast<long long>(amrsp::AtlasTexelBytes);
  return true;
}

//------------------------------------------------------------------------------
bool vtkAMRMapperAtlasTextures::Upload(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  return this->UploadPages(
    renWin, data.Data, data.Atlas, data.VertexCentred, this->AtlasLimit, false, error, progress);
}

//------------------------------------------------------------------------------
bool vtkAMRMapperAtlasTextures::UploadValues(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  // the previous step's pages, overwritten in place where no kept step holds them
  return this->UploadPages(
    renWin, data.Data, data.Atlas, data.VertexCentred, this->AtlasLimit, true, error, progress);
}

//------------------------------------------------------------------------------
std::unique_ptr<vtkSinglePassAMRGridData> vtkAMRMapperAtlasTextures::NewForAnotherStep() const
{
  std::unique_ptr<vtkAMRMapperAtlasTextures> other(new vtkAMRMapperAtlasTextures);
  other->AtlasLimit = this->AtlasLimit;
  return std::unique_ptr<vtkSinglePassAMRGridData>(other.release());
}

//------------------------------------------------------------------------------
void vtkAMRMapperAtlasTextures::Describe(vtkSinglePassAMRShaderVariant& variant) const
{
  variant.Storage = amrsp::DataStorage::PackedAtlas;
  variant.AtlasPages = static_cast<int>(this->Pages.size());
}

//------------------------------------------------------------------------------
void vtkAMRMapperAtlasTextures::ActivatePages()
{
  for (vtkTextureObject* page : this->Pages)
  {
    page->Activate();
  }
}

//------------------------------------------------------------------------------
void vtkAMRMapperAtlasTextures::Activate(vtkShaderProgram* program)
{
  // the atlas pages: amrspAtlas, then amrspAtlas1, amrspAtlas2, ...
  this->ActivatePages();
  std::vector<float> sizes;
  for (std::size_t p = 0; p < this->Pages.size(); ++p)
  {
    vtkTextureObject* page = this->Pages[p];
    program->SetUniformi(
      (p == 0 ? std::string("amrspAtlas") : "amrspAtlas" + std::to_string(p)).c_str(),
      page->GetTextureUnit());
    sizes.insert(
      sizes.end(), { float(page->GetWidth()), float(page->GetHeight()), float(page->GetDepth()) });
  }
  program->SetUniform3f("amrspAtlasSize", sizes.data());
  if (this->Pages.size() > 1)
  {
    program->SetUniform3fv(
      "amrspAtlasPageSize", static_cast<int>(this->Pages.size()), sizes.data());
  }
}

//------------------------------------------------------------------------------
void vtkAMRMapperAtlasTextures::Deactivate()
{
  for (vtkTextureObject* page : this->Pages)
  {
    page->Deactivate();
  }
}

//------------------------------------------------------------------------------
void vtkAMRMapperAtlasTextures::ReleaseGraphicsResources(vtkWindow* window)
{
  for (vtkSmartPointer<vtkTextureObject>& page : this->Pages)
  {
    page->ReleaseGraphicsResources(window);
  }
  this->Pages.clear();
  this->Bytes = 0;
}
