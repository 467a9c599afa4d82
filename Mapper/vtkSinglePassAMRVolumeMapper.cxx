// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkSinglePassAMRVolumeMapperInternals.h"

#include "vtkAMRMapperConversion.h"
#include "vtkSinglePassAMRFrameBudget.h"
#include "vtkAMRMapperContextCapabilities.h"
#include "vtkSinglePassAMRGridStorage.h"
#include "vtkAMRMapperDepthCopy.h"
#include "vtkAMRMapperProxyBox.h"
#include "vtkSinglePassAMRRayLoopChoice.h"
#include "vtkAMRMapperTransferFunctionTable.h"
#include "vtkAMRMapperViewGeometry.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/RayCastingData.h"
#include "amrsp/RayLoop.h"
#include "amrsp/SampleStep.h"

#include "vtkCamera.h"
#include "vtkContourValues.h"
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
#include "vtkTextureObject.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"
#include "vtkAMRMapperOpenGL.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <list>
#include <memory>
#include <string>
#include <vector>

// The public modes are the private storage enums' values.
static_assert(
  static_cast<int>(amrsp::DataStorage::Auto) == vtkSinglePassAMRVolumeMapper::AUTO_STORAGE &&
    static_cast<int>(amrsp::DataStorage::PackedAtlas) ==
      vtkSinglePassAMRVolumeMapper::PACKED_ATLAS &&
    static_cast<int>(amrsp::DataStorage::BindlessTextures) ==
      vtkSinglePassAMRVolumeMapper::BINDLESS_TEXTURES &&
    static_cast<int>(amrsp::DataStorage::LinearBricks) ==
      vtkSinglePassAMRVolumeMapper::LINEAR_BRICKS,
  "DataStorageMode and amrsp::DataStorage differ");
static_assert(
  static_cast<int>(amrsp::RayLoop::Nested) == vtkSinglePassAMRVolumeMapper::NESTED_LOOPS &&
    static_cast<int>(amrsp::RayLoop::Flat) == vtkSinglePassAMRVolumeMapper::FLAT_LOOP &&
    static_cast<int>(amrsp::RayLoop::Auto) == vtkSinglePassAMRVolumeMapper::AUTO_LOOP,
  "RayLoops and amrsp::RayLoop differ");
static_assert(
  static_cast<int>(amrsp::RayCaster::Fragment) == vtkSinglePassAMRVolumeMapper::FRAGMENT_CASTER &&
    static_cast<int>(amrsp::RayCaster::Compute) == vtkSinglePassAMRVolumeMapper::COMPUTE_CASTER &&
    static_cast<int>(amrsp::RayCaster::Auto) == vtkSinglePassAMRVolumeMapper::AUTO_CASTER,
  "RayCasters and amrsp::RayCaster differ");
static_assert(
  static_cast<int>(amrsp::BindlessAccess::Auto) == vtkSinglePassAMRVolumeMapper::AUTO_ACCESS &&
    static_cast<int>(amrsp::BindlessAccess::Direct) ==
      vtkSinglePassAMRVolumeMapper::DIRECT_ACCESS &&
    static_cast<int>(amrsp::BindlessAccess::Waterfall) ==
      vtkSinglePassAMRVolumeMapper::WATERFALL_ACCESS,
  "BindlessAccessMode and amrsp::BindlessAccess differ");

//------------------------------------------------------------------------------
vtkStandardNewMacro(vtkSinglePassAMRVolumeMapper);

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeMapper::vtkSinglePassAMRVolumeMapper()
  : Internals(new vtkInternals(this))
{
}

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeMapper::~vtkSinglePassAMRVolumeMapper()
{
  delete this->Internals;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::BuildData(vtkOverlappingAMR* amr, const std::string& array,
  bool mayRefresh, bool& refreshed, std::string& error)
{
  vtkInternals& in = *this->Internals;
  refreshed = false;
  const bool keeping = this->MaximumKeptStepBytes > 0;
  if (!mayRefresh || !keeping)
  {
    in.KeptSteps.clear(); // other settings, or nothing to keep: the kept textures do not apply
  }
  if (keeping && mayRefresh)
  {
    auto kept = std::find_if(in.KeptSteps.begin(), in.KeptSteps.end(),
      [amr](const vtkInternals::KeptStep& k)
      { return k.Input == amr && k.InputMTime == amr->GetMTime(); });
    if (kept != in.KeptSteps.end())
    {
      // a step shown before: its build and textures are back, nothing is built or uploaded
      vtkInternals::KeptStep step = std::move(*kept);
      in.KeptSteps.erase(kept);
      if (in.CurrentIsUploaded())
      {
        in.KeepCurrent(std::move(in.Data), std::move(step.Storage));
      }
      else
      {
        in.Storage = std::move(step.Storage);
      }
      in.Data = std::move(step.Data);
      in.DataInput = amr;
      in.DataInputMTime = amr->GetMTime();
      in.PendingUpload = false;
      in.PendingValuesUpload = false;
      ++in.KeptStepHits;
      refreshed = true;
      return true;
    }
  }
  try
  {
    vtkAMRMapperConversion::ArraySelection selection;
    selection.Name = array;
    selection.Component = this->ArrayComponent;
    amrsp::Hierarchy h;
    // ProgressEvent: the build reports 0 to 1 (conversion, then PrepareRayCasting's steps), the
    // upload in the first render 0 to 1 again
    this->BeginProgressPhase(PROGRESS_BUILD, "converting the AMR blocks");
    if (!vtkAMRMapperConversion::FromOverlappingAMR(amr, selection, h, error))
    {
      in.Data = amrsp::RayCastingData();
      in.PendingUpload = false;
      in.PendingValuesUpload = false;
      return false;
    }
    this->LastBorrowedValues = 0;
    this->LastCopiedValues = 0;
    for (const amrsp::GridValues& values : h.Values)
    {
      (values.IsBorrowed() ? this->LastBorrowedValues : this->LastCopiedValues) +=
        static_cast<vtkIdType>(values.size());
    }
    if (mayRefresh && (in.Data.NodeBlocks || in.Data.PendingNodeBlocks.valid()) &&
      amrsp::SameStructure(in.Data.Data, h))
    {
      // a time step between regrids: the tree, its encoding and the brick layout stay
      this->SetProgressText("the new values' ranges");
      if (keeping && in.CurrentIsUploaded())
      {
        // the shown step keeps its textures; the new one shares their tree textures
        if (std::unique_ptr<vtkSinglePassAMRGridStorage> shared = in.Storage->ShareStructure())
        {
          in.KeepCurrent(in.Data, std::move(shared));
        }
      }
      amrsp::RefreshValues(in.Data, std::move(h), true);
      in.DataInput = amr;
      in.DataInputMTime = amr->GetMTime();
      in.PendingValuesUpload = !in.PendingUpload; // else the pending full upload sends them
      refreshed = true;
      this->UpdateProgress(1.0);
      return true;
    }
    if (keeping && in.CurrentIsUploaded())
    {
      in.KeepCurrent(std::move(in.Data),
        std::unique_ptr<vtkSinglePassAMRGridStorage>(new vtkSinglePassAMRGridStorage));
    }
    in.Data = amrsp::RayCastingData();
    in.PendingUpload = false;
    in.PendingValuesUpload = false;
    in.DataInput = amr;
    in.DataInputMTime = amr->GetMTime();
    in.Data = amrsp::PrepareRayCasting(
      std::move(h), this->MaximumAtlasSize,
      static_cast<int64_t>(this->MaximumAtlasPageBytes / amrsp::AtlasTexelBytes),
      [this](double f, const char* step)
      {
        this->SetProgressText(step);
        this->UpdateProgress(0.05 + 0.95 * f);
      },
      true, // the node ranges are computed beside the first render's upload
      this->BuildPacksBricks());
  }
  catch (const std::exception& e)
  {
    error = e.what();
    in.Data = amrsp::RayCastingData();
    in.PendingUpload = false;
    in.PendingValuesUpload = false;
    return false;
  }
  in.PendingUpload = true;
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::GetBuiltBounds(double bounds[6])
{
  const double* b = this->Internals->Data.Levels.Bounds;
  std::copy(b, b + 6, bounds);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  in.LastStorage = amrsp::DataStorage::None;
  in.LastAccess = amrsp::BindlessAccess::None;
  in.LastCaster = amrsp::RayCaster::Auto;
  in.StorageNote.clear();
  in.CasterNote.clear();
  vtkOpenGLRenderWindow* renWin = nullptr;
  vtkOverlappingAMR* amr = this->BeginFrame(ren, renWin);
  if (!amr)
  {
    return;
  }
  // data: rebuilt only when the input or the array selection changed
  if (!this->EnsureBuilt(amr))
  {
    this->ReportError(this->GetBuildError());
    return;
  }
  vtkSinglePassAMRFrameSettings frame;
  vtkVolumeProperty* property = vol->GetProperty();
  if (!in.PrepareStorage(renWin, amr, frame) || !in.PrepareAppearance(renWin, property, frame))
  {
    return;
  }
  vtkAMRMapperViewGeometry::ViewGeometry view;
  std::string viewError;
  if (!vtkAMRMapperViewGeometry::ComputeViewGeometry(ren, vol, view, viewError))
  {
    this->ReportError(viewError);
    return;
  }
  const vtkSinglePassAMRFrameBudget::Settings budget{ this->AutoAdjustSampleDistances != 0,
    this->ImageSampleDistance, this->MinimumImageSampleDistance, this->MaximumImageSampleDistance,
    this->InteractiveAdjustSampleDistances != 0 };
  frame.Quality =
    in.Budget.Begin(vol, budget, view.Width, view.Height, this->GetBuildTime().GetMTime());
  // the rays' image: the viewport, or at (0, 0) the reduced image of this frame
  vtkAMRMapperViewGeometry::ViewGeometry rays = view;
  if (frame.Reduced())
  {
    rays.X0 = rays.Y0 = 0;
    vtkSinglePassAMRFrameBudget::ReducedSize(
      view.Width, view.Height, frame.Quality.ImageSampleDistance, rays.Width, rays.Height);
  }
  // an offscreen image for the rays: the reduced image (bilinear), or the compute caster's
  // viewport-sized one (nearest); the fragment caster draws a full frame into the frame itself
  const bool compute = frame.Caster == amrsp::RayCaster::Compute;
  const bool offscreen = frame.Reduced() || compute;
  if (offscreen &&
    !in.RaysImage(frame.Reduced())
       .Ensure(renWin, rays.Width, rays.Height, frame.Reduced(), viewError))
  {
    this->ReportError(viewError);
    return;
  }
  vtkShaderProgram* program = in.ReadyShader(renWin, vol, frame);
  if (!program)
  {
    return;
  }
  if (!compute && !in.BindProxyBox(program))
  {
    return;
  }
  if (frame.UseDepth)
  {
    in.Depth.CopyFrom(renWin, view); // leaves the depth texture active
  }
  if (!in.UpdateEmptySpaceFlags(renWin, frame))
  {
    return;
  }
  in.ActivateTextures(program, frame);
  in.SetDataUniforms(program, ren, property, rays, frame);
  if (frame.Reduced() && frame.UseDepth)
  {
    const float scale[2] = { static_cast<float>(view.Width) / static_cast<float>(rays.Width),
      static_cast<float>(view.Height) / static_cast<float>(rays.Height) };
    program->SetUniform2f("amrspDepthScale", scale);
  }
  if (frame.Shade || frame.Shadows || frame.Blend == amrsp::BlendMode::IsoSurface)
  {
    in.SetLightingUniforms(program, ren, vol, property, frame);
  }
  if (compute)
  {
    in.DispatchRays(program, rays, frame.Reduced());
  }
  else
  {
    in.Budget.DrawRays(
      renWin, frame.Reduced(), [&in, renWin, &view] { in.DrawBackFaces(renWin, view); });
  }
  in.DeactivateTextures(frame);
  in.LastStorage = frame.Storage;
  in.LastAccess = frame.Access;
  in.LastRopes = frame.Ropes && this->LODThreshold <= 0.0;
  in.LastFlatLoop = frame.FlatLoop;
  in.LastCaster = frame.Caster;
  if (offscreen && !in.RaysImage(frame.Reduced()).CompositeOver(renWin, viewError))
  {
    this->ReportError(viewError);
    return;
  }
  in.Budget.End(budget, frame.Quality);
  vtkOpenGLCheckErrorMacro("failed after vtkSinglePassAMRVolumeMapper::Render");
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::PrepareStorage(
  vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr, vtkSinglePassAMRFrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  this->TrimKeptSteps(static_cast<long long>(self->MaximumKeptStepBytes));
  this->Storage->SetLinearPageBytes(self->MaximumAtlasPageBytes);
  vtkSinglePassAMRStorageRequest request;
  request.Storage = static_cast<amrsp::DataStorage>(self->DataStorage);
  request.Access = static_cast<amrsp::BindlessAccess>(self->BindlessAccess);
  request.AutoBindlessWaste = self->AutoBindlessWaste;
  request.AutoLinearBytes = self->AutoLinearBytes;
  request.NewTextures = this->PendingUpload;
  const vtkSinglePassAMRStorageChoice choice =
    this->Storage->Choose(renWin, this->Data, request, self->MaximumAtlasSize);
  if (!choice.FallbackReason.empty())
  {
    this->StorageNote = choice.FallbackReason;
    self->WarnOnce("bindless textures requested, but " + choice.FallbackReason +
      ": rendering with the packed atlas instead");
  }
  if (choice.Storage == amrsp::DataStorage::None)
  {
    self->ReportError(choice.Error);
    return false;
  }
  frame.Storage = choice.Storage;
  frame.Access = choice.Access;
  const bool uploaded = this->Storage->IsUploaded(renWin, frame.Storage, self->MaximumAtlasSize);
  if (!this->PendingUpload && this->PendingValuesUpload && uploaded)
  {
    return this->UploadValues(renWin);
  }
  if (!this->PendingUpload && !this->PendingValuesUpload && uploaded)
  {
    return true;
  }
  if (!this->PendingUpload)
  {
    // the CPU copies were dropped after an upload of another storage or to another context:
    // rebuild them
    if (!self->Rebuild(amr))
    {
      self->ReportError(self->GetBuildError());
      return false;
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  self->BeginProgressPhase(PROGRESS_UPLOAD, "uploading the grid data");
  if (!this->Storage->Upload(renWin, frame.Storage, self->MaximumAtlasSize, this->Data, error,
        [self](double f) { self->UpdateProgress(f); }))
  {
    // keep the CPU data: a later context (or a smaller input) may succeed
    self->ReportError(error);
    return false;
  }
  self->UpdateProgress(1.0);
  this->Data.FreeUploadData();
  this->PendingUpload = false;
  try
  {
    // the one join of the build's deferred node ranges: every build is followed by this upload
    this->Data.WaitForNodeRanges();
  }
  catch (const std::exception& e)
  {
    self->ReportError(std::string("computing the value ranges failed: ") + e.what());
    return false;
  }
  self->UploadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::UploadValues(vtkOpenGLRenderWindow* renWin)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  const auto t0 = std::chrono::steady_clock::now();
  std::string error;
  self->BeginProgressPhase(PROGRESS_UPLOAD, "uploading the new time step's grid data");
  const bool ok = this->Storage->UploadValues(
    renWin, this->Data, error, [self](double f) { self->UpdateProgress(f); });
  this->PendingValuesUpload = false;
  if (!ok)
  {
    // the CPU copies of the tree are gone: the next frame builds from the input again
    self->InvalidateBuild();
    self->ReportError(error);
    return false;
  }
  self->UpdateProgress(1.0);
  this->Data.FreeUploadData();
  try
  {
    this->Data.WaitForNodeRanges();
  }
  catch (const std::exception& e)
  {
    self->ReportError(std::string("computing the value ranges failed: ") + e.what());
    return false;
  }
  self->UploadSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  vtkInternals& in = *this->Internals;
  in.Storage->ReleaseGraphicsResources(window);
  for (vtkInternals::KeptStep& kept : in.KeptSteps)
  {
    kept.Storage->ReleaseGraphicsResources(window);
  }
  in.KeptSteps.clear();
  in.Budget.Image.ReleaseGraphicsResources(window);
  in.ComputeImage.ReleaseGraphicsResources(window);
  in.FreeComputePrograms(window);
  in.Depth.ReleaseGraphicsResources(window);
  in.Transfer.ReleaseGraphicsResources(window);
  in.BoxBuffer->ReleaseGraphicsResources();
  in.BoxArray->ReleaseGraphicsResources();
  in.BoxArrayProgram = nullptr;
  if (!in.PendingUpload)
  {
    // the CPU copies were freed after the upload: rebuild from the input next time
    this->InvalidateBuild();
  }
  this->Superclass::ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::IsBindlessSupported(vtkRenderWindow* window, std::string* why)
{
  std::string reason;
  bool supported = IsRenderSupported(window, &reason);
  if (supported)
  {
    vtkAMRMapperContextCapabilities capabilities;
    capabilities.Update(vtkOpenGLRenderWindow::SafeDownCast(window));
    supported = capabilities.ResolveAccess(amrsp::BindlessAccess::Auto, reason) !=
      amrsp::BindlessAccess::None;
  }
  if (!supported && why)
  {
    *why = reason;
  }
  return supported;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  const vtkInternals& in = *this->Internals;
  os << indent << "LODThreshold: " << this->LODThreshold << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << " (minimum "
     << this->MinimumImageSampleDistance << ", maximum " << this->MaximumImageSampleDistance
     << ")\n";
  os << indent << "InteractiveAdjustSampleDistances: " << this->InteractiveAdjustSampleDistances
     << "\n";
  os << indent << "DataStorage: " << GetDataStorageName(this->DataStorage) << "\n";
  os << indent << "BindlessAccess: " << GetBindlessAccessName(this->BindlessAccess) << "\n";
  os << indent << "AutoBindlessWaste: " << this->AutoBindlessWaste << "\n";
  os << indent << "AutoLinearBytes: " << this->AutoLinearBytes << "\n";
  os << indent << "LastDataStorage: " << amrsp::DataStorageName(in.LastStorage)
     << ", LastBindlessAccess: " << amrsp::BindlessAccessName(in.LastAccess) << "\n";
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "EmptySpaceSkipping: " << (this->EmptySpaceSkipping ? "on" : "off") << "\n";
  os << indent << "AccelerationCountsOutput: " << (this->AccelerationCountsOutput ? "on" : "off")
     << "\n";
  os << indent << "LoopCountOutput: " << this->LoopCountOutput << "\n";
  os << indent << "Ropes: " << (this->Ropes ? "on" : "off") << "\n";
  os << indent << "OccupancyProbe: " << (this->OccupancyProbe ? "on" : "off") << "\n";
  os << indent << "RayLoop: " << amrsp::RayLoopName(static_cast<amrsp::RayLoop>(this->RayLoop))
     << "\n";
  os << indent
     << "RayCaster: " << amrsp::RayCasterName(static_cast<amrsp::RayCaster>(this->RayCaster))
     << "\n";
  os << indent << "DiagnosticAblation: " << this->DiagnosticAblation << " ("
     << this->DiagnosticAblationSamples << " samples)\n";
  os << indent
     << "CellInterpolation: " << (this->CellInterpolation == SMOOTH_CELL ? "smooth" : "nearest")
     << "\n";
  os << indent << "TransparentDataNodes: " << in.TransparentDataNodes << "\n";
  os << indent << "Shadows: " << (this->Shadows ? "on" : "off")
     << ", ShadowSampleDistance: " << this->ShadowSampleDistance << "\n";
  os << indent << "KdNodes: " << in.Data.KdNodes << ", DataNodes: " << in.Data.DataNodes << "\n";
  const glm::ivec3 d = in.Data.AtlasDims;
  os << indent << "AtlasDimensions: " << d.x << " x " << d.y << " x " << d.z << "\n";
  os << indent << "AtlasPages: " << in.Data.PageDims.size() << "\n";
}
