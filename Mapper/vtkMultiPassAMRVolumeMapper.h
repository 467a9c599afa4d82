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
 *   (vtkAMRMapperConversion, amrsp::BuildKdTree, one brick per grid in one packed R32F atlas).
 *   No tree textures: the tree lives on the CPU only.
 * - Each frame: the tree's leaves with data (type (b) nodes, the finest level everywhere; no
 *   level of detail) are ordered front to back for the current camera: at every inner node the
 *   child on the eye's side of the split plane first (parallel projection: the side the rays come
 *   from). Each node then costs one draw of its box (back faces, so a camera inside works; depth
 *   clamping keeps faces between the eye and the near plane) with the node's box, level, cell
 *   range and atlas offset as uniforms.
 * - Per fragment: the ray through the pixel centre (from the eye, or from the near plane for
 *   parallel projection) is clipped to the node box, cut by the sampling rule (docs/design.md) (n =
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

#include "vtkAMRKdTreeVolumeMapper.h"
#include "vtkSinglePassAMRModule.h" // for export macro

class VTKSINGLEPASSAMR_EXPORT vtkMultiPassAMRVolumeMapper : public vtkAMRKdTreeVolumeMapper
{
public:
  static vtkMultiPassAMRVolumeMapper* New();
  vtkTypeMacro(vtkMultiPassAMRVolumeMapper, vtkAMRKdTreeVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Renders the volume. Called by vtkVolume during the volumetric pass.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /// Frees the textures, framebuffer, buffers and shaders of `window`'s context.
  void ReleaseGraphicsResources(vtkWindow* window) override;

  ///@{
  /// Diagnostics of the last build and render (see also vtkAMRKdTreeVolumeMapper).
  /// Atlas texture dimensions, and the bytes of the data textures (the atlas: the multi-pass
  /// method has no tree textures). The RGBA32F accumulation target (16 bytes per viewport pixel)
  /// is counted apart.
  void GetAtlasDimensions(int dims[3]) override;
  long long GetTextureBytes() override;
  long long GetAccumulationBytes();
  /// kD-tree nodes and data nodes (types (a) and (b)) of the current hierarchy.
  long long GetNumberOfKdNodes() override;
  long long GetNumberOfDataNodes() override;
  /// Draws (passes) of the last frame: the tree's leaves with data, one per data node drawn.
  long long GetLastNumberOfPasses();
  /// CPU seconds of the last frame's front-to-back ordering of the nodes.
  double GetLastOrderSeconds();
  ///@}

protected:
  vtkMultiPassAMRVolumeMapper();
  ~vtkMultiPassAMRVolumeMapper() override;

  bool BuildData(vtkOverlappingAMR* amr, const std::string& array, bool mayRefresh, bool& refreshed,
    std::string& error) override;
  void GetBuiltBounds(double bounds[6]) override;

private:
  vtkMultiPassAMRVolumeMapper(const vtkMultiPassAMRVolumeMapper&) = delete;
  void operator=(const vtkMultiPassAMRVolumeMapper&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
