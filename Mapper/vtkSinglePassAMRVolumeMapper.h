// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRVolumeMapper
 * @brief   single-pass GPU raycaster for vtkOverlappingAMR (Kaehler & Abel 2013)
 *
 * Renders a structured AMR hierarchy at its native resolution in one shader pass (a compute
 * shader, or a fragment shader: SetRayCaster):
 * the hierarchy is decomposed into a kD-tree of non-overlapping same-level blocks, the tree is
 * encoded into two RG32UI 3D textures, every grid's cells become one brick, and per pixel the
 * shader walks the tree with kd-restart, samples each ray segment nearest-cell at the rate of its
 * level (about one sample per cell) and composites front to back.
 *
 * Data storage (paper section 5), chosen with SetDataStorage:
 * - PACKED_ATLAS: all bricks packed into one R32F 3D texture (the data nodes store the atlas
 *   texel of their lower corner);
 * - BINDLESS_TEXTURES: one R32F 3D texture per brick, reached through a 64-bit
 *   GL_ARB_bindless_texture handle kept resident and stored in an RG32UI "handles" texture
 *   indexed by the data node's brick index. A handle that differs between the invocations of one
 *   subgroup is only valid with GL_NV_gpu_shader5 (DIRECT_ACCESS); elsewhere the shader serves
 *   one distinct handle at a time with GL_ARB_shader_ballot (WATERFALL_ACCESS, a loop over
 *   readFirstInvocationARB). SetBindlessAccess forces either.
 * - LINEAR_BRICKS: every brick's texels back to back in 2D R32F textures (no packing, no gaps),
 *   found through an RG32UI brick table (amrsp::LinearBrickLayout): a brick's neighbouring
 *   texels are near in memory, which is what a CPU driver such as Mesa's llvmpipe reads fastest.
 * - AUTO_STORAGE (default): bindless where the extension exists and the atlas cannot be built or
 *   would leave more than AutoBindlessWaste of its texels unused; else linear bricks where the
 *   context is a CPU driver (Mesa's llvmpipe, softpipe, or zink on lavapipe) and the grid data
 *   holds at least AutoLinearBytes, or where the atlas cannot be built and bindless cannot run;
 *   packing otherwise.
 * When bindless is requested and cannot run (extension missing, neither access mode available,
 * or more grids than the driver can hold: Mesa's zink holds 1023, and frees a released set's
 * handles only later, so a new set there must also leave room for the largest earlier set of the
 * context), the mapper renders with the packed atlas and says so once with a VTK warning
 * (GetBindlessFallbackReason).
 * GetLastDataStorage() tells what rendered the last frame. The rule is decided in one place,
 * vtkSinglePassAMRStorageChoice::Choose (private; Mapper.StorageChoice tests it case by case).
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
 * (SetShadows) attenuate that light by the transmittance toward it. Composite rays stop at
 * OpacityThreshold (early ray termination) and skip data nodes whose value range is transparent
 * (EmptySpaceSkipping). Gradient opacity, cropping and clipping planes are ignored.
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

#include "vtkAMRKdTreeVolumeMapper.h"
#include "vtkSinglePassAMRModule.h" // for export macro

#include <string> // for IsBindlessSupported

class vtkRenderWindow;

class VTKSINGLEPASSAMR_EXPORT vtkSinglePassAMRVolumeMapper : public vtkAMRKdTreeVolumeMapper
{
public:
  static vtkSinglePassAMRVolumeMapper* New();
  vtkTypeMacro(vtkSinglePassAMRVolumeMapper, vtkAMRKdTreeVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// How the grid data reaches the GPU (see the class description).
  enum DataStorageMode
  {
    AUTO_STORAGE = 0,
    PACKED_ATLAS = 1,
    BINDLESS_TEXTURES = 2,
    LINEAR_BRICKS = 3
  };
  /// How the bindless shader reads a brick whose handle may differ between invocations.
  enum BindlessAccessMode
  {
    AUTO_ACCESS = 0,     ///< direct with GL_NV_gpu_shader5, else waterfall with ARB_shader_ballot
    DIRECT_ACCESS = 1,   ///< sampler3D(handle) as is; wrong images where handles must be uniform
    WATERFALL_ACCESS = 2 ///< one distinct handle per loop iteration (GL_ARB_shader_ballot)
  };

  ///@{
  /// Storage of the grid data: AUTO_STORAGE (default), PACKED_ATLAS, BINDLESS_TEXTURES or
  /// LINEAR_BRICKS. Changing it re-uploads the data textures (the kD-tree is not rebuilt).
  vtkSetClampMacro(DataStorage, int, AUTO_STORAGE, LINEAR_BRICKS);
  vtkGetMacro(DataStorage, int);
  void SetDataStorageToAuto() { this->SetDataStorage(AUTO_STORAGE); }
  void SetDataStorageToPackedAtlas() { this->SetDataStorage(PACKED_ATLAS); }
  void SetDataStorageToBindlessTextures() { this->SetDataStorage(BINDLESS_TEXTURES); }
  void SetDataStorageToLinearBricks() { this->SetDataStorage(LINEAR_BRICKS); }
  ///@}

  ///@{
  /// Access mode of the bindless shader: AUTO_ACCESS (default), DIRECT_ACCESS, WATERFALL_ACCESS.
  vtkSetClampMacro(BindlessAccess, int, AUTO_ACCESS, WATERFALL_ACCESS);
  vtkGetMacro(BindlessAccess, int);
  ///@}

  ///@{
  /// AUTO_STORAGE picks bindless (where available) when more than this fraction of the packed
  /// atlas's texels would be unused (default 0.25), or when the atlas cannot be built at all.
  vtkSetClampMacro(AutoBindlessWaste, double, 0.0, 1.0);
  vtkGetMacro(AutoBindlessWaste, double);
  ///@}

  ///@{
  /// AUTO_STORAGE picks the linear bricks on a CPU driver when the grid data holds at least this
  /// many bytes (default 64 MiB: below about 20 MB llvmpipe's caches hold the packed atlas and
  /// packing renders as fast or faster; docs/performance.md, "Linear bricks against packing").
  vtkSetClampMacro(AutoLinearBytes, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(AutoLinearBytes, vtkIdType);
  ///@}

  /// Renders the volume. Called by vtkVolume during the volumetric pass.
  void Render(vtkRenderer* ren, vtkVolume* vol) override;

  /// Frees the textures, buffers and shader of `window`'s context.
  void ReleaseGraphicsResources(vtkWindow* window) override;

#ifndef __VTK_WRAP__
  /// Whether `window`'s context can render with BINDLESS_TEXTURES: GL_ARB_bindless_texture and
  /// at least one access mode (GL_NV_gpu_shader5 for direct, GL_ARB_shader_ballot for waterfall).
  /// When it cannot, `why` says what is missing.
  static bool IsBindlessSupported(vtkRenderWindow* window, std::string* why = nullptr);
#endif

  ///@{
  /// What rendered the last frame: PACKED_ATLAS, BINDLESS_TEXTURES or LINEAR_BRICKS (-1 before the
  /// first successful Render), and for bindless DIRECT_ACCESS or WATERFALL_ACCESS (-1 for packing).
  int GetLastDataStorage();
  int GetLastBindlessAccess();
  /// Whether the last frame's rays followed the tree's ropes (Ropes on, a build with ropes, the
  /// level of detail off).
  bool GetLastRopes();
  /// Why the last frame rendered with the atlas although BINDLESS_TEXTURES was asked for (the
  /// missing extension, or a driver limit); empty otherwise.
  const char* GetBindlessFallbackReason();
  /// "packing", "bindless", "linear" or "none"; "direct", "waterfall" or "none".
  static const char* GetDataStorageName(int storage);
  static const char* GetBindlessAccessName(int access);
  ///@}

  ///@{
  /// Diagnostics of the last build and render (see also vtkAMRKdTreeVolumeMapper).
  /// Atlas texture dimensions (0 when no atlas could be packed) and the bytes of all data
  /// textures uploaded for the last frame (tree + data nodes + atlas, or + bricks + handles).
  void GetAtlasDimensions(int dims[3]) override;
  long long GetTextureBytes() override;
  /// Bytes either storage needs for the current data, whichever rendered (the paper's Table 2
  /// "GPU memory": tree textures + grid data). Packing is 0 when no atlas could be packed.
  long long GetPackedTextureBytes();
  long long GetBindlessTextureBytes();
  /// Fraction of the packed atlas's texels that hold no brick (0 when no atlas).
  double GetAtlasWaste();
  /// Atlas textures (pages) of the packed storage (MaximumAtlasPageBytes); 0 before a build and
  /// when the build packs no atlas (LINEAR_BRICKS).
  int GetNumberOfAtlasPages();
  /// 2D textures (pages) of the linear storage; 0 unless it rendered last.
  int GetNumberOfLinearPages();
  /// kD-tree nodes and data nodes of the current hierarchy.
  long long GetNumberOfKdNodes() override;
  long long GetNumberOfDataNodes() override;
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
   * Interactive frames, with VTK's names and meanings (vtkGPUVolumeRayCastMapper,
   * vtkSmartVolumeMapper). With AutoAdjustSampleDistances on (the default), a frame for which the
   * volume has less than one second allocated (vtkRenderer gives it 1 / DesiredUpdateRate of the
   * render window, shared among the props: ParaView's interactive renders ask 5 frames a second,
   * VTK's interactor 15) holds that budget: it casts one ray every ImageSampleDistance pixels per
   * axis (between MinimumImageSampleDistance and MaximumImageSampleDistance, the finest of the
   * rungs 1, 1.5, 2, 3, 4, 6, 8, 12, 16 that the previous frames' measured times predict to fit),
   * magnifies that image bilinearly over the viewport, and with InteractiveAdjustSampleDistances
   * on (the default) also multiplies the sample distance along the rays by the same factor. Still
   * frames (one second or more allocated) are drawn at full quality, unchanged. With
   * AutoAdjustSampleDistances off, every frame casts its rays every ImageSampleDistance pixels
   * (default 1: one ray per pixel). The cost model is amrsp::InteractiveQuality's.
   */
  vtkSetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(AutoAdjustSampleDistances, vtkTypeBool);
  vtkSetClampMacro(ImageSampleDistance, float, 1.0f, 100.0f);
  vtkGetMacro(ImageSampleDistance, float);
  vtkSetClampMacro(MinimumImageSampleDistance, float, 1.0f, 100.0f);
  vtkGetMacro(MinimumImageSampleDistance, float);
  vtkSetClampMacro(MaximumImageSampleDistance, float, 1.0f, 100.0f);
  vtkGetMacro(MaximumImageSampleDistance, float);
  vtkSetMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  vtkGetMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  vtkBooleanMacro(InteractiveAdjustSampleDistances, vtkTypeBool);
  ///@}

  ///@{
  /**
   * What the last frame did: whether it was interactive (see AutoAdjustSampleDistances), its
   * image sample distance and sample-distance scale (1 and 1 at full quality), its measured
   * seconds from the start of the ray casting to its glFinish (0 with AutoAdjustSampleDistances
   * off), and the seconds allocated to it.
   */
  bool GetLastFrameInteractive();
  double GetLastImageSampleDistance();
  double GetLastSampleDistanceScale();
  double GetLastFrameSeconds();
  double GetLastFrameBudget();
  ///@}

  ///@{
  /**
   * GPU memory for the textures of time steps shown before (default 0: only the current one).
   * When the input changes to a data object (the same object, unmodified) whose textures are
   * kept, it is shown without a build or an upload: playing a series again, e.g. from
   * ParaView's animation cache, costs a frame per step. The least recently used steps are
   * dropped beyond this many bytes (their textures, tree included, as GetTextureBytes counts
   * them). Steps of one structure share their tree textures. The bindless storage keeps no
   * steps (its resident handles are limited). Changing the array, component or atlas limits
   * drops them all. GetNumberOfKeptStepHits counts the steps shown from them.
   */
  vtkSetClampMacro(MaximumKeptStepBytes, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(MaximumKeptStepBytes, vtkIdType);
  int GetNumberOfKeptStepHits();
  /// Kept steps now, and the bytes of their textures.
  int GetNumberOfKeptSteps();
  vtkIdType GetKeptStepBytes();
  ///@}

  ///@{
  /**
   * Values of the last build's input that the conversion read in place, borrowed from the
   * blocks' one-component float arrays without ghost layers, and values it copied (other types,
   * components, ghost layers, vertex data made continuous). In situ, a simulation that hands
   * over such float arrays is copied only into the GPU's textures.
   */
  vtkGetMacro(LastBorrowedValues, vtkIdType);
  vtkGetMacro(LastCopiedValues, vtkIdType);
  ///@}

  ///@{
  /**
   * Early ray termination (composite blending): a ray stops once its accumulated opacity reaches
   * this value, in [0, 1]. The default 0.999 changes no 8-bit channel by more than 0.26 of 255;
   * 1 never stops a ray early. A pixel whose ray stopped at opacity A misses at most (1 - A) of
   * any channel.
   */
  vtkSetClampMacro(OpacityThreshold, double, 0.0, 1.0);
  vtkGetMacro(OpacityThreshold, double);
  ///@}

  ///@{
  /**
   * Empty-space skipping (composite blending; default on): the minimum and maximum scalar of
   * every data node's block are kept on the CPU (built with the data, 8 bytes per data node);
   * whenever the transfer function is re-tabulated, the nodes whose range has zero opacity
   * anywhere in the table are flagged in a small R8 texture indexed like the data nodes, and
   * the shader skips their ray segments (a transfer-function change never rebuilds the tree or
   * the ranges). Skipped samples would have had zero opacity, so the image does not change.
   */
  vtkSetMacro(EmptySpaceSkipping, bool);
  vtkGetMacro(EmptySpaceSkipping, bool);
  vtkBooleanMacro(EmptySpaceSkipping, bool);
  ///@}

  ///@{
  /**
   * Diagnostic output (default off): instead of colours, every pixel of the volume is written
   * opaque with the shader's own work counts for its ray, each an exact 8-bit value (counts above
   * 255 saturate): red = data segments skipped as empty space, green = 255 when the ray stopped
   * early at the opacity threshold (composite blending with a threshold below 1, as
   * amrsp::RenderStats counts it) and 0 otherwise, blue = data segments the ray reached (skipped
   * ones included). Summed over the image these equal the CPU kD-tree integrator's
   * SkippedSegments, TerminatedRays and DataSegments for the same view, which is how the tests
   * show that the accelerations really happen on the GPU. Pixels the volume does not cover keep
   * the background.
   */
  vtkSetMacro(AccelerationCountsOutput, bool);
  vtkGetMacro(AccelerationCountsOutput, bool);
  vtkBooleanMacro(AccelerationCountsOutput, bool);
  ///@}

  ///@{
  /**
   * Neighbour links ("ropes", Popov et al. 2007; default on): a ray that leaves a kD leaf
   * through one face continues from the node its rope names instead of descending again from
   * the restart node, which saves about two thirds of the tree levels descended per segment on
   * the paper's datasets (amrsp/KdTreeRopes.h, docs/performance.md). The image is the same
   * either way. Used where the build has them (refinement by powers of two) and the level of
   * detail is off; an RGBA32UI texture of 48 bytes per kD node.
   */
  vtkSetMacro(Ropes, bool);
  vtkGetMacro(Ropes, bool);
  vtkBooleanMacro(Ropes, bool);
  ///@}

  /// How the shader marches a ray (RayLoop).
  enum RayLoops
  {
    NESTED_LOOPS = 0, ///< per segment a descent loop, then a sample loop
    FLAT_LOOP = 1,    ///< one loop of single descent steps, segment set-ups and samples
    AUTO_LOOP = 2     ///< the nested loops (measured faster on an NVIDIA H200 and on llvmpipe)
  };

  ///@{
  /**
   * The shader's loop structure (default NESTED_LOOPS). A GPU runs a fragment shader in groups
   * of 32 pixels that share each loop iteration: with nested loops a group waits, per segment,
   * for its longest descent and then its longest sample run; the flat loop (Aila and Laine's
   * "if-if") lets every lane take its own next operation each iteration, at the price of both
   * branches where lanes disagree. The images and counts are the same. AUTO_LOOP takes the nested
   * loops: the work counters predict fewer lockstep steps for the flat loop
   * (amrsp/WorkCounters.h), but it measured 10-39 % slower on an NVIDIA H200 and 30-42 % slower
   * on llvmpipe (docs/performance.md, "On an NVIDIA H200"). GetLastRayLoop tells which loop the
   * last frame used (NESTED_LOOPS or
   * FLAT_LOOP; GetRayLoopName gives its word).
   */
  vtkSetClampMacro(RayLoop, int, NESTED_LOOPS, AUTO_LOOP);
  vtkGetMacro(RayLoop, int);
  int GetLastRayLoop();
  /// "nested", "flat", "auto" (amrsp::RayLoopName), or "none".
  static const char* GetRayLoopName(int loop);
  ///@}

  /// Which shader stage casts the rays (RayCaster); the values of amrsp::RayCaster.
  enum RayCasters
  {
    FRAGMENT_CASTER = 0, ///< a fragment shader over the proxy box's back faces
    COMPUTE_CASTER = 1,  ///< a compute shader over the rays' image, then one composite draw
    AUTO_CASTER = 2      ///< compute on a GPU with compute shaders, fragment on a CPU driver
  };

  ///@{
  /**
   * The shader stage that casts the rays (default AUTO_CASTER). FRAGMENT_CASTER runs the ray of
   * each pixel the proxy box's back faces cover in a fragment shader and blends it into the
   * frame. COMPUTE_CASTER runs one compute-shader invocation per pixel of the rays' image, in
   * work groups of 8 x 4 pixels, writes premultiplied colour to an RGBA32F image and composites
   * it over the frame with one quad, blended as the fragment caster blends (depth of opaque
   * geometry, reduced interactive images, every storage and feature alike): the same bytes on the
   * screen. On a datacenter GPU the compute caster runs on every multiprocessor, where fragments
   * run only on the few that rasterise (NVIDIA's H100 and H200: 4 of 132 SMs). AUTO_CASTER takes
   * the compute caster on a GPU with compute shaders and the fragment caster on a CPU driver
   * (docs/performance.md, "The compute caster"). A context without compute shaders (OpenGL 4.3,
   * or 4.2 with GL_ARB_compute_shader) renders with the fragment caster and says so once
   * (GetRayCasterFallbackReason). GetLastRayCaster tells which caster the last frame used.
   */
  vtkSetClampMacro(RayCaster, int, FRAGMENT_CASTER, AUTO_CASTER);
  vtkGetMacro(RayCaster, int);
  /// (FRAGMENT_CASTER or COMPUTE_CASTER; -1 before the first successful Render)
  int GetLastRayCaster();
  /// Why the last frame was cast by the fragment shader although COMPUTE_CASTER or AUTO_CASTER
  /// was asked for and the context has no compute shaders; empty otherwise.
  const char* GetRayCasterFallbackReason();
  /// "fragment", "compute", "auto" (amrsp::RayCasterName), or "none".
  static const char* GetRayCasterName(int caster);
  ///@}

  ///@{
  /**
   * Diagnostic output (default off), on contexts with GL_NV_shader_thread_group (NVIDIA): every
   * ray that meets the volume writes, opaque and 8-bit exact, where it ran instead of its colour:
   * red the multiprocessor (gl_SMIDNV), green the warp slot on it (gl_WarpIDNV), blue the chip's
   * multiprocessor count (gl_SMCountNV). Counting the distinct values over a frame shows how much
   * of the GPU a caster uses (on an H100 fragments run on the 4 SMs that rasterise). Elsewhere a
   * frame with the probe is an error naming the missing extension. Takes precedence over the
   * work-count outputs.
   */
  vtkSetMacro(OccupancyProbe, bool);
  vtkGetMacro(OccupancyProbe, bool);
  vtkBooleanMacro(OccupancyProbe, bool);
  ///@}

  /// Diagnostic ablations (DiagnosticAblation).
  enum Ablations
  {
    NO_ABLATION = 0,    ///< the frame as it is (the default)
    TRAVERSAL_ONLY = 1, ///< the tree is traversed, but no data segment is sampled
    SAMPLING_ONLY = 2   ///< each ray samples one brick, without traversing the tree further
  };

  ///@{
  /**
   * Diagnostic ablation (default NO_ABLATION), to locate where a frame's GPU time goes; the
   * images are not meant to be looked at. TRAVERSAL_ONLY walks the tree as usual but adds a
   * constant per data segment instead of its samples (no brick or transfer-function reads).
   * SAMPLING_ONLY descends once to the ray's first leaf with data and samples that brick
   * DiagnosticAblationSamples times over the rest of the ray (clamped into the brick), with
   * compositing and early termination as usual, and no further traversal. LoopCountOutput
   * counts what an ablated frame did.
   */
  vtkSetClampMacro(DiagnosticAblation, int, NO_ABLATION, SAMPLING_ONLY);
  vtkGetMacro(DiagnosticAblation, int);
  vtkSetClampMacro(DiagnosticAblationSamples, int, 1, 1 << 20);
  vtkGetMacro(DiagnosticAblationSamples, int);
  ///@}

  /// What LoopCountOutput writes.
  enum LoopCounts
  {
    NO_LOOP_COUNT = 0,      ///< colours (the default)
    SEGMENT_COUNT = 1,      ///< iterations of the segment loop (one per kd-restart)
    DESCENT_STEP_COUNT = 2, ///< iterations of the descent loop (tree levels descended)
    SAMPLE_COUNT = 3        ///< iterations of the sample loop
  };

  ///@{
  /**
   * Diagnostic output (default NO_LOOP_COUNT): instead of colours, every pixel of the volume is
   * written opaque with one count of its ray's loops as an exact 24-bit integer, red the low
   * byte, green the middle and blue the high one. Summed over the image they equal the segments,
   * descent steps and samples of amrsp::MeasureSinglePassWork for the same view (the CPU mirror
   * of the shader), which is how the cost model of amrsp/WorkCounters.h is tied to the GPU. Takes
   * precedence over AccelerationCountsOutput.
   */
  vtkSetClampMacro(LoopCountOutput, int, NO_LOOP_COUNT, SAMPLE_COUNT);
  vtkGetMacro(LoopCountOutput, int);
  ///@}

  ///@{
  /**
   * Reconstruction of cell-centred data. NEAREST_CELL (the default, the paper's): the value of
   * the cell containing the sample. SMOOTH_CELL: trilinear interpolation in the dual cell of the
   * sample's level (the 8 surrounding cell centres of that level), each corner the nearest value
   * of the finest cell containing it, found by point location in the kD-tree (so corners reach
   * into neighbouring bricks and other levels); continuous inside a level and across same-level
   * grids, with a jump across level boundaries of at most the field's change over one cell of
   * the finer level. Up to 8 tree descents per sample near node boundaries. Point data is
   * trilinear anyway and ignores it.
   */
  enum CellInterpolationModes
  {
    NEAREST_CELL = 0,
    SMOOTH_CELL = 1
  };
  vtkSetClampMacro(CellInterpolation, int, NEAREST_CELL, SMOOTH_CELL);
  vtkGetMacro(CellInterpolation, int);
  void SetCellInterpolationToNearest()
  {
    this->SetCellInterpolation(NEAREST_CELL);
  }
  void SetCellInterpolationToSmooth()
  {
    this->SetCellInterpolation(SMOOTH_CELL);
  }
  ///@}

  /// Diagnostic of empty-space skipping: how many data nodes the last rendered frame's transfer
  /// function makes transparent (the shader skips every segment through them), computed on the
  /// CPU with the shader's test (amrsp::TableRangeTransparent); 0 when skipping is off or the
  /// blend mode is not composite.
  long long GetNumberOfTransparentDataNodes();

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

  bool BuildData(vtkOverlappingAMR* amr, const std::string& array, bool mayRefresh, bool& refreshed,
    std::string& error) override;
  void GetBuiltBounds(double bounds[6]) override;
  bool BuildPacksBricks() override
  {
    return this->DataStorage != LINEAR_BRICKS;
  }

  double LODThreshold = 0.0;
  vtkTypeBool AutoAdjustSampleDistances = 1;
  float ImageSampleDistance = 1.0f;
  float MinimumImageSampleDistance = 1.0f;
  float MaximumImageSampleDistance = 10.0f;
  vtkTypeBool InteractiveAdjustSampleDistances = 1;
  int DataStorage = AUTO_STORAGE;
  int BindlessAccess = AUTO_ACCESS;
  double AutoBindlessWaste = 0.25;
  vtkIdType AutoLinearBytes = vtkIdType(64) << 20;
  double OpacityThreshold = 0.999;
  bool EmptySpaceSkipping = true;
  bool AccelerationCountsOutput = false;
  int LoopCountOutput = NO_LOOP_COUNT;
  bool Ropes = true;
  vtkIdType MaximumKeptStepBytes = 0;
  vtkIdType LastBorrowedValues = 0;
  vtkIdType LastCopiedValues = 0;
  int RayLoop = NESTED_LOOPS;
  int RayCaster = AUTO_CASTER;
  bool OccupancyProbe = false;
  int DiagnosticAblation = NO_ABLATION;
  int DiagnosticAblationSamples = 256;
  int CellInterpolation = NEAREST_CELL;
  bool Shadows = false;
  double ShadowSampleDistance = 0.0;

private:
  vtkSinglePassAMRVolumeMapper(const vtkSinglePassAMRVolumeMapper&) = delete;
  void operator=(const vtkSinglePassAMRVolumeMapper&) = delete;

  class vtkInternals;
  vtkInternals* Internals;
};

#endif
