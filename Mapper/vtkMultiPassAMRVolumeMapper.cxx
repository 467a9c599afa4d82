// SPDX-License-Identifier: BSD-3-Clause
#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkMultiPassAMRVolumeMapperInternals.h"

#include "vtkAMRMapperDepthCopy.h"
#include "vtkAMRMapperPackedAtlas.h"
#include "vtkAMRMapperProxyBox.h"
#include "vtkAMRMapperScopedBlendedDraw.h"
#include "vtkAMRMapperShaderComposer.h"
#include "vtkAMRMapperTransferFunctionTable.h"
#include "vtkAMRMapperViewGeometry.h"

#include "amrsp/MultiPassNodes.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/IntegerMath.h"
#include "amrsp/SampleStep.h"
#include "amrsp/KdTree.h"

#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLError.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLShaderCache.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLVertexArrayObject.h"
#include "vtkOverlappingAMR.h"
#include "vtkRenderer.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkAMRMapperOffscreenImage.h"
#include "vtkAMRMapperOpenGL.h"

// GLSL embedded at build time (vtk_encode_string)
#include "amrsp_MultiPassAMR_frag_glsl.h"
#include "amrsp_MultiPassAMR_vert_glsl.h"
#include "amrsp_BrickSample_glsl.h"
#include "amrsp_RayCommon_glsl.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::vtkInternals::Build(vtkOverlappingAMR* amr,
  const std::string& array, int component, int packLimit, int64_t maxPageTexels, bool mayRefresh,
  bool& refreshed, std::string& error)
{
  const bool ok = vtkAMRMapperPackedAtlas::RefreshPackedHierarchy(
    amr, array, component, packLimit, maxPageTexels, mayRefresh, this->Data, refreshed, error);
  if (ok && refreshed)
  {
    return true; // a time step of the same structure: the nodes to draw are the same
  }
  this->Nodes = amrsp::MultiPassNodes();
  if (!ok)
  {
    return false;
  }
  this->Nodes = amrsp::ListMultiPassNodes(this->Data.Structure, this->Data.Tree, this->Data.Atlas);
  this->TextureBytes = this->Data.Atlas.TotalTexels() * static_cast<long long>(sizeof(float));
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::vtkInternals::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Depth.ReleaseGraphicsResources(window);
  this->Atlas.ReleaseGraphicsResources(window);
  this->Accumulation.ReleaseGraphicsResources(window);
  this->Transfer.ReleaseGraphicsResources(window);
  this->CubeBuffer->ReleaseGraphicsResources();
  this->CubeArray->ReleaseGraphicsResources();
  this->CubeArrayProgram = nullptr;
  this->Context = nullptr;
}

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkMultiPassAMRVolumeMapper);

//------------------------------------------------------------------------------
vtkMultiPassAMRVolumeMapper::vtkMultiPassAMRVolumeMapper()
  : Internals(new vtkInternals(this))
{
}

//------------------------------------------------------------------------------
vtkMultiPassAMRVolumeMapper::~vtkMultiPassAMRVolumeMapper()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::BuildData(vtkOverlappingAMR* amr, const std::string& array,
  bool mayRefresh, bool& refreshed, std::string& error)
{
  // ProgressEvent: 0 and 1 around the build; the upload in the first render 0 to 1 again
  this->BeginProgressPhase(PROGRESS_BUILD, "converting the AMR blocks, kD-tree and packing");
  const bool built =
    this->Internals->Build(amr, array, this->ArrayComponent, this->MaximumAtlasSize,
      static_cast<int64_t>(this->MaximumAtlasPageBytes / amrsp::AtlasTexelBytes), mayRefresh,
      refreshed, error);
  this->UpdateProgress(1.0);
  return built;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::GetBuiltBounds(double bounds[6])
{
  const double* b = this->Internals->Data.Bounds;
  std::copy(b, b + 6, bounds);
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  in.Passes = 0;
  vtkOpenGLRenderWindow* renWin = nullptr;
  vtkOverlappingAMR* amr = this->BeginFrame(ren, renWin);
  if (!amr)
  {
    return;
  }
  if (this->GetBlendMode() != vtkVolumeMapper::COMPOSITE_BLEND)
  {
    this->ReportError("the multi-pass method implements composite blending only (blend mode " +
      std::to_string(this->GetBlendMode()) + " requested)");
    return;
  }
  // data: rebuilt only when the input, the array selection or the packing limit changed
  if (!this->EnsureBuilt(amr))
  {
    this->ReportError(this->GetBuildError());
    return;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  if (!property)
  {
    this->ReportError("the volume has no vtkVolumeProperty");
    return;
  }
  if (!in.UploadAtlas(renWin, amr))
  {
    return;
  }
  if (!in.Transfer.Update(renWin, property, in.Data.ScalarRange, this->GetBuildTime()))
  {
    this->ReportError("uploading the transfer-function table failed");
    return;
  }
  if (!in.Transfer.GetWarning().empty())
  {
    this->WarnOnce(in.Transfer.GetWarning());
  }
  vtkShaderProgram* program = in.ReadyShaders(renWin, vol);
  if (!program)
  {
    return;
  }
  vtkAMRMapperViewGeometry::ViewGeometry view;
  std::string error;
  if (!vtkAMRMapperViewGeometry::ComputeViewGeometry(ren, vol, view, error) ||
    !in.Accumulation.Ensure(renWin, view.Width, view.Height, false, error))
  {
    this->ReportError(error);
    return;
  }
  if (!in.BindCube(program))
  {
    return;
  }
  // the opaque geometry's depth, read before the accumulation target is bound
  if (this->UseDepthBuffer)
  {
    in.Depth.CopyFrom(renWin, view); // leaves the depth texture active
  }
  in.OrderNodes(view); // CPU: the data nodes front to back for this camera
  in.SetFrameUniforms(program, property, view);
  std::vector<float> steps;
  for (double edge : in.Data.LevelMinEdge)
  {
    steps.push_back(static_cast<float>(amrsp::LevelSampleStep(this->SampleDistanceFactor, edge)));
  }
  glm::vec3 clipLo, clipHi;
  in.ClipBox(clipLo, clipHi);
  in.DrawNodes(renWin->GetState(), program, view, steps, clipLo, clipHi);
  in.Atlas.Deactivate();
  in.Transfer.GetTexture()->Deactivate();
  if (this->UseDepthBuffer)
  {
    in.Depth.Depth->Deactivate();
  }
  // the accumulated image over the renderer's framebuffer (premultiplied "over")
  if (!in.Accumulation.CompositeOver(renWin, error))
  {
    this->ReportError(error);
    return;
  }
  vtkOpenGLCheckErrorMacro("failed after vtkMultiPassAMRVolumeMapper::Render");
}

//------------------------------------------------------------------------------
bool vtkMultiPassAMRVolumeMapper::vtkInternals::UploadAtlas(
  vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr)
{
  vtkMultiPassAMRVolumeMapper* self = this->Self;
  if (this->Atlas.GetNumberOfPages() > 0 && this->Context == renWin &&
    this->UploadLimit == self->MaximumAtlasSize &&
    this->UploadedBuildTime == self->GetBuildTime().GetMTime())
  {
    return true;
  }
  this->UploadLimit = self->MaximumAtlasSize;
  // the CPU copy is dropped after an upload: uploading to another context rebuilds it
  if (!this->Data.Structure.HasValues() && !self->Rebuild(amr))
  {
    self->ReportError(self->GetBuildError());
    return false;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  // the previous pages, overwritten in place when of the same size in the same context (a time
  // step's new values: no allocation, no first-touch of fresh driver memory)
  self->BeginProgressPhase(PROGRESS_UPLOAD, "uploading the atlas");
  if (!this->Atlas.UploadPages(renWin, this->Data.Structure, this->Data.Atlas,
        this->Data.VertexCentred, self->MaximumAtlasSize, this->Context == renWin, error,
        [self](double f) { self->UpdateProgress(f); }))
  {
    // keep the CPU data: a later context (or a smaller input) may succeed
    self->ReportError(error);
    return false;
  }
  std::vector<amrsp::GridValues>().swap(this->Data.Structure.Values); // the atlas holds them
  this->Context = renWin;
  this->UploadedBuildTime = self->GetBuildTime().GetMTime();
  self->UploadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->ReleaseGraphicsResources(window);
  if (!this->Internals->Data.Structure.HasValues())
  {
    // the CPU copy of the atlas was freed after the upload: rebuild from the input next time
    this->InvalidateBuild();
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::GetAtlasDimensions(int dims[3])
{
  const glm::ivec3 d =
    (this->Internals->Data.Atlas.Pages.empty() ? glm::ivec3(0)
                                               : this->Internals->Data.Atlas.Pages[0].Dims);
  dims[0] = d.x;
  dims[1] = d.y;
  dims[2] = d.z;
}

long long vtkMultiPassAMRVolumeMapper::GetTextureBytes()
{
  return this->Internals->TextureBytes;
}

long long vtkMultiPassAMRVolumeMapper::GetAccumulationBytes()
{
  const vtkAMRMapperOffscreenImage& a = this->Internals->Accumulation;
  return 16LL * a.GetWidth() * a.GetHeight();
}

long long vtkMultiPassAMRVolumeMapper::GetNumberOfKdNodes()
{
  return static_cast<long long>(this->Internals->Data.Tree.Nodes.size());
}

long long vtkMultiPassAMRVolumeMapper::GetNumberOfDataNodes()
{
  return this->Internals->Nodes.DataNodes;
}

long long vtkMultiPassAMRVolumeMapper::GetLastNumberOfPasses()
{
  return this->Internals->Passes;
}

double vtkMultiPassAMRVolumeMapper::GetLastOrderSeconds()
{
  return this->Internals->OrderSeconds;
}

//------------------------------------------------------------------------------
void vtkMultiPassAMRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "KdNodes: " << in.Data.Tree.Nodes.size() << ", DataNodes: " << in.Nodes.DataNodes
     << ", drawn leaves: " << in.Nodes.Draws.size() << "\n";
  const glm::ivec3 d = (in.Data.Atlas.Pages.empty() ? glm::ivec3(0) : in.Data.Atlas.Pages[0].Dims);
  os << indent << "AtlasDimensions: " << d.x << " x " << d.y << " x " << d.z << "\n";
  os << indent << "LastNumberOfPasses: " << in.Passes << "\n";
}
