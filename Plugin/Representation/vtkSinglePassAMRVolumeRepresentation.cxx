// SPDX-License-Identifier: BSD-3-Clause
#include "vtkSinglePassAMRVolumeRepresentation.h"

#include "vtkSinglePassAMRDataModel.h"

#include "vtkAbstractArray.h"
#include "vtkAlgorithmOutput.h"
#include "vtkCellData.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkContourValues.h"
#include "vtkDataObject.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLODProp3D.h"
#include "vtkMath.h"
#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkOverlappingAMR.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProcessModule.h"
#include "vtkPVDataRepresentationPipeline.h"
#include "vtkPVLODVolume.h"
#include "vtkPVLogger.h"
#include "vtkPVRenderView.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkSinglePassAMRGather.h"
#include "vtkAMRKdTreeVolumeMapper.h"
#include "vtkSinglePassAMRRegionSplit.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkStructuredData.h"
#include "vtkUniformGrid.h"
#include "vtkVolumeProperty.h"

#include "amrsp/DataStorage.h"
#include "amrsp/RayCaster.h"
#include "amrsp/RayLoop.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>

namespace model = vtkSinglePassAMRDataModel;

namespace
{
/**
 * vtkPVLODVolume refuses to render (its non-virtual CanRender) when a vtkVolumeMapper's
 * vtkDataSet input has no scalars, a guard for mappers that crash without them. An AMR input is
 * not a vtkDataSet, so that guard would always refuse: this prop renders without it.
 * vtkSinglePassAMRVolumeMapper checks its input and array itself (and reports what is missing
 * through GetLastError), and the representation hides the prop when no array is coloured.
 */
class vtkSinglePassAMRLODVolume : public vtkPVLODVolume
{
public:
  static vtkSinglePassAMRLODVolume* New();
  vtkTypeMacro(vtkSinglePassAMRLODVolume, vtkPVLODVolume);

  int RenderOpaqueGeometry(vtkViewport* viewport) override
  {
    const int rendered = this->LODProp->RenderOpaqueGeometry(viewport);
    this->EstimatedRenderTime = this->LODProp->GetEstimatedRenderTime();
    return rendered;
  }
  int RenderTranslucentPolygonalGeometry(vtkViewport* viewport) override
  {
    const int rendered = this->LODProp->RenderTranslucentPolygonalGeometry(viewport);
    this->EstimatedRenderTime = this->LODProp->GetEstimatedRenderTime();
    return rendered;
  }
  int RenderVolumetricGeometry(vtkViewport* viewport) override
  {
    const int rendered = this->LODProp->RenderVolumetricGeometry(viewport);
    this->EstimatedRenderTime = this->LODProp->GetEstimatedRenderTime();
    return rendered;
  }

protected:
  vtkSinglePassAMRLODVolume() = default;
  ~vtkSinglePassAMRLODVolume() override = default;

private:
  vtkSinglePassAMRLODVolume(const vtkSinglePassAMRLODVolume&) = delete;
  void operator=(const vtkSinglePassAMRLODVolume&) = delete;
};
vtkStandardNewMacro(vtkSinglePassAMRLODVolume);
} // namespace

namespace
{
/// Calls `visit` with every non-empty cell and point array of every block of `amr`.
void ForEachArray(vtkOverlappingAMR* amr, const std::function<void(vtkAbstractArray*)>& visit)
{
  if (!amr)
  {
    return;
  }
  for (unsigned int level = 0; level < amr->GetNumberOfLevels(); ++level)
  {
    for (unsigned int index = 0; index < model::NumberOfBlocks(amr, level); ++index)
    {
      vtkDataSet* block = model::Block(amr, level, index);
      if (!block)
      {
        continue;
      }
      for (vtkFieldData* data : { static_cast<vtkFieldData*>(block->GetCellData()),
             static_cast<vtkFieldData*>(block->GetPointData()) })
      {
        for (int a = 0; a < data->GetNumberOfArrays(); ++a)
        {
          vtkAbstractArray* array = data->GetAbstractArray(a);
          if (array && array->GetNumberOfValues() > 0)
          {
            visit(array);
          }
        }
      }
    }
  }
}

/// The memory of the arrays of `amr`'s blocks, sorted.
std::vector<const void*> ArrayMemory(vtkOverlappingAMR* amr)
{
  std::vector<const void*> memory;
  ForEachArray(amr, [&memory](vtkAbstractArray* a) { memory.push_back(a->GetVoidPointer(0)); });
  std::sort(memory.begin(), memory.end());
  return memory;
}
} // namespace

vtkStandardNewMacro(vtkSinglePassAMRVolumeRepresentation);

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeRepresentation::vtkSinglePassAMRVolumeRepresentation()
  : VolumeMapper(vtkSmartPointer<vtkSinglePassAMRVolumeMapper>::New())
  , MultiPassMapper(vtkSmartPointer<vtkMultiPassAMRVolumeMapper>::New())
{
  // replaces vtkVolumeRepresentation's prop (before anything else refers to it)
  this->Actor = vtkSmartPointer<vtkSinglePassAMRLODVolume>::New();
  this->Actor->SetProperty(this->Property);
  this->Actor->SetMapper(this->VolumeMapper);
  // No LOD mapper: while interacting the full mapper renders (its cost does not depend on the
  // data size the view's LOD threshold looks at, and SetLODThreshold is the mapper's own LOD).
  this->Actor->SetEnableLOD(0);
  for (vtkAlgorithm* mapper : { static_cast<vtkAlgorithm*>(this->VolumeMapper),
         static_cast<vtkAlgorithm*>(this->MultiPassMapper) })
  {
    mapper->AddObserver(
      vtkCommand::ProgressEvent, this, &vtkSinglePassAMRVolumeRepresentation::OnMapperProgress);
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::OnMapperProgress(
  vtkObject* caller, unsigned long, void* callData)
{
  vtkAMRKdTreeVolumeMapper* mapper = vtkAMRKdTreeVolumeMapper::SafeDownCast(caller);
  const char* step = mapper ? mapper->GetProgressText() : nullptr;
  if (!step)
  {
    return; // the executive's events around the mapper's input update, not a preparation's
  }
  // the mapper reports its build 0 to 1, then its upload 0 to 1: one run here, the build in
  // [0, 0.5] and the upload in [0.5, 1]
  const bool upload = mapper->GetProgressPhase() == vtkAMRKdTreeVolumeMapper::PROGRESS_UPLOAD;
  const double fraction = 0.5 * (*static_cast<const double*>(callData) + (upload ? 1.0 : 0.0));
  this->SetProgressText((std::string("AMR Single-Pass Volume: ") + step).c_str());
  this->UpdateProgress(fraction);
  if (fraction >= 1.0)
  {
    this->SetProgressText(nullptr);
  }
}

//------------------------------------------------------------------------------
vtkSinglePassAMRVolumeRepresentation::~vtkSinglePassAMRVolumeRepresentation() = default;

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkOverlappingAMR");
  // optional: on processes without the data (client, render server) there is no input
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkMath::UninitializeBounds(this->DataBounds);
  this->DataSize = 0;

  vtkOverlappingAMR* input = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkOverlappingAMR::GetData(inputVector[0], 0)
    : nullptr;
  vtkSmartPointer<vtkOverlappingAMR> cache;
  this->InputProblem.clear();
  vtkMultiProcessController* global = vtkMultiProcessController::GetGlobalController();
  if (input && model::NumberOfBlocks(input) == 0 &&
    (!global || global->GetNumberOfProcesses() == 1))
  {
    // one process holds all of the data: none at all is an empty or failed read (with several
    // ranks an empty local piece is normal)
    this->InputProblem =
      "the AMR dataset holds no blocks (an empty or failed read): nothing to draw";
  }
  if (this->InputProblem != this->ReportedInputProblem)
  {
    this->ReportedInputProblem = this->InputProblem;
    if (!this->InputProblem.empty())
    {
      vtkErrorMacro(<< this->InputProblem);
    }
  }
  if (input)
  {
    // A copy of the hierarchy that shares the input's block objects (CompositeShallowCopy; a
    // ShallowCopy would make a new vtkUniformGrid per block, about 4 kB each): the pipeline may
    // give its output other blocks later, the copy keeps what was delivered. The mapper keys
    // its texture rebuilds on this object and its MTime.
    cache = vtkSmartPointer<vtkOverlappingAMR>::New();
    cache->CompositeShallowCopy(input);
  }
  this->InputArrayMemory = ArrayMemory(cache);

  // Several ranks (pvbatch or pvserver under mpiexec): each holds the whole metadata but only
  // some blocks' data. pvbatch: each rank takes its region of the hierarchy and renders it; its
  // bounds are the region's, which order the ranks' images for compositing. Otherwise rank 0
  // gathers every block and renders the whole volume; the other ranks render nothing (their
  // images are empty, so any compositing order gives rank 0's image).
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  this->RendersLocally = true;
  // in a client-server session the client has no input: it renders what the view delivers
  const int processType = vtkProcessModule::GetProcessType();
  this->RendersFromCache = processType == vtkProcessModule::PROCESS_BATCH ||
    (processType == vtkProcessModule::PROCESS_CLIENT && input != nullptr);
  bool haveRegion = false;
  double regionBounds[6];
  if (controller && controller->GetNumberOfProcesses() > 1 &&
    this->ParallelMode == PARALLEL_REGIONS &&
    vtkProcessModule::GetProcessType() == vtkProcessModule::PROCESS_BATCH)
  {
    // collective; on failure every rank returns null and all gather below
    std::string error;
    vtkSmartPointer<vtkOverlappingAMR> region =
      vtkSinglePassAMRRegionSplit::SplitByRegion(controller, cache, regionBounds, &error);
    if (region)
    {
      long long cells = 0;
      for (unsigned int level = 0; level < region->GetNumberOfLevels(); ++level)
      {
        for (unsigned int index = 0; index < model::NumberOfBlocks(region, level); ++index)
        {
          vtkDataSet* grid = model::Block(region, level, index);
          cells += grid ? static_cast<long long>(grid->GetNumberOfCells()) : 0;
        }
      }
      vtkVLogF(PARAVIEW_LOG_DATA_MOVEMENT_VERBOSITY(),
        "AMR single-pass: rank %d renders region [%g, %g] x [%g, %g] x [%g, %g]: %u blocks, "
        "%lld cells",
        controller->GetLocalProcessId(), regionBounds[0], regionBounds[1], regionBounds[2],
        regionBounds[3], regionBounds[4], regionBounds[5], model::NumberOfBlocks(region), cells);
      cache = region;
      haveRegion = true;
      // a region in a gap between level-0 grids holds nothing: draw nothing there (the mapper
      // would report an empty hierarchy), but keep the region as this rank's bounds
      this->RendersLocally = model::NumberOfBlocks(region) > 0;
    }
    else if (controller->GetLocalProcessId() == 0)
    {
      vtkErrorMacro("cannot split the AMR hierarchy into per-rank regions ("
        << error << "): rank 0 gathers every block and renders alone");
    }
  }
  if (controller && controller->GetNumberOfProcesses() > 1 && !haveRegion)
  {
    std::string error;
    cache = vtkSinglePassAMRGather::GatherBlocks(controller, cache, 0, &error);
    if (!error.empty())
    {
      vtkErrorMacro("gathering the AMR blocks on rank 0: " << error);
    }
    if (controller->GetLocalProcessId() != 0)
    {
      this->RendersLocally = false;
      cache = nullptr;
    }
  }

  // A rank of a region split integrates its rays inside its region only: the ghost cells around
  // it serve smooth interpolation and gradients at the faces, and the next rank draws them.
  for (vtkVolumeMapper* mapper : { static_cast<vtkVolumeMapper*>(this->VolumeMapper),
         static_cast<vtkVolumeMapper*>(this->MultiPassMapper) })
  {
    mapper->SetCropping(haveRegion ? 1 : 0);
    if (haveRegion)
    {
      mapper->SetCroppingRegionFlagsToSubVolume();
      mapper->SetCroppingRegionPlanes(regionBounds);
    }
  }

  if (cache)
  {
    this->Cache = cache;
    if (haveRegion)
    {
      // the region, even where its blocks leave gaps: the ranks' bounds must tile the domain
      std::copy(regionBounds, regionBounds + 6, this->DataBounds);
    }
    else if (model::NumberOfBlocks(cache, 0) > 0)
    {
      cache->GetBounds(this->DataBounds);
    }
    this->DataSize = cache->GetActualMemorySize();
  }
  else
  {
    // A process without the input (or a rank other than 0 in parallel) still needs a data
    // object of the right type for the view's delivery; an AMR with one empty level (an AMR
    // with no level at all is not valid).
    // ParaView's data movement marshals it, which needs an origin and a grid description.
    vtkNew<vtkOverlappingAMR> empty;
    model::Initialize(empty, { 0 });
    const double origin[3] = { 0.0, 0.0, 0.0 };
    empty->SetOrigin(origin);
    empty->SetGridDescription(model::XYZGrid);
    this->Cache = empty;
  }
  this->Executed = true;
  this->CacheTime =
    this->GetUpdateTimeValid() ? this->GetUpdateTime() : std::numeric_limits<double>::quiet_NaN();
  return this->Superclass::RequestData(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::FollowAnimationCache(vtkInformation* inInfo)
{
  vtkPVView* view = vtkPVView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
  if (!view || !(view->GetUseCache() || this->GetForceUseCache()))
  {
    this->CachedSteps.clear();
    this->Executed = false;
    return;
  }
  const double key = this->GetCacheKey();
  const double time =
    this->GetUpdateTimeValid() ? this->GetUpdateTime() : std::numeric_limits<double>::quiet_NaN();
  const auto sameTime = [time](double t)
  { return t == time || (std::isnan(t) && std::isnan(time)); };
  auto found = this->CachedSteps.find(key);
  if (!this->Executed && found != this->CachedSteps.end() && sameTime(found->second.Time))
  {
    // the view skipped RequestData for a step it had cached: show that step's data again
    const CachedStep& step = found->second;
    if (step.Data != this->Cache)
    {
      this->Cache = step.Data;
      this->CacheTime = step.Time;
      this->InputArrayMemory = step.InputArrayMemory;
      std::copy(step.Bounds, step.Bounds + 6, this->DataBounds);
      this->DataSize = step.Size;
      this->RendersLocally = step.RendersLocally;
      for (vtkVolumeMapper* mapper : { static_cast<vtkVolumeMapper*>(this->VolumeMapper),
             static_cast<vtkVolumeMapper*>(this->MultiPassMapper) })
      {
        mapper->SetCropping(step.Cropping ? 1 : 0);
        if (step.Cropping)
        {
          mapper->SetCroppingRegionPlanes(step.Bounds);
        }
      }
    }
    return;
  }
  if (!this->Executed && !sameTime(this->CacheTime))
  {
    // the view holds a piece for this key from an update at another time (ParaView keeps the
    // last piece under the view's cache key when it is not caching): update for this time
    auto executive = vtkPVDataRepresentationPipeline::SafeDownCast(this->GetExecutive());
    if (executive)
    {
      executive->SetNeedsUpdate(true);
      this->Update();
      executive->SetNeedsUpdate(false);
    }
  }
  this->Executed = false;
  CachedStep& step = this->CachedSteps[key];
  step.Time = this->CacheTime;
  step.Data = this->Cache;
  step.InputArrayMemory = this->InputArrayMemory;
  std::copy(this->DataBounds, this->DataBounds + 6, step.Bounds);
  step.Size = this->DataSize;
  step.RendersLocally = this->RendersLocally;
  step.Cropping = this->VolumeMapper->GetCropping() != 0;
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    // invisible: no pass concerns us
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    this->FollowAnimationCache(inInfo);
    // DataSize (kibibytes) drives the view's remote-rendering and LOD decisions, whatever piece
    // stands for the data
    vtkDataObject* piece = this->RendersFromCache
      ? static_cast<vtkDataObject*>(this->PlaceholderPiece.Get())
      : static_cast<vtkDataObject*>(this->Cache.Get());
    vtkPVView::SetPiece(inInfo, this, piece, this->DataSize);
    vtkPVRenderView::SetGeometryBounds(inInfo, this, this->DataBounds, this->Actor->GetMatrix());
    // Translucent: with several rendering ranks the view composites the ranks' images by
    // alpha blending in visibility order (IceT's ordered compositing; the volume writes no
    // depth), ordered by each rank's bounds (the geometry bounds above: each rank's region,
    // which tile the domain; when gathering, rank 0 the whole volume and the others none, an
    // empty image). The data itself is never redistributed by the view.
    // Not when the view cannot render on the ranks (RemoteRenderingAvailable false): the view
    // then renders on one process, and vtkPVRenderView::Render would still redistribute data
    // for ordered compositing there, a collective call only that process makes.
    vtkPVRenderView* view = vtkPVRenderView::SafeDownCast(inInfo->Get(vtkPVView::VIEW()));
    this->ReportParallelRenderingOff(view);
    if (!view || view->GetRemoteRenderingAvailable())
    {
      outInfo->Set(vtkPVRenderView::NEED_ORDERED_COMPOSITING(), 1);
      vtkPVRenderView::SetOrderedCompositingConfiguration(
        inInfo, this, vtkPVRenderView::USE_BOUNDS_FOR_REDISTRIBUTION, this->DataBounds);
    }
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // both mappers follow the data (the cache where this process holds it, else the delivered
    // piece); only the one in use builds textures (when it renders), so the other keeps its
    // textures until it renders new data
    vtkAlgorithmOutput* producer =
      this->RendersFromCache ? nullptr : vtkPVRenderView::GetPieceProducer(inInfo, this);
    for (vtkVolumeMapper* mapper : { static_cast<vtkVolumeMapper*>(this->VolumeMapper),
           static_cast<vtkVolumeMapper*>(this->MultiPassMapper) })
    {
      if (this->RendersFromCache)
      {
        if (mapper->GetNumberOfInputConnections(0) < 1 ||
          mapper->GetInputDataObject(0, 0) != this->Cache.Get())
        {
          mapper->SetInputDataObject(this->Cache);
        }
      }
      else if (mapper->GetNumberOfInputConnections(0) < 1 ||
        mapper->GetInputConnection(0, 0) != producer)
      {
        mapper->SetInputConnection(producer);
      }
    }
    this->UpdateMapperParameters();
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::ReportParallelRenderingOff(vtkPVRenderView* view)
{
  // pvbatch on several ranks renders on every rank and composites with IceT, unless the view's
  // RemoteRenderingAvailable is off: vtkSMRenderViewProxy::CreateVTKObjects turns it off on all
  // ranks when any rank fails vtkPVRenderingCapabilitiesInformation's probe (XOpenDisplay and
  // an OpenGL context, once per process; a refused X connection is enough). Rank 0 then renders
  // alone, but its renderer keeps the IceT pass, whose first render duplicates the MPI
  // communicator (MPI_Comm_dup, collective) while the other ranks wait for commands: ParaView
  // 5.11 deadlocks there whatever is shown. Say why before that happens.
  vtkProcessModule* pm = vtkProcessModule::GetProcessModule();
  if (this->ReportedParallelRenderingOff || !view || view->GetRemoteRenderingAvailable() || !pm ||
    vtkProcessModule::GetProcessType() != vtkProcessModule::PROCESS_BATCH ||
    pm->GetNumberOfLocalPartitions() < 2 || pm->GetPartitionId() != 0)
  {
    return;
  }
  this->ReportedParallelRenderingOff = true;
  vtkErrorMacro("parallel rendering is off on these "
    << pm->GetNumberOfLocalPartitions()
    << " pvbatch ranks (a rank failed ParaView's X display/OpenGL check; pvbatch "
       "--disable-xdisplay-test skips it): ParaView 5.11 then deadlocks in IceT "
       "(MPI_Comm_dup) at the first render");
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::UpdateMapperParameters()
{
  const char* arrayName = nullptr;
  vtkInformation* info = this->GetInputArrayInformation(0);
  if (info && info->Has(vtkDataObject::FIELD_NAME()))
  {
    arrayName = info->Get(vtkDataObject::FIELD_NAME());
  }
  const bool haveArray = arrayName != nullptr && arrayName[0] != '\0';
  if (haveArray)
  {
    // The mapper looks the name up among the cell arrays, then the point arrays (point data is
    // rendered vertex-centred); ParaView's array list offers only arrays that exist.
    this->VolumeMapper->SelectScalarArray(arrayName);
    this->MultiPassMapper->SelectScalarArray(arrayName);
  }

  // The component follows the colour map: a colour map in COMPONENT mode renders that
  // component, in MAGNITUDE mode the vector's magnitude (-1).
  int component = -1;
  if (vtkColorTransferFunction* ctf = this->Property->GetRGBTransferFunction(0))
  {
    if (ctf->GetVectorMode() == vtkScalarsToColors::COMPONENT)
    {
      component = ctf->GetVectorComponent();
    }
  }
  this->VolumeMapper->SetArrayComponent(component);
  this->MultiPassMapper->SetArrayComponent(component);
  this->UpdateMethod();

  // Solid colouring has nothing to volume-render (as ParaView's Volume representation).
  this->Actor->SetVisibility(this->GetVisibility() && haveArray && this->RendersLocally ? 1 : 0);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeRepresentation::AddToView(vtkView* view)
{
  vtkPVRenderView* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->AddActor(this->Actor);
  return this->Superclass::AddToView(view);
}

//------------------------------------------------------------------------------
bool vtkSinglePassAMRVolumeRepresentation::RemoveFromView(vtkView* view)
{
  vtkPVRenderView* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView)
  {
    return false;
  }
  renderView->GetRenderer()->RemoveActor(this->Actor);
  return this->Superclass::RemoveFromView(view);
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetParallelMode(int mode)
{
  if (mode != PARALLEL_REGIONS && mode != PARALLEL_GATHER)
  {
    vtkErrorMacro("unknown parallel mode " << mode << " (0 regions, 1 gather on rank 0); keeping "
                                           << this->ParallelMode);
    return;
  }
  if (mode != this->ParallelMode)
  {
    this->ParallelMode = mode;
    this->MarkModified();
  }
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::SetMethod(int method)
{
  if (method < METHOD_AUTO || method > METHOD_LINEAR)
  {
    vtkErrorMacro("unknown method " << method
                                    << " (0 auto, 1 packing, 2 multi-pass, 3 bindless, 4 linear); "
                                       "keeping "
                                    << this->Method);
    return;
  }
  if (method != this->Method)
  {
    this->Method = method;
    this->UpdateMethod();
    this->Modified();
  }
}

void vtkSinglePassAMRVolumeRepresentation::UpdateMethod()
{
  // every method but multi-pass is a data storage of the single-pass mapper (the property's
  // values are kept for saved states, so they are mapped here, in this one table)
  static const std::pair<int, amrsp::DataStorage> storageOfMethod[] = {
    { METHOD_AUTO, amrsp::DataStorage::Auto },
    { METHOD_PACKING, amrsp::DataStorage::PackedAtlas },
    { METHOD_BINDLESS, amrsp::DataStorage::BindlessTextures },
    { METHOD_LINEAR, amrsp::DataStorage::LinearBricks },
  };
  vtkVolumeMapper* mapper = this->MultiPassMapper;
  for (const auto& row : storageOfMethod)
  {
    if (row.first == this->Method)
    {
      this->VolumeMapper->SetDataStorage(static_cast<int>(row.second));
      mapper = this->VolumeMapper;
    }
  }
  if (this->Actor->GetMapper() != mapper)
  {
    this->Actor->SetMapper(mapper);
  }
}

//------------------------------------------------------------------------------
int vtkSinglePassAMRVolumeRepresentation::GetNumberOfBlockCopies()
{
  vtkOverlappingAMR* rendered =
    vtkOverlappingAMR::SafeDownCast(this->VolumeMapper->GetNumberOfInputConnections(0) > 0
        ? this->VolumeMapper->GetInputDataObject(0, 0)
        : nullptr);
  if (!rendered)
  {
    return 0;
  }
  int copies = 0;
  for (unsigned int level = 0; level < rendered->GetNumberOfLevels(); ++level)
  {
    const bool inCache = this->Cache && level < this->Cache->GetNumberOfLevels();
    for (unsigned int index = 0; index < model::NumberOfBlocks(rendered, level); ++index)
    {
      vtkDataSet* block = model::Block(rendered, level, index);
      const bool own = inCache && index < model::NumberOfBlocks(this->Cache, level) &&
        model::Block(this->Cache, level, index) == block;
      copies += block && !own ? 1 : 0;
    }
  }
  return copies;
}

//------------------------------------------------------------------------------
double vtkSinglePassAMRVolumeRepresentation::GetNumberOfCopiedValues()
{
  vtkOverlappingAMR* rendered =
    vtkOverlappingAMR::SafeDownCast(this->VolumeMapper->GetNumberOfInputConnections(0) > 0
        ? this->VolumeMapper->GetInputDataObject(0, 0)
        : nullptr);
  double copied = 0.0;
  ForEachArray(rendered,
    [this, &copied](vtkAbstractArray* array)
    {
      if (!std::binary_search(this->InputArrayMemory.begin(), this->InputArrayMemory.end(),
            static_cast<const void*>(array->GetVoidPointer(0))))
      {
        copied += static_cast<double>(array->GetNumberOfValues());
      }
    });
  return copied;
}

//------------------------------------------------------------------------------
double* vtkSinglePassAMRVolumeRepresentation::GetLastFrameQuality()
{
  vtkSinglePassAMRVolumeMapper* m = this->VolumeMapper;
  this->LastFrameQuality[0] = m->GetLastFrameInteractive() ? 1.0 : 0.0;
  this->LastFrameQuality[1] = m->GetLastImageSampleDistance();
  this->LastFrameQuality[2] = m->GetLastSampleDistanceScale();
  this->LastFrameQuality[3] = m->GetLastFrameBudget();
  this->LastFrameQuality[4] = m->GetLastFrameSeconds();
  return this->LastFrameQuality;
}

double* vtkSinglePassAMRVolumeRepresentation::GetLastBuildSeconds()
{
  vtkAMRKdTreeVolumeMapper* m = this->Method == METHOD_MULTI_PASS
    ? static_cast<vtkAMRKdTreeVolumeMapper*>(this->MultiPassMapper)
    : static_cast<vtkAMRKdTreeVolumeMapper*>(this->VolumeMapper);
  this->LastBuildSeconds[0] = m->GetLastBuildSeconds();
  this->LastBuildSeconds[1] = m->GetLastUploadSeconds();
  return this->LastBuildSeconds;
}

double* vtkSinglePassAMRVolumeRepresentation::GetLastInputValues()
{
  this->LastInputValues[0] = static_cast<double>(this->VolumeMapper->GetLastBorrowedValues());
  this->LastInputValues[1] = static_cast<double>(this->VolumeMapper->GetLastCopiedValues());
  return this->LastInputValues;
}

const char* vtkSinglePassAMRVolumeRepresentation::GetLastRenderError()
{
  if (!this->InputProblem.empty())
  {
    return this->InputProblem.c_str();
  }
  return this->Method == METHOD_MULTI_PASS ? this->MultiPassMapper->GetLastError()
                                           : this->VolumeMapper->GetLastError();
}

const char* vtkSinglePassAMRVolumeRepresentation::GetLastDataStorage()
{
  if (this->Method == METHOD_MULTI_PASS)
  {
    this->LastDataStorage = "multi-pass";
  }
  else
  {
    // the mapper's public modes have the values of the core's enumerations
    this->LastDataStorage = amrsp::StorageInWords(
      static_cast<amrsp::DataStorage>(this->VolumeMapper->GetLastDataStorage()),
      static_cast<amrsp::BindlessAccess>(this->VolumeMapper->GetLastBindlessAccess()));
  }
  return this->LastDataStorage.c_str();
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeRepresentation::GetLastRayLoop()
{
  if (this->Method == METHOD_MULTI_PASS || this->VolumeMapper->GetLastDataStorage() < 0)
  {
    return "none";
  }
  return amrsp::RayLoopName(static_cast<amrsp::RayLoop>(this->VolumeMapper->GetLastRayLoop()));
}

//------------------------------------------------------------------------------
const char* vtkSinglePassAMRVolumeRepresentation::GetLastRayCaster()
{
  if (this->Method == METHOD_MULTI_PASS)
  {
    return "none";
  }
  return amrsp::RayCasterName(
    static_cast<amrsp::RayCaster>(this->VolumeMapper->GetLastRayCaster()));
}

//------------------------------------------------------------------------------
void vtkSinglePassAMRVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Method: " << this->Method << "\n";
  os << indent << "SampleDistanceFactor: " << this->GetSampleDistanceFactor() << "\n";
  os << indent << "LODThreshold: " << this->GetLODThreshold() << "\n";
  os << indent << "BlendMode: " << this->GetBlendMode() << "\n";
  os << indent << "RendersLocally: " << this->RendersLocally << "\n";
  os << indent << "ParallelMode: " << this->ParallelMode << "\n";
  os << indent << "Cache: " << static_cast<void*>(this->Cache.Get()) << "\n";
}
