// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRLinearBricks.h"

#include "vtkSinglePassAMRShaderVariant.h"

#include "vtkAMRMapperTextures.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/LinearBricks.h"

#include "vtkOpenGLRenderWindow.h"
#include "vtkShaderProgram.h"
#include "vtkTextureObject.h"
#include "vtkAMRMapperOpenGL.h"

#include <algorithm>
#include <stdexcept>

namespace
{
// Rows of Width texels, texels 0 after `layout`'s bricks, as a 2D R32F texture of `renWin`.
vtkSmartPointer<vtkTextureObject> MakePage(vtkOpenGLRenderWindow* renWin, int width, int rows)
{
  auto page = vtkSmartPointer<vtkTextureObject>::New();
  page->SetContext(renWin);
  page->SetInternalFormat(GL_R32F);
  page->SetFormat(GL_RED);
  page->SetDataType(GL_FLOAT);
  page->SetMinificationFilter(vtkTextureObject::Nearest);
  page->SetMagnificationFilter(vtkTextureObject::Nearest);
  page->SetWrapS(vtkTextureObject::ClampToEdge);
  page->SetWrapT(vtkTextureObject::ClampToEdge);
  if (!page->Create2DFromRaw(
        static_cast<unsigned int>(width), static_cast<unsigned int>(rows), 1, VTK_FLOAT, nullptr))
  {
    return nullptr;
  }
  // A refused allocation leaves a texture without storage, which Create2DFromRaw does not report
  // (VTK's own error check may have read the GL_OUT_OF_MEMORY already): its slabs would upload
  // nowhere and the frame would be black. The texture's size tells.
  GLint allocated[2] = { 0, 0 };
  page->Activate();
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_WIDTH, &allocated[0]);
  glGetTexLevelParameteriv(GL_TEXTURE_2D, 0, GL_TEXTURE_HEIGHT, &allocated[1]);
  page->Deactivate();
  return allocated[0] == width && allocated[1] == rows ? page : nullptr;
}
} // namespace

//------------------------------------------------------------------------------
int vtkSinglePassAMRLinearBricks::PageShape(
  vtkOpenGLRenderWindow* renWin, long long maxPageBytes, int& widthLog2, int& maxRows)
{
  const int maxSize = std::max(1, vtkTextureObject::GetMaximumTextureSize(renWin));
  widthLog2 = 0;
  while (widthLog2 < 14 && (2 << widthLog2) <= maxSize)
  {
    ++widthLog2;
  }
  maxRows = std::min(maxSize, 1 << (28 - widthLog2));
  if (maxPageBytes > 0)
  {
    const long long rows = maxPageBytes / static_cast<long long>(sizeof(float)) >> widthLog2;
    maxRows = static_cast<int>(std::max(1LL, std::min<long long>(maxRows, rows)));
  }
  return maxSize;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRLinearBricks::Fits(vtkOpenGLRenderWindow* renWin, const amrsp::Hierarchy& h,
  bool vertexCentred, long long maxPageBytes)
{
  int widthLog2 = 0;
  int maxRows = 0;
  PageShape(renWin, maxPageBytes, widthLog2, maxRows);
  // the layout leaves less than one brick unused at the end of each page
  const long long capacity = static_cast<long long>(maxRows) << widthLog2;
  long long texels = 0;
  long long largest = 0;
  for (const glm::ivec3& e : amrsp::BrickExtents(h, vertexCentred))
  {
    const long long t = static_cast<long long>(e.x) * e.y * e.z;
    texels += t;
    largest = std::max(largest, t);
  }
  return largest <= capacity &&
    texels + amrsp::MaxLinearPages * largest <= amrsp::MaxLinearPages * capacity;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRLinearBricks::UploadBricks(vtkOpenGLRenderWindow* renWin,
  const amrsp::Hierarchy& h, bool vertexCentred, long long maxPageBytes, std::string& error,
  const std::function<void(double)>& progress)
{
  // this object's previous pages, overwritten in place where nothing else holds them (a time
  // step's new values in the same layout: no allocation, no first-touch of fresh driver memory)
  std::vector<vtkSmartPointer<vtkTextureObject>> previous;
  previous.swap(this->Pages);
  this->Clear();
  int widthLog2 = 0;
  int maxRows = 0;
  const int maxSize = PageShape(renWin, maxPageBytes, widthLog2, maxRows);
  amrsp::LinearBrickLayout layout;
  try
  {
    layout = amrsp::LayOutLinearBricks(amrsp::BrickExtents(h, vertexCentred), widthLog2, maxRows);
  }
  catch (const std::exception& e)
  {
    error = std::string("the linear storage cannot hold the grid data: ") + e.what() +
      " (GL_MAX_TEXTURE_SIZE = " + std::to_string(maxSize) + ")";
    return false;
  }
  if (h.Values.size() != layout.Base.size())
  {
    error = "the linear storage has " + std::to_string(layout.Base.size()) +
      " bricks and the hierarchy " + std::to_string(h.Values.size()) + " value arrays";
    return false;
  }
  const int width = 1 << widthLog2;
  const double total = static_cast<double>(layout.TotalTexels());
  double done = 0.0;
  // Each brick goes straight from its values to its rectangles of the page (no staging copy):
  // full rows are contiguous in both, so a rectangle needs no unpack row length.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  std::size_t g = 0;
  for (std::size_t p = 0; p < layout.PageRows.size(); ++p)
  {
    const int rows = layout.PageRows[p];
    const bool reusable = p < previous.size() && previous[p]->GetReferenceCount() == 1 &&
      static_cast<int>(previous[p]->GetWidth()) == width &&
      static_cast<int>(previous[p]->GetHeight()) == rows;
    vtkSmartPointer<vtkTextureObject> page = reusable ? previous[p] : MakePage(renWin, width, rows);
    if (!page)
    {
      error = "the driver refused a linear page of " + std::to_string(width) + " x " +
        std::to_string(rows) + " R32F texels (out of GPU memory, or over one of its limits)";
      this->Clear();
      return false;
    }
    page->Activate(); // bound to a texture unit of its own for the uploads
    for (; g < layout.Base.size() && layout.PageOfGrid[g] == static_cast<int>(p); ++g)
    {
      const glm::ivec3 e = layout.Extents[g];
      if (h.Values[g].size() < static_cast<std::size_t>(e.x) * e.y * e.z)
      {
        error = "grid " + std::to_string(g) + " has fewer values than its brick";
        page->Deactivate();
        this->Clear();
        return false;
      }
      const float* values = h.Values[g].data();
      for (const amrsp::LinearRun& run : amrsp::LinearBrickRuns(layout, g))
      {
        glTexSubImage2D(GL_TEXTURE_2D, 0, run.X, run.Y, run.Width, run.Rows, GL_RED, GL_FLOAT,
          values + run.FirstValue);
        done += static_cast<double>(run.Width) * run.Rows;
      }
      if (progress && (g & 1023) == 0)
      {
        progress(done / total);
      }
    }
    page->Deactivate();
    this->Pages.push_back(page);
  }
  if (progress)
  {
    progress(1.0);
  }
  this->Table = vtkAMRMapperTextures::MakeIntegerTexture(renWin, amrsp::LinearBrickTable(layout));
  if (!this->Table)
  {
    error = "the driver refused the linear storage's brick table";
    this->Clear();
    return false;
  }
  this->WidthLog2 = widthLog2;
  this->Bytes = static_cast<long long>(total) * static_cast<long long>(amrsp::AtlasTexelBytes) +
    static_cast<long long>(amrsp::HandleTextureBytes(layout.Base.size()));
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRLinearBricks::Activate(vtkShaderProgram* program)
{
  for (std::size_t p = 0; p < this->Pages.size(); ++p)
  {
    this->Pages[p]->Activate();
    program->SetUniformi(
      (p == 0 ? std::string("amrspLinear") : "amrspLinear" + std::to_string(p)).c_str(),
      this->Pages[p]->GetTextureUnit());
  }
  this->Table->Activate();
  program->SetUniformi("amrspBrickTable", this->Table->GetTextureUnit());
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRLinearBricks::Upload(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  this->Clear(); // new pages
  return this->UploadBricks(
    renWin, data.Data, data.VertexCentred, this->MaximumPageBytes, error, progress);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRLinearBricks::UploadValues(vtkOpenGLRenderWindow* renWin,
  const amrsp::RayCastingData& data, std::string& error,
  const std::function<void(double)>& progress)
{
  return this->UploadBricks(
    renWin, data.Data, data.VertexCentred, this->MaximumPageBytes, error, progress);
}

//------------------------------------------------------------------------------
std::unique_ptr<vtkSinglePassAMRGridData> vtkSinglePassAMRLinearBricks::NewForAnotherStep() const
{
  std::unique_ptr<vtkSinglePassAMRLinearBricks> other(new vtkSinglePassAMRLinearBricks);
  other->MaximumPageBytes = this->MaximumPageBytes;
  return std::unique_ptr<vtkSinglePassAMRGridData>(other.release());
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRLinearBricks::Describe(vtkSinglePassAMRShaderVariant& variant) const
{
  variant.Storage = amrsp::DataStorage::LinearBricks;
  variant.LinearPages = this->GetNumberOfPages();
  variant.LinearWidthLog2 = this->WidthLog2;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRLinearBricks::Deactivate()
{
  for (vtkTextureObject* page : this->Pages)
  {
    page->Deactivate();
  }
  this->Table->Deactivate();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRLinearBricks::ReleaseGraphicsResources(vtkWindow* window)
{
  for (vtkTextureObject* page : this->Pages)
  {
    page->ReleaseGraphicsResources(window);
  }
  if (this->Table)
  {
    this->Table->ReleaseGraphicsResources(window);
  }
  this->Clear();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRLinearBricks::Clear()
{
  this->Pages.clear();
  this->Table = nullptr;
  this->Bytes = 0;
}
