// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkAMRKdTreeVolumeMapper
 * @brief   what the project's GPU AMR volume mappers share: input, bounds, build, diagnostics
 *
 * Abstract base of vtkSinglePassAMRVolumeMapper (the paper's single-pass ray caster) and
 * vtkMultiPassAMRVolumeMapper (its multi-pass baseline), which both render through the
 * hierarchy's kD-tree of same-level blocks, as vtkGPUVolumeRayCastMapper holds the API of VTK's
 * OpenGL ray caster. It owns
 * - the input: one vtkOverlappingAMR port (the vtkDataSet overloads of vtkVolumeMapper are
 *   rejected with an error) and the bounds of its root box;
 * - the array selection: vtkAbstractVolumeMapper's SelectScalarArray, and ArrayComponent;
 * - the rebuild policy: the CPU build (conversion, kD-tree, packing, encoding) runs only when the
 *   input object, its modification time, the array selection, MaximumAtlasSize or
 *   MaximumAtlasPageBytes change;
 * - the settings both mappers honour (SampleDistanceFactor, UseDepthBuffer, MaximumAtlasSize);
 * - error reporting: a frame that cannot be drawn says why once with vtkErrorMacro (the same
 *   message is not repeated every frame) and in GetLastError; fallbacks warn once;
 * - the diagnostics of the last build and upload.
 * Subclasses implement the build (BuildData) and Render.
 */
#ifndef vtkAMRKdTreeVolumeMapper_h
#define vtkAMRKdTreeVolumeMapper_h

#include "vtkSinglePassAMRModule.h" // for export macro
#include "vtkTimeStamp.h"           // for GetBuildTime
#include "vtkVolumeMapper.h"

#include <set>    // for the warnings already given
#include <string> // for IsRenderSupported and the error messages

class vtkOpenGLRenderWindow;
class vtkOverlappingAMR;
class vtkRenderWindow;

class VTKSINGLEPASSAMR_EXPORT vtkAMRKdTreeVolumeMapper : public vtkVolumeMapper
{
public:
  vtkTypeMacro(vtkAMRKdTreeVolumeMapper, vtkVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The AMR input. The vtkDataSet overloads of vtkVolumeMapper are rejected with an error.
  virtual void SetInputData(vtkOverlappingAMR* input);
  void SetInputData(vtkImageData* input) override;
  void SetInputData(vtkDataSet* input) override;
  void SetInputData(vtkRectilinearGrid* input) override;
  vtkOverlappingAMR* GetAMRInput();
  ///@}

  ///@{
  /// Bounds of the root box of the hierarchy (the bounding box of the level-0 grids), in model
  /// coordinates. Computing them converts the input (the same conversion rendering needs).
  double* GetBounds() VTK_SIZEHINT(6) override;
  void GetBounds(double bounds[6]) override;
  ///@}

  ///@{
  /// Component of a multi-component scalar array; -1 (default) takes the magnitude.
  vtkSetMacro(ArrayComponent, int);
  vtkGetMacro(ArrayComponent, int);
  ///@}

  ///@{
  /// Sampling distance of a ray segment in one kD node, in units of the smallest edge of a cell
  /// of that node's level (default 1: about one sample per cell).
  vtkSetClampMacro(SampleDistanceFactor, double, 1e-3, 1e3);
  vtkGetMacro(SampleDistanceFactor, double);
  ///@}

  ///@{
  /// Clip rays at the depth of opaque geometry rendered before the volume (default on).
  vtkSetMacro(UseDepthBuffer, bool);
  vtkGetMacro(UseDepthBuffer, bool);
  vtkBooleanMacro(UseDepthBuffer, bool);
  ///@}

  ///@{
  /// Largest atlas edge accepted, in texels: 0 (default) uses the context's
  /// GL_MAX_3D_TEXTURE_SIZE; a positive value lowers that limit (to keep memory for others, and
  /// to exercise the error path in tests).
  vtkSetClampMacro(MaximumAtlasSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumAtlasSize, int);
  ///@}

  ///@{
  /// Largest atlas texture, in bytes: bricks that would make one atlas larger are spread over up
  /// to four atlas pages (textures) of at most this size, each read by the shaders through the
  /// data node's page. The default, 2 GiB - 64 MiB, stays below what Mesa's llvmpipe allocates
  /// per texture (2 GiB); 0 packs one atlas whatever its size.
  vtkSetClampMacro(MaximumAtlasPageBytes, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumAtlasPageBytes, vtkIdType);
  ///@}

  ///@{
  /// Diagnostics of the last build and render.
  /// GetLastError: empty after a successful Render(), else one line naming the problem.
  const char* GetLastError();
  /// Seconds spent converting, building the kD-tree, packing and encoding (CPU), and uploading.
  double GetLastBuildSeconds();
  double GetLastUploadSeconds();
  /// Number of times the data were (re)built; camera or transfer-function changes must not
  /// increase it. A new time step counts, whether rebuilt or refreshed.
  int GetNumberOfBuilds();
  /// Of those, the builds that kept the structure: a new input (a time step) whose hierarchy
  /// (levels, boxes, ratios, array, centring) equals the one built last only took its values,
  /// keeping the kD-tree, its encoding and the brick layout; the upload then sends the grid
  /// data only. The image is the full rebuild's.
  int GetNumberOfValueRefreshes();
  /// Whether the last build was such a refresh.
  bool GetLastBuildRefreshedValues();
  /// What a ProgressEvent reports, read during the event: the CPU build (conversion, kD-tree,
  /// packing, encoding; in GetBounds or the first render after a data change) or the upload of
  /// the grid data in a render. Each runs its progress from 0 to 1 and names its current step in
  /// GetProgressText().
  enum ProgressPhases
  {
    PROGRESS_BUILD = 0,
    PROGRESS_UPLOAD = 1
  };
  vtkGetMacro(ProgressPhase, int);
  /// Atlas texture dimensions (0 when no atlas could be packed) and the bytes of the data
  /// textures uploaded for the last frame.
  virtual void GetAtlasDimensions(int dims[3]) = 0;
  virtual long long GetTextureBytes() = 0;
  /// kD-tree nodes and data nodes of the current hierarchy.
  virtual long long GetNumberOfKdNodes() = 0;
  virtual long long GetNumberOfDataNodes() = 0;
  ///@}

#ifndef __VTK_WRAP__
  /// Whether `window` offers an OpenGL 3.2 core context (integer and float textures, GLSL 1.50,
  /// float colour attachments, depth clamping). When it does not, `why` says what is missing.
  static bool IsRenderSupported(vtkRenderWindow* window, std::string* why = nullptr);
#endif

protected:
  vtkAMRKdTreeVolumeMapper();
  ~vtkAMRKdTreeVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  /// Starts the progress of `phase` (ProgressPhases): its step `text`, and 0.
  void BeginProgressPhase(int phase, const char* text);

  /// The CPU build of `amr` (array `array`, component ArrayComponent, MaximumAtlasSize): returns
  /// false with a one-line `error` when the input cannot be rendered. `mayRefresh`: only the
  /// input changed since the last successful build (same array, component and limits), so a
  /// hierarchy of the same structure may keep what was built from it (amrsp::RefreshValues);
  /// `refreshed` says whether it did.
  virtual bool BuildData(vtkOverlappingAMR* amr, const std::string& array, bool mayRefresh,
    bool& refreshed, std::string& error) = 0;
  /// Model-space bounds of the data built last (called after a successful BuildData).
  virtual void GetBuiltBounds(double bounds[6]) = 0;
  /// Whether the next build should pack the bricks into an atlas (the single-pass mapper's
  /// linear storage does not need it). A build without packing is redone when this turns true.
  virtual bool BuildPacksBricks()
  {
    return true;
  }

  /// Builds when the build key (input object and MTime, array, component, MaximumAtlasSize, page
  /// bytes, and packing wanted where the last build did not pack) differs from the last build's.
  /// Returns whether the data built for it are valid.
  bool EnsureBuilt(vtkOverlappingAMR* amr);
  /// Builds again for the current key (a subclass that freed its CPU copies after an upload and
  /// must upload again). Returns whether it succeeded.
  bool Rebuild(vtkOverlappingAMR* amr);
  /// Forgets the build: the next EnsureBuilt builds again.
  void InvalidateBuild()
  {
    this->Built = false;
  }
  /// The error of the last build (empty when it succeeded) and when it last succeeded.
  const std::string& GetBuildError() const
  {
    return this->BuildError;
  }
  const vtkTimeStamp& GetBuildTime() const
  {
    return this->BuildTime;
  }

  /// The common start of Render: clears the frame's error, checks the window and the input and
  /// updates it. Returns the input, or nullptr after ReportError; `renWin` is then null too.
  vtkOverlappingAMR* BeginFrame(vtkRenderer* ren, vtkOpenGLRenderWindow*& renWin);
  /// The frame cannot be drawn: vtkErrorMacro unless the previous frame said the same.
  void ReportError(const std::string& message);
  /// A fallback or an ignored setting: vtkWarningMacro once per message per mapper.
  void WarnOnce(const std::string& message);

  int ArrayComponent = -1;
  double SampleDistanceFactor = 1.0;
  bool UseDepthBuffer = true;
  int MaximumAtlasSize = 0;
  vtkIdType MaximumAtlasPageBytes = (vtkIdType(2048) - 64) << 20;
  /// Seconds of the last upload (set by the subclass).
  double UploadSeconds = 0.0;
  int ProgressPhase = PROGRESS_BUILD;

private:
  vtkAMRKdTreeVolumeMapper(const vtkAMRKdTreeVolumeMapper&) = delete;
  void operator=(const vtkAMRKdTreeVolumeMapper&) = delete;

  bool RunBuild(vtkOverlappingAMR* amr, bool mayRefresh = false);

  // the build key and the result of the build made for it
  vtkOverlappingAMR* BuiltInput = nullptr; // identity only, never dereferenced
  vtkMTimeType BuiltInputMTime = 0;
  std::string BuiltArray;
  int BuiltComponent = -1;
  int BuiltPackLimit = -1;
  vtkIdType BuiltPageBytes = -1;
  bool BuiltPacked = false;
  bool Built = false;     // a build was attempted for the key above
  bool DataValid = false; // ... and succeeded
  std::string BuildError; // ... or failed with this message
  vtkTimeStamp BuildTime;
  int NumberOfBuilds = 0;
  int NumberOfValueRefreshes = 0;
  bool LastBuildRefreshed = false;
  double BuildSeconds = 0.0;

  std::string LastError;
  std::string PreviousError;    // the last frame's error, not reported again
  std::set<std::string> Warned; // warnings already given
};

#endif
