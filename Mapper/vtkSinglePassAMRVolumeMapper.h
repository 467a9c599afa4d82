// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRVolumeMapper
 * @brief   single-pass GPU raycaster for vtkOverlappingAMR (Kaehler & Abel 2013)
 *
 * Renders a structured AMR hierarchy at its native resolution in one fragment-shader pass:
 * the hierarchy is decomposed into a kD-tree of non-overlapping same-level blocks, the tree is
 * encoded into two RG32UI 3D textures, every grid's cells are copied as one brick into a packed
 * R32F atlas, and per pixel the shader walks the tree with kd-restart, samples each ray segment
 * nearest-cell at the rate of its level (about one sample per cell) and composites front to back.
 *
 * Input: vtkOverlappingAMR with cell data (one port). The scalars are the array selected with
 * SelectScalarArray(name) (vtkAbstractVolumeMapper's by-name selection); without a selection the
 * first cell array of the first non-empty block is used. Multi-component arrays render the
 * component ArrayComponent, or their magnitude when it is -1 (the default).
 *
 * Appearance comes from the vtkVolumeProperty: the colour (or grey) transfer function and the
 * scalar opacity function of component 0, tabulated over the union of their ranges (values beyond
 * clamp to the end points), and ScalarOpacityUnitDistance (a sample standing for a ray length dt
 * has opacity 1 - (1 - a)^(dt / unit)). Blend modes: composite, maximum, minimum and average
 * intensity, and iso-surfaces (ISOSURFACE_BLEND with vtkVolumeProperty::GetIsoSurfaceValues(), 1
 * to 8 values, composited semi-transparently with the transfer function's colour and opacity at
 * each value). ShadeOn (with Ambient, Diffuse, Specular, SpecularPower of component 0) lights
 * composite samples and iso-surface hits with gradients taken by central differences through the
 * kD-tree, under the first switched-on light of the renderer (headlight, camera or scene light;
 * positional lights as point lights: cone angle and attenuation are ignored). Shadow rays
 * (SetShadows) attenuate that light by the transmittance toward it. Gradient opacity, cropping and
 * clipping planes are ignored.
 *
 * Rebuild policy: the hierarchy conversion, kD-tree, packing and texture upload happen only when
 * the input data object, its modification time, the array selection or the sample-independent
 * settings change; camera and transfer-function changes only update uniforms and the small
 * transfer-function texture.
 *
 * Opaque geometry drawn before the volume clips the rays (its depth buffer is copied once per
 * frame). The volume's own transform (vtkProp3D matrix) is honoured; distances, sampling and
 * opacity correction are then measured in model units.
 *
 * Errors (no input, missing array, hierarchy the layout cannot encode, atlas larger than
 * GL_MAX_3D_TEXTURE_SIZE, shader compile or link failure) are reported with vtkErrorMacro and
 * GetLastError(); nothing is drawn.
 */
#ifndef vtkSinglePassAMRVolumeMapper_h
#define vtkSinglePassAMRVolumeMapper_h

#include "vtkSinglePassAMRModule.h" // for export macro
#include "vtkVolumeMapper.h"

#include <string> // for IsRenderSupported

class vtkOverlappingAMR;
class vtkRenderWindow;

class VTKSINGLEPASSAMR_EXPORT vtkSinglePassAMRVolumeMapper : public vtkVolumeMapper
{
public:
  static vtkSinglePassAMRVolumeMapper* New();
  vtkTypeMacro(vtkSinglePassAMRVolumeMapper, vtkVolumeMapper);
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

  /// Renders the volume. Called by vtkVolume during the volumetric pass.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /// Frees the textures, buffers and shader of `window`'s context.
  void ReleaseGraphicsResources(vtkWindow* window) override;

#ifndef __VTK_WRAP__
  /// Whether `window` offers what the mapper needs: an OpenGL 3.2 core context (integer
  /// textures, GLSL 1.50). When it does not, `why` says what is missing.
  static bool IsRenderSupported(vtkRenderWindow* window, std::string* why = nullptr);
#endif

  ///@{
  /// Diagnostics of the last build and render.
  /// GetLastError: empty after a successful Render(), else one line naming the problem.
  const char* GetLastError();
  /// Seconds spent converting, building the kD-tree, packing and encoding (CPU), and uploading.
  double GetLastBuildSeconds();
  double GetLastUploadSeconds();
  /// Number of times the data textures were (re)built; camera or transfer-function changes must
  /// not increase it.
  int GetNumberOfBuilds();
  /// Atlas texture dimensions and the bytes of all data textures (atlas + tree + data nodes).
  void GetAtlasDimensions(int dims[3]);
  long long GetTextureBytes();
  /// kD-tree nodes and data nodes of the current hierarchy.
  long long GetNumberOfKdNodes();
  long long GetNumberOfDataNodes();
  ///@}

  ///@{
  /**
   * Level of detail at the kD-tree's type (a) nodes: the traversal stops descending when one cell
   * of the node's data level projects to fewer than this many pixels where the ray enters the
   * node, and renders the node at that coarser level. 0 (the default) always renders the finest
   * level. Changing it never rebuilds the textures.
   */
  vtkSetClampMacro(LODThreshold, double, 0.0, 1e6);
  vtkGetMacro(LODThreshold, double);
  ///@}

  ///@{
  /**
   * Shadow rays (default off): from every composite sample or iso-surface hit a secondary ray
   * toward the light (up to a positional light, or out of the root box along a directional one)
   * samples the scalar through the kD-tree every ShadowSampleDistance and scales the light's
   * diffuse and specular contribution by the transmittance (opacity corrected with
   * ScalarOpacityUnitDistance). Without ShadeOn the sample is lit as if facing the light.
   * Applies to composite and iso-surface blending.
   */
  vtkSetMacro(Shadows, bool);
  vtkGetMacro(Shadows, bool);
  vtkBooleanMacro(Shadows, bool);
  ///@}

  ///@{
  /// Step of the shadow rays in model units; 0 (default) uses the smallest edge of a level-0 cell.
  vtkSetClampMacro(ShadowSampleDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(ShadowSampleDistance, double);
  ///@}

protected:
  vtkSinglePassAMRVolumeMapper();
  ~vtkSinglePassAMRVolumeMapper() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;

  int ArrayComponent = -1;
  double SampleDistanceFactor = 1.0;
  bool UseDepthBuffer = true;
  int MaximumAtlasSize = 0;
  double LODThreshold = 0.0;
  bool Shadows = false;
  double ShadowSampleDistance = 0.0;

private:
  vtkSinglePassAMRVolumeMapper(const vtkSinglePassAMRVolumeMapper&) = delete;
  void operator=(const vtkSinglePassAMRVolumeMapper&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
