// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file    vtkSinglePassAMRVolumeMapperInternals.h
 * @brief   the single-pass mapper's state and the steps of its frame (private to the module)
 *
 * vtkSinglePassAMRVolumeMapper.cxx holds the build, the storage and the kept time steps;
 * vtkSinglePassAMRVolumeMapperFrame.cxx the frame's appearance, shader, uniforms and draw.
 */
#ifndef vtkSinglePassAMRVolumeMapperInternals_h
#define vtkSinglePassAMRVolumeMapperInternals_h

#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkSinglePassAMRComputeProgram.h"
#include "vtkAMRMapperDepthCopy.h"
#include "vtkSinglePassAMRFrameBudget.h"
#include "vtkSinglePassAMRGridStorage.h"
#include "vtkSinglePassAMRShaderVariant.h"
#include "vtkSinglePassAMRStorageChoice.h"
#include "vtkAMRMapperTransferFunctionTable.h"
#include "vtkAMRMapperViewGeometry.h"

#include "amrsp/RayCastingData.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLVertexArrayObject.h"

#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

class vtkOpenGLRenderWindow;
class vtkRenderer;
class vtkShaderProgram;
class vtkVolume;
class vtkVolumeProperty;

/// What one frame renders, resolved from the mapper's settings, the volume property and what
/// the context offers. The shader variant depends on these and on the data only.
struct vtkSinglePassAMRFrameSettings
{
  amrsp::DataStorage Storage = amrsp::DataStorage::None;
  amrsp::BindlessAccess Access = amrsp::BindlessAccess::None; // bindless only
  amrsp::BlendMode Blend = amrsp::BlendMode::Composite;
  std::vector<float> IsoValues; // sorted, padded to 8 (iso-surface blending only)
  int IsoCount = 0;
  bool Shade = false;       // gradient shading (composite and iso-surface blending)
  bool Shadows = false;     // shadow rays (composite and iso-surface blending)
  bool SkipEmpty = false;   // empty-space skipping (composite blending)
  bool SmoothCells = false; // trilinear cell reconstruction (cell data)
  bool Ropes = false;       // neighbour links (when the build has them)
  bool FlatLoop = false;    // the flat loop (RayLoop, AUTO_LOOP resolved for the context)
  amrsp::RayCaster Caster = amrsp::RayCaster::Fragment; // RayCaster resolved for the context
  bool UseDepth = false;
  amrsp::FrameQuality Quality; // image sample distance and sample-distance scale

  bool Reduced() const { return this->Quality.ImageSampleDistance > 1.0; }
};

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
  bool PrepareStorage(
    vtkOpenGLRenderWindow* renWin, vtkOverlappingAMR* amr, vtkSinglePassAMRFrameSettings& frame);
  /// Uploads the refreshed values of the uploaded structure (PendingValuesUpload).
  bool UploadValues(vtkOpenGLRenderWindow* renWin);
  /// Tabulates the transfer function and resolves blending, shading, shadows and skipping.
  bool PrepareAppearance(vtkOpenGLRenderWindow* renWin, vtkVolumeProperty* property,
    vtkSinglePassAMRFrameSettings& frame);
  /// The shader variant of `frame` for its caster: the fragment program from VTK's shader
  /// cache, or the compute program (ComputePrograms), each compiled once per variant.
  vtkShaderProgram* ReadyShader(
    vtkOpenGLRenderWindow* renWin, vtkVolume* vol, const vtkSinglePassAMRFrameSettings& frame);
  /// `frame`'s shader variant (both casters).
  vtkSinglePassAMRShaderVariant ShaderVariant(const vtkSinglePassAMRFrameSettings& frame) const;
  /// The compute caster's program for `source` in `renWin`, compiled on first use.
  vtkShaderProgram* ReadyComputeProgram(vtkOpenGLRenderWindow* renWin, const std::string& source);
  /// Casts the rays of `rays` (the viewport, or the reduced image at (0, 0)) with the bound
  /// compute `program` into RaysImage(reduced), which Render made ready; Render composites it.
  void DispatchRays(
    vtkShaderProgram* program, const vtkAMRMapperViewGeometry::ViewGeometry& rays, bool reduced);
  /// The offscreen image a frame's rays go into: the reduced image of an interactive frame
  /// (bilinear), or the compute caster's viewport-sized one (nearest).
  vtkAMRMapperOffscreenImage& RaysImage(bool reduced)
  {
    return reduced ? this->Budget.Image : this->ComputeImage;
  }
  /// Uploads the root box's triangles after a build and binds them to `program`'s vertexMC.
  bool BindProxyBox(vtkShaderProgram* program);
  /// Re-flags the transparent data nodes when the transfer table changed (composite only).
  bool UpdateEmptySpaceFlags(
    vtkOpenGLRenderWindow* renWin, const vtkSinglePassAMRFrameSettings& frame);
  void ActivateTextures(vtkShaderProgram* program, const vtkSinglePassAMRFrameSettings& frame);
  /// The tree, the levels, sampling, transfer function, clipping and level of detail.
  void SetDataUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkVolumeProperty* property,
    const vtkAMRMapperViewGeometry::ViewGeometry& view, const vtkSinglePassAMRFrameSettings& frame);
  /// The first light in model coordinates, the material, shadow step and iso-values.
  void SetLightingUniforms(vtkShaderProgram* program, vtkRenderer* ren, vtkVolume* vol,
    vtkVolumeProperty* property, const vtkSinglePassAMRFrameSettings& frame);
  /// Draws the proxy box's back faces once per pixel, blending premultiplied colour "over".
  void DrawBackFaces(
    vtkOpenGLRenderWindow* renWin, const vtkAMRMapperViewGeometry::ViewGeometry& view);
  void DeactivateTextures(const vtkSinglePassAMRFrameSettings& frame);

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
  vtkAMRMapperTransferFunctionTable Transfer;
  vtkAMRMapperDepthCopy Depth;
  vtkSinglePassAMRFrameBudget Budget;

  // proxy geometry: the root box's 12 triangles, for the build of BoxBufferTime
  vtkNew<vtkOpenGLBufferObject> BoxBuffer;
  vtkNew<vtkOpenGLVertexArrayObject> BoxArray;
  vtkShaderProgram* BoxArrayProgram = nullptr;
  vtkMTimeType BoxBufferTime = 0;

  std::string FailedFragmentSource; // do not retry a program that failed to compile
  std::string FailedComputeSource;
  /// The compute caster's programs of ComputeContext, by source (at most MaxComputePrograms,
  /// the oldest dropped first), and its full-size rays' image (nearest filtering).
  std::list<std::pair<std::string, vtkSmartPointer<vtkSinglePassAMRComputeProgram>>>
    ComputePrograms;
  static constexpr std::size_t MaxComputePrograms = 16;
  vtkOpenGLRenderWindow* ComputeContext = nullptr;
  vtkAMRMapperOffscreenImage ComputeImage;
  void FreeComputePrograms(vtkWindow* window);

  // what the last frame did
  amrsp::DataStorage LastStorage = amrsp::DataStorage::None;
  bool LastRopes = false;
  bool LastFlatLoop = false;
  amrsp::RayCaster LastCaster = amrsp::RayCaster::Auto; // Auto: no frame yet
  std::string CasterNote; // why the fragment caster ran where compute was asked for
  amrsp::BindlessAccess LastAccess = amrsp::BindlessAccess::None;
  std::string StorageNote; // why it did not use the bindless storage it was asked for
  long long TransparentDataNodes = 0;
};

#endif
