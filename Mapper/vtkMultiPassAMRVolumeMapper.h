// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkMultiPassAMRVolumeMapper
 * @brief   multi-pass GPU raycaster for vtkOverlappingAMR: one draw per kD-tree data node
 *
 * The baseline Kaehler & Abel 2013 compare their single-pass methods with (their reference
 * vg06-kaehler, section 6): the kD-tree is traversed on the CPU, and every data node is rendered
 * separately by drawing its bounding box; the fragment shader raycasts only the ray segment
 * inside that box and the segments are composited by blending, front to back across the draws.
 *
 * - Data: the same decomposition and storage as vtkSinglePassAMRVolumeMapper's packing path
 *   (vtkSinglePassAMRConversion, amrsp::BuildKdTree, one brick per grid in one packed R32F atlas).
 *   No tree textures: the tree lives on the CPU only.
 * - Each frame: the tree's leaves with data (type (b) nodes, the finest level everywhere; no
 *   level of detail) are ordered front to back for the current camera: at every inner node the
 *   child on the eye's side of the split plane first (parallel projection: the side the rays come
 *   from). Each node then costs one draw of its box (back faces, so a camera inside works; depth
 *   clamping keeps faces between the eye and the near plane) with the node's box, level, cell
 *   range and atlas offset as uniforms.
 * - Per fragment: the ray through the pixel centre (from the eye, or from the near plane for
 *   parallel projection) is clipped to the node box, cut by the README sampling rule (n =
 *   max(1, ceil(length / D)) equal steps, samples at the midpoints, D = SampleDistanceFactor x
 *   the smallest edge of a cell of the node's level), sampled nearest-cell (cell data) or
 *   trilinearly (vertex data) and integrated into premultiplied colour and opacity.
 * - Blending: into a cleared RGBA32F offscreen target with glBlendFunc(ONE_MINUS_DST_ALPHA, ONE)
 *   ("under", front to back); the result is composited over the renderer's framebuffer with one
 *   full-screen quad (ONE, ONE_MINUS_SRC_ALPHA), exactly as the single-pass mapper blends its
 *   output. There is no early ray termination across draws.
 *
 * The segments are bounded by the same node boxes as the single-pass traversal visits (computed
 * in the same float arithmetic), so both mappers and amrsp::RenderKdTree take the same samples.
 *
 * Input, array selection (SelectScalarArray, ArrayComponent), transfer function
 * (vtkVolumeProperty component 0, ScalarOpacityUnitDistance), camera conventions, depth-buffer
 * clipping (UseDepthBuffer), MaximumAtlasSize, rebuild policy and error reporting
 * (vtkErrorMacro once, GetLastError) are those of vtkSinglePassAMRVolumeMapper. Only composite
 * blending is implemented (another BlendMode is an error), and there is no level of detail.
 */
#ifndef vtkMultiPassAMRVolumeMapper_h
#define vtkMultiPassAMRVolumeMapper_h

#include "vtkSinglePassAMRModule.h" // for export macro
#include "vtkVolumeMapper.h"

#include <string> // for IsRenderSupported

class vtkOverlappingAMR;
class vtkRenderWindow;

class VTKSINGLEPASSAMR_EXPORT vtkMultiPassAMRVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkMultiPassAMRVolumeMapper* New();
  vtkTypeMacro(vtkMultiPassAMRVolumeMapper, vtkVolumeMapper);
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
  /// GL_MAX_3D_TEXTURE_SIZE; a positive value lowers that limit.
  vtkSetClampMacro(MaximumAtlasSize, int, 0, VTK_INT_MAX);
  vtkGetMacro(MaximumAtlasSize, int);
  ///@}

  /// Renders the volume. Called by vtkVolume during the volumetric pass.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /// Frees the textures, framebuffer, buffers and shaders of `window`'s context.
  void ReleaseGraphicsResources(vtkWindow* window) override;

#ifndef __VTK_WRAP__
  /// Whether `window` offers what the mapper needs: an OpenGL 3.2 core context (float colour
  /// attachments, depth clamping, GLSL 1.50). When it does not, `why` says what is missing.
  static bool IsRenderSupported(vtkRenderWindow* window, std::string* why = nullptr);
#endif

  ///@{
  /// Diagnostics of the last build and render.
  /// GetLastError: empty after a successful Render(), else one line naming the problem.
  const char* GetLastError();
  /// Seconds spent converting, building the kD-tree and packing (CPU), and uploading.
  double GetLastBuildSeconds();
  double GetLastUploadSeconds();
  /// Number of times the data were (re)built; camera or transfer-function changes must not
  /// increase it.
  int GetNumberOfBuilds();
  /// Atlas texture dimensions, and the bytes of the data textures (the atlas: the multi-pass
  /// method has no tree textures). The RGBA32F accumulation target (16 bytes per viewport pixel)
  /// is counted apart.
  void GetAtlasDimensions(int dims[3]);
  long long GetTextureBytes();
  long long GetAccumulationBytes();
  /// kD-tree nodes and data nodes (types (a) and (b)) of the current hierarchy.
  long long GetNumberOfKdNodes();
  long long GetNumberOfDataNodes();
  /// Draws (passes) of the last frame: the tree's leaves with data, one per data node drawn.
  long long GetLastNumberOfPasses();
  /// CPU seconds of the last frame's front-to-back ordering of the nodes.
  double GetLastOrderSeconds();
  ///@}

protected:
  vtkMultiPassAMRVolumeMapper();
  ~vtkMultiPassAMRVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  int ArrayComponent = -1;
  double SampleDistanceFactor = 1.0;
  bool UseDepthBuffer = true;
  int MaximumAtlasSize = 0;

private:
  vtkMultiPassAMRVolumeMapper(const vtkMultiPassAMRVolumeMapper&) = delete;
  void operator=(const vtkMultiPassAMRVolumeMapper&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
