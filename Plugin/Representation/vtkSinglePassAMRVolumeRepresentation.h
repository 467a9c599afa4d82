// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRVolumeRepresentation
 * @brief   ParaView representation that volume-renders vtkOverlappingAMR at native resolution
 *
 * Renders its vtkOverlappingAMR input with vtkSinglePassAMRVolumeMapper (Kaehler & Abel 2013
 * single-pass raycasting of the hierarchy's kD-tree), instead of resampling the hierarchy onto
 * one uniform grid as ParaView's AMR "Volume" representation (vtkAMRStreamingVolumeRepresentation)
 * does. It is added to ParaView's `AMRRepresentation` as the representation type
 * "AMR Single-Pass Volume" by the plugin's server-manager XML.
 *
 * Appearance: the vtkVolumeProperty of vtkVolumeRepresentation. ParaView's colour map
 * (LookupTable, forwarded with SetColor) and the scalar-opacity function of the coloured array
 * (ScalarOpacityFunction, SetScalarOpacity), and ScalarOpacityUnitDistance, are shared with
 * ParaView's own volume representation, so the colour-map editor drives both. The coloured array
 * (ColorArrayName, i.e. SetInputArrayToProcess(0, ...)) is the array the mapper renders; a vector
 * array renders the component the colour map selects, or its magnitude. Without a coloured array
 * nothing is drawn (as ParaView's Volume representation); switching a display to the type picks
 * one on the client (vtkSMSinglePassAMRVolumeRepresentationProxy).
 *
 * Data movement: RequestData shallow-copies the input; REQUEST_UPDATE hands that copy to the view
 * with vtkPVView::SetPiece, and REQUEST_RENDER connects the mapper to the piece the view delivered
 * (vtkPVRenderView::GetPieceProducer). In a builtin session (pvpython, the GUI without a server,
 * pvbatch on one rank) the delivered piece is the copy itself: nothing is moved or duplicated.
 * With one pvserver, ParaView's delivery does the rest: below the remote-render threshold the
 * whole vtkOverlappingAMR is sent to the client, which renders it; above it the server renders
 * and sends the image (both tested). Several MPI ranks (pvbatch or pvserver under mpiexec):
 * each rank holds the whole metadata but only some blocks' data. With PARALLEL_REGIONS (the
 * default; pvbatch only) RequestData splits the root box into one convex region per rank and
 * redistributes the blocks' parts (vtkSinglePassAMRRegionSplit); each rank renders its region and
 * reports it as its bounds, and the view composites the ranks' images in visibility order
 * (IceT's ordered compositing by those bounds). With PARALLEL_GATHER, and always on a
 * multi-rank pvserver (whose view may deliver the data to the client instead of rendering on
 * the ranks), rank 0 gathers every block (vtkSinglePassAMRGather) and renders the whole volume
 * while the other ranks deliver an empty hierarchy and draw nothing.
 * Not handled: block streaming, and LOD geometry while interacting (the mapper's own
 * LODThreshold is the level of detail).
 *
 * Invariants: when the mapper renders, its input is the piece the view delivered for the last
 * REQUEST_UPDATE (the view may ask the prop for its bounds before it delivers, while its producer
 * holds an empty placeholder: the mapper then reports no bounds and keeps its textures). The
 * representation re-executes, and the mapper rebuilds its textures, only when the input data
 * changes; never for colour-map, opacity, camera, blend-mode, sampling, LOD or visibility changes.
 */
#ifndef vtkSinglePassAMRVolumeRepresentation_h
#define vtkSinglePassAMRVolumeRepresentation_h

#include "vtkSinglePassAMRParaViewModule.h" // for export macro
#include "vtkNew.h"                         // for ivar
#include "vtkSmartPointer.h"                // for ivar
#include "vtkVolumeRepresentation.h"

#include <map>    // for ivar
#include <string> // for ivar
#include <vector> // for ivar

class vtkMultiPassAMRVolumeMapper;
class vtkOverlappingAMR;
class vtkPVRenderView;
class vtkPolyData;
class vtkSinglePassAMRVolumeMapper;

class VTKSINGLEPASSAMRPARAVIEW_EXPORT vtkSinglePassAMRVolumeRepresentation
  : public vtkVolumeRepresentation
{
public:
  static vtkSinglePassAMRVolumeRepresentation* New();
  vtkTypeMacro(vtkSinglePassAMRVolumeRepresentation, vtkVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Handles the view's passes: REQUEST_UPDATE gives the view the data and its bounds,
   * REQUEST_RENDER connects the mapper to the delivered data and passes the array selection.
   */
  int ProcessViewRequest(vtkInformationRequestKey* request_type, vtkInformation* inInfo,
    vtkInformation* outInfo) override;

  ///@{
  /**
   * Forwarded to vtkSinglePassAMRVolumeMapper: sampling distance in cells of each ray segment's
   * level (1 = about one sample per cell), level-of-detail threshold in pixels (0 = always the
   * finest level), and blend mode (vtkVolumeMapper::BlendModes: composite, maximum, minimum or
   * average intensity; the mapper reports an error for the others).
   */
  void SetSampleDistanceFactor(double factor);
  double GetSampleDistanceFactor();
  void SetLODThreshold(double pixels);
  double GetLODThreshold();
  /// Interactive frames of the single-pass mapper, forwarded as they are named there
  /// (vtkSinglePassAMRVolumeMapper::SetAutoAdjustSampleDistances and the rest): while ParaView
  /// renders interactively (5 frames a second asked) a frame casts fewer rays and samples.
  void SetAutoAdjustSampleDistances(int on);
  void SetImageSampleDistance(double pixels);
  void SetMinimumImageSampleDistance(double pixels);
  void SetMaximumImageSampleDistance(double pixels);
  void SetInteractiveAdjustSampleDistances(int on);
  void SetBlendMode(int mode);
  int GetBlendMode();
  /// Single-pass mapper options (see vtkSinglePassAMRVolumeMapper): early ray termination,
  /// empty-space skipping, nearest (0) or smooth (1) reconstruction of cell data.
  void SetOpacityThreshold(double threshold);
  double GetOpacityThreshold();
  void SetEmptySpaceSkipping(bool on);
  bool GetEmptySpaceSkipping();
  void SetCellInterpolation(int mode);
  int GetCellInterpolation();
  /// The shader stage that casts the rays (vtkSinglePassAMRVolumeMapper::RayCasters; default
  /// AUTO_CASTER).
  void SetRayCaster(int caster);
  int GetRayCaster();
  /// The shader's ray loop (vtkSinglePassAMRVolumeMapper::RayLoops; default NESTED_LOOPS).
  void SetRayLoop(int loop);
  int GetRayLoop();
  ///@}

  ///@{
  /// Lighting, forwarded to the vtkVolumeProperty (the names and meaning of ParaView's Volume
  /// representation, whose properties these are shared with): gradient shading on/off and the
  /// Phong coefficients.
  void SetShade(bool on);
  void SetAmbient(double value);
  void SetDiffuse(double value);
  void SetSpecular(double value);
  void SetSpecularPower(double value);
  ///@}

  ///@{
  /// Shadow rays toward the renderer's light and their step in model units (0: a level-0 cell
  /// edge), forwarded to the single-pass mapper.
  void SetShadows(bool on);
  void SetShadowSampleDistance(double distance);
  ///@}

  ///@{
  /// Iso-surface values of the "Isosurface" blend mode (vtkVolumeProperty's contour values).
  void SetNumberOfIsosurfaces(int count);
  void SetIsosurfaceValue(int index, double value);
  ///@}

  /**
   * Rendering method. METHOD_AUTO: the single-pass mapper with the storage it chooses
   * (vtkSinglePassAMRVolumeMapper::AUTO_STORAGE; the rule is vtkSinglePassAMRStorageChoice's,
   * described with the mapper's DataStorage). METHOD_PACKING: the
   * single-pass mapper, packed atlas. METHOD_BINDLESS: the single-pass mapper, one texture per
   * brick through GL_ARB_bindless_texture handles (where the context lacks them it renders with the
   * atlas and warns once). METHOD_LINEAR: the single-pass mapper, the bricks back to back in 2D
   * textures (no packing; the fastest on CPU drivers such as llvmpipe). METHOD_MULTI_PASS:
   * vtkMultiPassAMRVolumeMapper (one draw per kD-tree data node, CPU traversal; composite blending
   * only, no level of detail). Each mapper keeps its own textures: switching to or from multi-pass
   * builds a mapper's textures only the first time it renders the current data; switching the
   * single-pass mapper's storage re-uploads its data. Values are stable (they are the proxy
   * property's values).
   */
  enum Methods
  {
    METHOD_AUTO = 0,
    METHOD_PACKING = 1,
    METHOD_MULTI_PASS = 2,
    METHOD_BINDLESS = 3,
    METHOD_LINEAR = 4,
  };
  void SetMethod(int method);
  vtkGetMacro(Method, int);

  /**
   * How several MPI ranks share the rendering. PARALLEL_REGIONS: each pvbatch rank renders one
   * convex region of the domain (regions balance the cells of all levels) and the images are
   * composited in visibility order. PARALLEL_GATHER: rank 0 gathers all blocks and renders alone.
   * A multi-rank pvserver always gathers. Changing it re-executes the representation. Values
   * are stable (the proxy property's values).
   */
  enum ParallelModes
  {
    PARALLEL_REGIONS = 0,
    PARALLEL_GATHER = 1,
  };
  void SetParallelMode(int mode);

  /// GPU memory, in MiB, for the textures of time steps shown before
  /// (vtkSinglePassAMRVolumeMapper::SetMaximumKeptStepBytes; default 0): playing a series again
  /// shows them without a build or an upload.
  void SetKeptStepsMiB(double mib);
  /// Steps shown from the kept textures so far (SinglePassKeptStepHits).
  int GetNumberOfKeptStepHits();
  vtkGetMacro(ParallelMode, int);

  /// The single-pass mapper (for tests and diagnostics).
  vtkSinglePassAMRVolumeMapper* GetVolumeMapper();
  /// The multi-pass mapper (for tests and diagnostics).
  vtkMultiPassAMRVolumeMapper* GetMultiPassMapper();

  ///@{
  /**
   * Diagnostics, also offered as information-only proxy properties (SinglePassRenderError,
   * SinglePassTextureBuilds) so that clients see them in every session type: of the mapper the
   * Method selects, its last error (empty after a successful render), and how many times it has
   * built
   * its data textures (camera, colour-map, opacity, blend-mode, sampling and LOD changes must
   * not increase it).
   */
  const char* GetLastRenderError();
  int GetNumberOfTextureBuilds();
  /// Of those builds, the ones that kept the structure and took new values only: a time step
  /// between regrids (SinglePassValueRefreshes).
  int GetNumberOfValueRefreshes();
  /// The single-pass mapper's last frame (vtkSinglePassAMRVolumeMapper::GetLastFrameInteractive
  /// and the rest): { interactive (0 or 1), image sample distance, sample-distance scale,
  /// allocated seconds, measured seconds }.
  double* GetLastFrameQuality() VTK_SIZEHINT(5);
  /// The last data change's CPU build (conversion, kD-tree, packing, encoding) and GPU upload,
  /// in seconds, of the mapper the Method selects (SinglePassLastBuildSeconds).
  double* GetLastBuildSeconds() VTK_SIZEHINT(2);
  /// The single-pass mapper's last build: input values it read in place and values it copied
  /// (vtkSinglePassAMRVolumeMapper::GetLastBorrowedValues; SinglePassLastInputValues).
  double* GetLastInputValues() VTK_SIZEHINT(2);
  /// Blocks of the hierarchy the mappers read that are not the block objects of this process's
  /// own copy of its input (SinglePassBlockCopies): 0 where the mappers read that copy (builtin
  /// sessions, pvbatch); every delivered block on a client that renders what a pvserver sent.
  int GetNumberOfBlockCopies();
  /// Array values (cell and point data) of the hierarchy the mappers read that do not lie in
  /// the memory of this process's input arrays (SinglePassCopiedValues): 0 where every block is
  /// the input's or shares its arrays; the pieces of other ranks' blocks and the blocks cut to
  /// this rank's region under MPI; everything a client received from a pvserver.
  double GetNumberOfCopiedValues();
  /// What rendered the last frame (SinglePassDataStorage): "packing", "bindless (waterfall)",
  /// "bindless (direct)", "multi-pass", or "none" before the first successful frame.
  const char* GetLastDataStorage();
  /// The caster of the last frame (SinglePassRayCaster): "fragment" or "compute"; "none" for the
  /// multi-pass method or before the first successful frame.
  const char* GetLastRayCaster();
  /// The ray loop of the last frame (SinglePassRayLoop): "nested" or "flat"; "none" for the
  /// multi-pass method or before the first successful frame.
  const char* GetLastRayLoop();
  ///@}

protected:
  vtkSinglePassAMRVolumeRepresentation();
  ~vtkSinglePassAMRVolumeRepresentation() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;

  /// Array selection, component and visibility, from the coloured array and the colour map.
  void UpdateMapperParameters();

  /// Points the prop at the mapper Method selects (and sets that mapper's storage).
  void UpdateMethod();

  /// A mapper's ProgressEvent during its build and upload (which run inside the view's render),
  /// reported as this representation's progress with the text "AMR Single-Pass Volume: STEP".
  /// ParaView registers the representation, not its mappers, with its progress handler
  /// (vtkSIProxy::CreateVTKObjects), which forwards it to the GUI's progress bar.
  void OnMapperProgress(vtkObject* caller, unsigned long event, void* callData);

  /// Reports once (rank 0) when several pvbatch ranks cannot render in parallel, a state in
  /// which ParaView 5.11 deadlocks at the first render (see the .cxx).
  void ReportParallelRenderingOff(vtkPVRenderView* view);

  vtkSmartPointer<vtkSinglePassAMRVolumeMapper> VolumeMapper;
  vtkSmartPointer<vtkMultiPassAMRVolumeMapper> MultiPassMapper;
  int Method = METHOD_AUTO;
  int ParallelMode = PARALLEL_REGIONS;
  /// The data to render, made by the last RequestData: a copy of the input that shares its
  /// blocks; with several ranks, this rank's region of the hierarchy, or (gathering) the whole
  /// hierarchy on rank 0 and an empty one on the others.
  vtkSmartPointer<vtkOverlappingAMR> Cache;
  /// The memory of the input blocks' arrays at the last RequestData, sorted (for
  /// GetNumberOfCopiedValues: never read through).
  std::vector<const void*> InputArrayMemory;
  /// With ParaView's animation caching (the view's UseCache, *Cache Geometry For Animation*) the
  /// view skips RequestData for a time step it has cached: what RequestData made for each cache
  /// key is kept here, and put back when the view shows that key again. Emptied as soon as the
  /// view stops caching.
  struct CachedStep
  {
    double Time; ///< the update time it was made for (NaN: none)
    vtkSmartPointer<vtkOverlappingAMR> Data;
    std::vector<const void*> InputArrayMemory;
    double Bounds[6];
    unsigned long Size;
    bool RendersLocally;
    bool Cropping;
  };
  std::map<double, CachedStep> CachedSteps;
  bool Executed = false;  ///< RequestData ran since the last REQUEST_UPDATE pass
  double CacheTime = 0.0; ///< the update time Cache was made for (NaN: none)
  /// Keeps or restores CachedSteps around the view's update pass (see CachedSteps).
  void FollowAnimationCache(vtkInformation* inInfo);
  /// False on the ranks other than 0 when gathering on rank 0: they draw nothing.
  bool RendersLocally = true;
  /// True where the process that renders is the one that holds the data (a builtin session,
  /// pvbatch): the mappers read Cache itself and the view is handed PlaceholderPiece. The view's
  /// delivery would shallow-copy the hierarchy twice (vtkPVDataDeliveryManager::SetPiece, then
  /// vtkMPIMoveData), each copy a new vtkUniformGrid per block. False in a pvserver (below the
  /// remote-render threshold the client renders the delivered hierarchy) and on its client.
  bool RendersFromCache = false;
  vtkNew<vtkPolyData> PlaceholderPiece; // empty
  bool ReportedParallelRenderingOff = false;
  // What is wrong with the delivered data itself (no blocks at all), said once per change in
  double LastFrameQuality[5] = { 0.0, 1.0, 1.0, 0.0, 0.0 };
  double LastBuildSeconds[2] = { 0.0, 0.0 };
  double LastInputValues[2] = { 0.0, 0.0 };
  // ParaView's output window and returned by GetLastRenderError before the mapper's error.
  std::string InputProblem;
  std::string ReportedInputProblem;
  std::string LastDataStorage; // GetLastDataStorage's text

private:
  vtkSinglePassAMRVolumeRepresentation(const vtkSinglePassAMRVolumeRepresentation&) = delete;
  void operator=(const vtkSinglePassAMRVolumeRepresentation&) = delete;
};

#endif
