// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkSinglePassAMRConversion.h"
#include "vtkSinglePassAMRFrameBudget.h"
#include "vtkSinglePassAMRGridStorage.h"
#include "vtkSinglePassAMRDepthCopy.h"
#include "vtkSinglePassAMRProxyBox.h"
#include "vtkSinglePassAMRScopedBlendedDraw.h"
#include "vtkSinglePassAMRShaderComposer.h"
#include "vtkSinglePassAMRTransferFunctionTable.h"
#include "vtkSinglePassAMRViewGeometry.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/RayCastingData.h"
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
#include "vtkSinglePassAMROpenGL.h"

// GLSL embedded at build time (vtk_encode_string)
#include "amrsp_BrickSample_glsl.h"
#include "amrsp_KdTreeLayout_glsl.h"
#include "amrsp_RayCommon_glsl.h"
#include "amrsp_RaySteps_glsl.h"
#include "amrsp_Shading_glsl.h"
#include "amrsp_SmoothCells_glsl.h"
#include "amrsp_SinglePassAMR_frag_glsl.h"
#include "amrsp_SinglePassAMR_vert_glsl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <list>
#include <memory>
#include <string>
#include <vector>

namespace
{
/// What one frame renders, resolved from the mapper's settings, the volume property and what
/// the context offers. The shader variant depends on these and on the data only.
struct FrameSettings
{
  int Storage = -1; // PACKED_ATLAS, BINDLESS_TEXTURES or LINEAR_BRICKS
  int Access = -1;  // DIRECT_ACCESS or WATERFALL_ACCESS with bindless, else -1
  int Blend = 0;    // AMRSP_BLEND_MODE: 0 composite, 1 maximum, 2 minimum, 3 average, 4 iso
  std::vector<float> IsoValues; // sorted, padded to 8 (iso-surface blending only)
  int IsoCount = 0;
  bool Shade = false;       // gradient shading (composite and iso-surface blending)
  bool Shadows = false;     // shadow rays (composite and iso-surface blending)
  bool SkipEmpty = false;   // empty-space skipping (composite blending)
  bool SmoothCells = false; // trilinear cell reconstruction (cell data)
  bool Ropes = false;       // neighbour links (when the build has them)
  bool UseDepth = false;
  amrsp::FrameQuality Quality; // image sample distance and sample-distance scale

  bool Reduced() const { return this->Quality.ImageSampleDistance > 1.0; }
};
} // namespace

//------------------------------------------------------------------------------
class vtkSinglePassAMRVolumeMapper::vtkInternals
{
public:
  explicit vtkInternals(vtkSinglePassAMRVolumeMapper* self)
    : Self(self)
  {
  }

  // The steps of a frame, in order. Each returns false after Self->ReportError when the frame
  // cannot be drawn.
  /// Chooses the storage (warning once when a requested bindless storage falls back to the
  /// atlas) and uploads the data when the build, the storage, the context or the atlas limit
  /// changed.
  bool PrepareStorage(vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr, FrameSettings& frame);
  /// Uploads the refreshed values of the uploaded structure (PendingValuesUpload).
  bool UploadValues(vtkOpenGLRenderWindow* renWin);
  /// Tabulates the transfer function and resolves blending, shading, shadows and skipping.
  bool PrepareAppearance(
    vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property, FrameSettings& frame);
  /// The shader variant of `frame`, compiled once per variant by VTK's shader cache.
  vtkShaderProgram* ReadyShader(
    vtkOpenGLRenderWindow* renWin, vtkVolume* vol, const FrameSettings& frame);
  /// Uploads the root box's triangles after a build and binds them to `program`'s vertexMC.
  bool BindProxyBox(vtkShaderProgram* program);
  /// Re-flags the transparent data nodes when the transfer table changed (composite only).
  bool UpdateEmptySpaceFlags(vtkOpenGLRenderWindow* renWin, const FrameSettings& frame);
  void ActivateTextures(vtkShaderProgram* program, const FrameSettings& frame);
  /// The tree, the levels, sampling, transfer function, clipping and level of detail.
  void SetDataUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkVolumeProperty* property,
    const vtkSinglePassAMRViewGeometry::ViewGeometry& view, const FrameSettings& frame);
  /// The first light in model coordinates, the material, shadow step and iso-values.
  void SetLightingUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkVolume* vol,
    vtkVolumeProperty* property, const FrameSettings& frame);
  /// Draws the proxy box's back faces once per pixel, blending premultiplied colour "over".
  void DrawBackFaces(
    vtkOpenGLRenderWindow* renWin, const vtkSinglePassAMRViewGeometry::ViewGeometry& view);
  void DeactivateTextures(const FrameSettings& frame);

  vtkSinglePassAMRVolumeMapper* Self;

  /// The CPU build; its bricks and texels wait in it until uploaded (PendingUpload), or, after
  /// a refresh of the values of an uploaded structure, its new bricks (PendingValuesUpload).
  amrsp::RayCastingData Data;
  bool PendingUpload = false;
  bool PendingValuesUpload = false;
  /// The input Data was built from (identity only, never dereferenced) and its MTime.
  const void* DataInput = nullptr;
  vtkMTimeType DataInputMTime = 0;

  /// Time steps shown before, kept with their textures (MaximumKeptStepBytes), most recently
  /// used first: an input that is one of them again is shown without a build or an upload.
  struct KeptStep
  {
    const void* Input;
    vtkMTimeType InputMTime;
    amrsp::RayCastingData Data;
    std::unique_ptr<vtkSinglePassAMRGridStorage> Storage;
  };
  std::list<KeptStep> KeptSteps;
  int KeptStepHits = 0;
  /// Whether the current data are on the GPU with nothing pending (then it can be kept).
  bool CurrentIsUploaded() const
  {
    return !this->PendingUpload && !this->PendingValuesUpload && this->Storage->HasUpload();
  }
  /// Moves the current step into KeptSteps; `next` becomes the current storage.
  void KeepCurrent(amrsp::RayCastingData data, std::unique_ptr<vtkSinglePassAMRGridStorage> next)
  {
    this->KeptSteps.push_front(
      KeptStep{ this->DataInput, this->DataInputMTime, std::move(data), std::move(this->Storage) });
    this->Storage = std::move(next);
  }
  /// Frees the least recently used kept steps beyond `budget` bytes of textures (in a render:
  /// their textures are deleted in the current context).
  void TrimKeptSteps(long long budget)
  {
    long long bytes = 0;
    for (auto it = this->KeptSteps.begin(); it != this->KeptSteps.end();)
    {
      bytes += it->Storage->GetTextureBytes();
      it = bytes > budget ? this->KeptSteps.erase(it) : std::next(it);
    }
  }
  std::unique_ptr<vtkSinglePassAMRGridStorage> Storage{ new vtkSinglePassAMRGridStorage };
  vtkSinglePassAMRTransferFunctionTable Transfer;
  vtkSinglePassAMRDepthCopy Depth;
  vtkSinglePassAMRFrameBudget Budget;

  // proxy geometry: the root box's 12 triangles, for the build of BoxBufferTime
  vtkNew<vtkOpenGLBufferObject> BoxBuffer;
  vtkNew<vtkOpenGLVertexArrayObject> BoxArray;
  vtkShaderProgram* BoxArrayProgram = nullptr;
  vtkMTimeType BoxBufferTime = 0;

  std::string FailedFragmentSource; // do not retry a program that failed to compile

  // what the last frame did
  int LastStorage = -1;
  bool LastRopes = false;
  int LastAccess = -1;
  std::string StorageNote; // why it did not use the bindless storage it was asked for
  long long TransparentDataNodes = 0;
};

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
    vtkSinglePassAMRConversion::ArraySelection selection;
    selection.Name = array;
    selection.Component = this->ArrayComponent;
    amrsp::Hierarchy h;
    // ProgressEvent: the build reports 0 to 1 (conversion, then PrepareRayCasting's steps), the
    // upload in the first render 0 to 1 again
    this->BeginProgressPhase(PROGRESS_BUILD, "converting the AMR blocks");
    if (!vtkSinglePassAMRConversion::FromOverlappingAMR(amr, selection, h, error))
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
  in.LastStorage = -1;
  in.LastAccess = -1;
  in.StorageNote.clear();
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
  FrameSettings frame;
  vtkVolumeProperty* property = vol->GetProperty();
  if (!in.PrepareStorage(renWin, amr, frame) || !in.PrepareAppearance(renWin, property, frame))
  {
    return;
  }
  vtkSinglePassAMRViewGeometry::ViewGeometry view;
  std::string viewError;
  if (!vtkSinglePassAMRViewGeometry::ComputeViewGeometry(ren, vol, view, viewError))
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
  vtkSinglePassAMRViewGeometry::ViewGeometry rays = view;
  if (frame.Reduced())
  {
    rays.X0 = rays.Y0 = 0;
    vtkSinglePassAMRFrameBudget::ReducedSize(
      view.Width, view.Height, frame.Quality.ImageSampleDistance, rays.Width, rays.Height);
    if (!in.Budget.Image.Ensure(renWin, rays.Width, rays.Height, true, viewError))
    {
      this->ReportError(viewError);
      return;
    }
  }
  vtkShaderProgram* program = in.ReadyShader(renWin, vol, frame);
  if (!program)
  {
    return;
  }
  if (!in.BindProxyBox(program))
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
  if (frame.Shade || frame.Shadows || frame.Blend == 4)
  {
    in.SetLightingUniforms(program, ren, vol, property, frame);
  }
  in.Budget.DrawRays(
    renWin, frame.Reduced(), [&in, renWin, &view] { in.DrawBackFaces(renWin, view); });
  in.DeactivateTextures(frame);
  in.LastStorage = frame.Storage;
  in.LastAccess = frame.Access;
  in.LastRopes = frame.Ropes && this->LODThreshold <= 0.0;
  if (frame.Reduced() && !in.Budget.Image.CompositeOver(renWin, viewError))
  {
    this->ReportError(viewError);
    return;
  }
  in.Budget.End(budget, frame.Quality);
  vtkOpenGLCheckErrorMacro("failed after vtkSinglePassAMRVolumeMapper::Render");
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::PrepareStorage(
  vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr, FrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  this->TrimKeptSteps(static_cast<long long>(self->MaximumKeptStepBytes));
  this->Storage->SetLinearPageBytes(self->MaximumAtlasPageBytes);
  const vtkSinglePassAMRGridStorage::Choice choice =
    this->Storage->Choose(renWin, this->Data, self->DataStorage, self->BindlessAccess,
      self->AutoBindlessWaste, self->MaximumAtlasSize, self->AutoLinearBytes);
  if (!choice.FallbackReason.empty())
  {
    this->StorageNote = choice.FallbackReason;
    self->WarnOnce("bindless textures requested, but " + choice.FallbackReason +
      ": rendering with the packed atlas instead");
  }
  if (choice.Storage < 0)
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
bool vtkSinglePassAMRVolumeMapper::vtkInternals::PrepareAppearance(
  vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property, FrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  if (!property)
  {
    self->ReportError("the volume has no vtkVolumeProperty");
    return false;
  }
  if (!this->Transfer.Update(renWin, property, this->Data.ScalarRange, self->GetBuildTime()))
  {
    self->ReportError("uploading the transfer-function table failed");
    return false;
  }
  if (!this->Transfer.GetWarning().empty())
  {
    self->WarnOnce(this->Transfer.GetWarning());
  }
  switch (self->GetBlendMode())
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      frame.Blend = 0;
      break;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      frame.Blend = 1;
      break;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      frame.Blend = 2;
      break;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      frame.Blend = 3;
      break;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      frame.Blend = 4;
      break;
    default:
      self->ReportError("blend mode " + std::to_string(self->GetBlendMode()) +
        " is not supported (composite, maximum, minimum, average intensity and iso-surface are)");
      return false;
  }
  if (frame.Blend == 4)
  {
    vtkContourValues* values = property->GetIsoSurfaceValues();
    const int count = values ? values->GetNumberOfContours() : 0;
    if (count < 1 || count > 8)
    {
      self->ReportError("iso-surface blending needs 1 to 8 values in "
                        "vtkVolumeProperty::GetIsoSurfaceValues() (it has " +
        std::to_string(count) + ")");
      return false;
    }
    for (int i = 0; i < count; ++i)
    {
      frame.IsoValues.push_back(static_cast<float>(values->GetValue(i)));
    }
    std::sort(frame.IsoValues.begin(), frame.IsoValues.end());
    frame.IsoValues.resize(8, 0.0f);
    frame.IsoCount = count;
  }
  // shading and shadows apply to composite and iso-surface blending only
  const bool lit = frame.Blend == 0 || frame.Blend == 4;
  frame.Shade = lit && property->GetShade(0) != 0;
  frame.Shadows = lit && self->Shadows;
  frame.SkipEmpty = self->EmptySpaceSkipping && frame.Blend == 0;
  frame.SmoothCells = self->CellInterpolation == SMOOTH_CELL && !this->Data.VertexCentred;
  frame.Ropes = self->Ropes && this->Storage->GetRopes() != nullptr;
  frame.UseDepth = self->UseDepthBuffer;
  return true;
}

//------------------------------------------------------------------------------
vtkShaderProgram* vtkSinglePassAMRVolumeMapper::vtkInternals::ReadyShader(
  vtkOpenGLRenderWindow* renWin, vtkVolume* vol, const FrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  const amrsp::LevelTable& levels = this->Data.Levels;
  std::string defines = "#define AMRSP_LEVEL_COUNT " +
    std::to_string(this->Data.LevelCellSize.size()) + "\n" + this->Storage->GetGridDataDefines() +
    (this->Data.VertexCentred ? "#define AMRSP_VERTEX_CENTRED 1\n"
                              : "#define AMRSP_CELL_CENTRED 1\n");
  const auto define = [&defines](bool on, const std::string& line)
  {
    if (on)
    {
      defines += "#define " + line + "\n";
    }
  };
  define(frame.Access == WATERFALL_ACCESS, "AMRSP_WATERFALL 1");
  define(this->Transfer.IsLogarithmic(), "AMRSP_LOG_TRANSFER 1");
  define(frame.UseDepth, "AMRSP_USE_DEPTH 1");
  define(frame.UseDepth && frame.Reduced(), "AMRSP_REDUCED_IMAGE 1");
  define(!levels.LevelToFinestLog2.empty(), "AMRSP_POWER_OF_TWO_REFINEMENT 1");
  define(levels.UniformRefinementLog2 > 0,
    "AMRSP_UNIFORM_REFINEMENT_LOG2 " + std::to_string(levels.UniformRefinementLog2));
  define(true, "AMRSP_BLEND_MODE " + std::to_string(frame.Blend));
  define(frame.SkipEmpty, "AMRSP_SKIP_EMPTY 1");
  define(frame.SmoothCells, "AMRSP_SMOOTH_CELLS 1");
  define(frame.Ropes, "AMRSP_ROPES 1");
  define(self->RayLoop == FLAT_LOOP, "AMRSP_FLAT_LOOP 1");
  define(self->DiagnosticAblation != NO_ABLATION,
    "AMRSP_ABLATION " + std::to_string(self->DiagnosticAblation));
  define(frame.Shade, "AMRSP_SHADE 1");
  define(frame.Shadows, "AMRSP_SHADOWS 1");
  define(
    self->WorkCountersOutput && self->WorkCountOutput == NO_WORK_COUNT, "AMRSP_WORK_COUNTERS 1");
  define(self->WorkCountOutput != NO_WORK_COUNT,
    "AMRSP_WORK_COUNT " + std::to_string(self->WorkCountOutput));
  const std::string fragment =
    vtkSinglePassAMRShaderComposer::ComposeFragmentShader(amrsp_SinglePassAMR_frag_glsl, defines,
      { { "KdTreeLayout", amrsp_KdTreeLayout_glsl }, { "RayCommon", amrsp_RayCommon_glsl },
        { "BrickSample", amrsp_BrickSample_glsl }, { "SmoothCells", amrsp_SmoothCells_glsl },
        { "Shading", amrsp_Shading_glsl }, { "RaySteps", amrsp_RaySteps_glsl } },
      vol);
  if (fragment == this->FailedFragmentSource)
  {
    self->ReportError(
      "the single-pass AMR shader failed to compile or link (see the earlier error)");
    return nullptr;
  }
  vtkShaderProgram* program = renWin->GetShaderCache()->ReadyShaderProgram(
    amrsp_SinglePassAMR_vert_glsl, fragment.c_str(), "");
  if (!program)
  {
    this->FailedFragmentSource = fragment;
    self->ReportError("the single-pass AMR shader failed to compile or link (see the error above)");
  }
  return program;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::BindProxyBox(vtkShaderProgram* program)
{
  const vtkMTimeType buildTime = this->Self->GetBuildTime().GetMTime();
  if (this->BoxBufferTime != buildTime || this->BoxBuffer->GetHandle() == 0)
  {
    const double* b = this->Data.Levels.Bounds;
    const double lo[3] = { b[0], b[2], b[4] };
    const double hi[3] = { b[1], b[3], b[5] };
    this->BoxBuffer->Upload(
      vtkSinglePassAMRProxyBox::BoxTriangles(lo, hi), vtkOpenGLBufferObject::ArrayBuffer);
    this->BoxBufferTime = buildTime;
    this->BoxArrayProgram = nullptr;
  }
  this->BoxArray->Bind();
  if (this->BoxArrayProgram != program)
  {
    this->BoxArray->ReleaseGraphicsResources();
    this->BoxArray->Bind();
    if (!this->BoxArray->AddAttributeArray(
          program, this->BoxBuffer, "vertexMC", 0, 3 * sizeof(float), VTK_FLOAT, 3, false))
    {
      this->BoxArray->Release();
      this->Self->ReportError("cannot bind the proxy box's vertices to the shader");
      return false;
    }
    this->BoxArrayProgram = program;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeMapper::vtkInternals::UpdateEmptySpaceFlags(
  vtkOpenGLRenderWindow* renWin, const FrameSettings& frame)
{
  // the flags stay valid while skipping is switched off: switching it on again reuses them
  this->TransparentDataNodes = 0;
  if (!frame.SkipEmpty)
  {
    return true;
  }
  // the node ranges were joined after the upload (PrepareStorage)
  float tableRange[2];
  this->Transfer.GetShaderRange(tableRange);
  const vtkSinglePassAMRTransferFunctionTable& table = this->Transfer;
  if (!this->Storage->UpdateTransparentFlags(renWin, this->Data.NodeRanges, table.GetOpacityTable(),
        tableRange, table.GetTableTime(), [&table](float s) { return table.TableScalar(s); }))
  {
    this->Self->ReportError("uploading the empty-space skipping flags failed");
    return false;
  }
  this->TransparentDataNodes = this->Storage->GetFlaggedDataNodes();
  return true;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::ActivateTextures(
  vtkShaderProgram* program, const FrameSettings& frame)
{
  vtkSinglePassAMRGridStorage& s = *this->Storage;
  s.GetTree()->Activate();
  s.GetDataNodes()->Activate();
  s.ActivateGridData(program);
  this->Transfer.GetTexture()->Activate();
  program->SetUniformi("amrspTree", s.GetTree()->GetTextureUnit());
  program->SetUniformi("amrspDataNodes", s.GetDataNodes()->GetTextureUnit());
  program->SetUniformi("amrspTransfer", this->Transfer.GetTexture()->GetTextureUnit());
  if (frame.SmoothCells)
  {
    s.GetBrickBoxes()->Activate();
    program->SetUniformi("amrspBrickBoxes", s.GetBrickBoxes()->GetTextureUnit());
  }
  if (frame.SkipEmpty)
  {
    s.GetTransparentFlags()->Activate();
    program->SetUniformi("amrspTransparentFlags", s.GetTransparentFlags()->GetTextureUnit());
  }
  if (frame.Ropes)
  {
    s.GetRopes()->Activate();
    program->SetUniformi("amrspRopes", s.GetRopes()->GetTextureUnit());
    program->SetUniform3f("amrspRopeCellSize", &this->Data.RopeCellSize.x);
  }
  if (frame.UseDepth)
  {
    program->SetUniformi("amrspDepth", this->Depth.Depth->GetTextureUnit());
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::SetDataUniforms(vtkShaderProgram* program,
  vtkRenderer* ren, vtkVolumeProperty* property,
  const vtkSinglePassAMRViewGeometry::ViewGeometry& view, const FrameSettings& frame)
{
  vtkSinglePassAMRVolumeMapper* self = this->Self;
  const amrsp::RayCastingData& d = this->Data;
  const amrsp::LevelTable& levels = d.Levels;
  const int levelCount = static_cast<int>(d.LevelCellSize.size());
  std::vector<float> steps;
  for (double edge : levels.LevelMinEdge)
  {
    steps.push_back(static_cast<float>(amrsp::LevelSampleStep(
      self->SampleDistanceFactor * frame.Quality.SampleDistanceScale, edge)));
  }
  const glm::vec3 origin(d.Data.Origin);
  const glm::vec3 spacing(d.Data.Spacing0);
  const float viewport[4] = { static_cast<float>(view.X0), static_cast<float>(view.Y0),
    static_cast<float>(view.Width), static_cast<float>(view.Height) };
  float transferRange[2];
  this->Transfer.GetShaderRange(transferRange);

  program->SetUniformf("amrspOpacityThreshold", static_cast<float>(self->OpacityThreshold));
  program->SetUniformMatrix4x4("amrspMCDCMatrix", const_cast<float*>(view.MCDC));
  program->SetUniformMatrix4x4("amrspDCMCMatrix", const_cast<float*>(view.DCMC));
  program->SetUniform4f("amrspViewport", viewport);
  program->SetUniform4f("amrspEyeMC", view.EyeMC);
  program->SetUniform3f("amrspOrigin", &origin.x);
  program->SetUniform3f("amrspSpacing0", &spacing.x);
  program->SetUniform3f("amrspRootLo", &d.RootLo.x);
  program->SetUniform3f("amrspRootHi", &d.RootHi.x);
  glm::vec3 clipLo, clipHi;
  std::string cropWarning;
  vtkSinglePassAMRProxyBox::ClipBox(
    self, d.Data.Origin, d.Data.Spacing0, d.RootLo, d.RootHi, clipLo, clipHi, cropWarning);
  if (!cropWarning.empty())
  {
    self->WarnOnce(cropWarning);
  }
  program->SetUniform3f("amrspClipLo", &clipLo.x);
  program->SetUniform3f("amrspClipHi", &clipHi.x);
  program->SetUniform1iv("amrspRootLoFinest", 3, &levels.RootLoFinest.x);
  program->SetUniform1iv("amrspRootHiFinest", 3, &levels.RootHiFinest.x);
  // (with uniform power-of-two refinement the shader computes these from the level)
  if (program->IsUniformUsed("amrspLevelCellSize"))
  {
    program->SetUniform3fv("amrspLevelCellSize", levelCount, &d.LevelCellSize[0].x);
  }
  if (program->IsUniformUsed("amrspLevelToFinest"))
  {
    program->SetUniform1iv("amrspLevelToFinest", 3 * levelCount, levels.LevelToFinest.data());
  }
  if (levels.UniformRefinementLog2 > 0)
  {
    program->SetUniformf("amrspFinestCellSize", d.LevelCellSize.back().x);
  }
  else if (!levels.LevelToFinestLog2.empty())
  {
    program->SetUniform1iv(
      "amrspLevelToFinestLog2", 3 * levelCount, levels.LevelToFinestLog2.data());
  }
  program->SetUniform1fv("amrspLevelStep", levelCount, steps.data());
  const long long guard = 4 * d.KdNodes + 16;
  program->SetUniformi("amrspMaxSegments", static_cast<int>(std::min<long long>(guard, 1 << 30)));
  if (self->DiagnosticAblation == SAMPLING_ONLY)
  {
    program->SetUniformi("amrspAblationSamples", self->DiagnosticAblationSamples);
  }
  program->SetUniform2f("amrspTransferRange", transferRange);
  program->SetUniformf(
    "amrspTransferSize", static_cast<float>(vtkSinglePassAMRTransferFunctionTable::Size));
  // level of detail: world size of a pixel at distance 1 (perspective) or everywhere (parallel),
  // as amrsp::LevelOfDetail
  vtkCamera* camera = ren->GetActiveCamera();
  const float pixelPerDistance = view.Parallel
    ? 0.0f
    : static_cast<float>(
        2.0 * std::tan(vtkMath::RadiansFromDegrees(camera->GetViewAngle()) * 0.5) / view.Height);
  const float parallelPixel =
    view.Parallel ? static_cast<float>(2.0 * camera->GetParallelScale() / view.Height) : 0.0f;
  program->SetUniformf("amrspLodThreshold", static_cast<float>(self->LODThreshold));
  program->SetUniformf("amrspPixelSizePerDistance", pixelPerDistance);
  program->SetUniformf("amrspParallelPixelSize", parallelPixel);
  program->SetUniformf("amrspUnitDistance",
    static_cast<float>(std::max(property->GetScalarOpacityUnitDistance(0), 1e-12)));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::SetLightingUniforms(vtkShaderProgram* program,
  vtkRenderer* ren, vtkVolume* vol, vtkVolumeProperty* property, const FrameSettings& frame)
{
  const vtkSinglePassAMRViewGeometry::ModelLight light =
    vtkSinglePassAMRViewGeometry::FirstLightInModel(ren, vol);
  const auto setIfUsed = [program](const char* name, auto&& set)
  {
    if (program->IsUniformUsed(name))
    {
      set(name);
    }
  };
  setIfUsed("amrspAmbient",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetAmbient(0))); });
  setIfUsed("amrspDiffuse",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetDiffuse(0))); });
  setIfUsed("amrspSpecular",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(property->GetSpecular(0))); });
  setIfUsed("amrspSpecularPower",
    [&](const char* n)
    { program->SetUniformf(n, static_cast<float>(property->GetSpecularPower(0))); });
  setIfUsed("amrspLightPositional",
    [&](const char* n) { program->SetUniformi(n, light.Positional ? 1 : 0); });
  setIfUsed(
    "amrspLightPositionMC", [&](const char* n) { program->SetUniform3f(n, light.Position); });
  setIfUsed(
    "amrspLightDirectionMC", [&](const char* n) { program->SetUniform3f(n, light.Direction); });
  setIfUsed("amrspLightColour", [&](const char* n) { program->SetUniform3f(n, light.Colour); });
  const std::vector<double>& minEdge = this->Data.Levels.LevelMinEdge;
  const double shadowStep = this->Self->ShadowSampleDistance > 0.0
    ? this->Self->ShadowSampleDistance
    : (minEdge.empty() ? 1.0 : minEdge[0]);
  setIfUsed("amrspShadowStep",
    [&](const char* n) { program->SetUniformf(n, static_cast<float>(shadowStep)); });
  setIfUsed("amrspIsoCount", [&](const char* n) { program->SetUniformi(n, frame.IsoCount); });
  if (!frame.IsoValues.empty())
  {
    setIfUsed("amrspIsoValues",
      [&](const char* n) { program->SetUniform1fv(n, 8, frame.IsoValues.data()); });
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::DrawBackFaces(
  vtkOpenGLRenderWindow* renWin, const vtkSinglePassAMRViewGeometry::ViewGeometry& view)
{
  {
    // back faces only (a mirroring volume transform flips the winding), premultiplied "over"
    const vtkSinglePassAMRScopedBlendedDraw blended(
      renWin->GetState(), view.Mirrored ? GL_BACK : GL_FRONT, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDrawArrays(GL_TRIANGLES, 0, 36);
  }
  this->BoxArray->Release();
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeMapper::vtkInternals::DeactivateTextures(const FrameSettings& frame)
{
  vtkSinglePassAMRGridStorage& s = *this->Storage;
  s.GetTree()->Deactivate();
  s.GetDataNodes()->Deactivate();
  s.DeactivateGridData();
  this->Transfer.GetTexture()->Deactivate();
  if (frame.SmoothCells)
  {
    s.GetBrickBoxes()->Deactivate();
  }
  if (frame.SkipEmpty)
  {
    s.GetTransparentFlags()->Deactivate();
  }
  if (frame.Ropes)
  {
    s.GetRopes()->Deactivate();
  }
  if (frame.UseDepth)
  {
    this->Depth.Depth->Deactivate();
  }
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
void vtkSinglePassAMRVolumeMapper::GetAtlasDimensions(int dims[3])
{
  const glm::ivec3 d = this->Internals->Data.AtlasDims;
  dims[0] = d.x;
  dims[1] = d.y;
  dims[2] = d.z;
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfKeptStepHits()
{
  return this->Internals->KeptStepHits;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeMapper::GetNumberOfKeptSteps()
{
  return static_cast<int>(this->Internals->KeptSteps.size());
}

//------------------------------------------------------------------------------
vtkIdType vtkSinglePassAMRVolumeMapper::GetKeptStepBytes()
{
  vtkIdType bytes = 0;
  for (const auto& kept : this->Internals->KeptSteps)
  {
    bytes += static_cast<vtkIdType>(kept.Storage->GetTextureBytes());
  }
  return bytes;
}

//------------------------------------------------------------------------------
long long vtkSinglePassAMRVolumeMapper::GetTextureBytes()
{
  return this->Internals->Storage->GetTextureBytes();
}

long long vtkSinglePassAMRVolumeMapper::GetPackedTextureBytes()
{
  return this->Internals->Data.PackedBytes;
}

long long vtkSinglePassAMRVolumeMapper::GetBindlessTextureBytes()
{
  return this->Internals->Data.BindlessBytes;
}

bool vtkSinglePassAMRVolumeMapper::GetLastFrameInteractive()
{
  return this->Internals->Budget.LastInteractive;
}

double vtkSinglePassAMRVolumeMapper::GetLastImageSampleDistance()
{
  return this->Internals->Budget.LastQuality.ImageSampleDistance;
}

double vtkSinglePassAMRVolumeMapper::GetLastSampleDistanceScale()
{
  return this->Internals->Budget.LastQuality.SampleDistanceScale;
}

double vtkSinglePassAMRVolumeMapper::GetLastFrameSeconds()
{
  return this->Internals->Budget.LastSeconds;
}

double vtkSinglePassAMRVolumeMapper::GetLastFrameBudget()
{
  return this->Internals->Budget.LastBudget;
}

int vtkSinglePassAMRVolumeMapper::GetNumberOfAtlasPages()
{
  const vtkSinglePassAMRGridStorage& s = *this->Internals->Storage;
  return s.GetUploadedStorage() == LINEAR_BRICKS
    ? s.GetNumberOfLinearPages()
    : static_cast<int>(this->Internals->Data.PageDims.size());
}

double vtkSinglePassAMRVolumeMapper::GetAtlasWaste()
{
  return this->Internals->Data.AtlasWaste;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfKdNodes()
{
  return this->Internals->Data.KdNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfDataNodes()
{
  return this->Internals->Data.DataNodes;
}

long long vtkSinglePassAMRVolumeMapper::GetNumberOfTransparentDataNodes()
{
  return this->Internals->TransparentDataNodes;
}

int vtkSinglePassAMRVolumeMapper::GetLastDataStorage()
{
  return this->Internals->LastStorage;
}

bool vtkSinglePassAMRVolumeMapper::GetLastRopes()
{
  return this->Internals->LastRopes;
}

const char* vtkSinglePassAMRVolumeMapper::GetBindlessFallbackReason()
{
  return this->Internals->StorageNote.c_str();
}

int vtkSinglePassAMRVolumeMapper::GetLastBindlessAccess()
{
  return this->Internals->LastAccess;
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
  os << indent << "LastDataStorage: " << GetDataStorageName(in.LastStorage)
     << ", LastBindlessAccess: " << GetBindlessAccessName(in.LastAccess) << "\n";
  os << indent << "OpacityThreshold: " << this->OpacityThreshold << "\n";
  os << indent << "EmptySpaceSkipping: " << (this->EmptySpaceSkipping ? "on" : "off") << "\n";
  os << indent << "WorkCountersOutput: " << (this->WorkCountersOutput ? "on" : "off") << "\n";
  os << indent << "WorkCountOutput: " << this->WorkCountOutput << "\n";
  os << indent << "Ropes: " << (this->Ropes ? "on" : "off") << "\n";
  os << indent << "RayLoop: " << (this->RayLoop == FLAT_LOOP ? "flat" : "nested") << "\n";
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
