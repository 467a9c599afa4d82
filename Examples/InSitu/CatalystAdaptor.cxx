// SPDX-License-Identifier: BSD-3-Clause
#include "CatalystAdaptor.h"

#include "BlobSimulation.h"

#include "vtkAMRBox.h"
#include "vtkCPDataDescription.h"
#include "vtkCPInputDataDescription.h"
#include "vtkCPProcessor.h"
#include "vtkCPPythonPipeline.h"
#include "vtkCellData.h"
#include "vtkCompositeDataIterator.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkInitializationHelper.h"
#include "vtkLogger.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkProcessModule.h"
#include "vtkProcessModuleConfiguration.h"
#include "vtkSMPluginManager.h"
#include "vtkSMProxyManager.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkStructuredData.h"
#include "vtkUniformGrid.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <vector>

#if defined(__has_include)
#if __has_include("vtkAMRDataObject.h")
#define INSITU_VTK_AMR_DATA_OBJECT 1 // VTK 9.6's AMR data model
#endif
#endif

namespace insitu
{
namespace
{

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

vtkSmartPointer<vtkOverlappingAMR> CatalystAdaptor::Describe(BlobSimulation& simulation)
{
  std::vector<Block>& blocks = simulation.Blocks();
  int levels = 0;
  for (const Block& b : blocks)
  {
    levels = std::max(levels, b.Level + 1);
  }
  std::vector<unsigned int> perLevel(static_cast<std::size_t>(levels), 0);
  for (const Block& b : blocks)
  {
    ++perLevel[static_cast<std::size_t>(b.Level)];
  }
  auto amr = vtkSmartPointer<vtkOverlappingAMR>::New();
#ifdef INSITU_VTK_AMR_DATA_OBJECT
  amr->Initialize(perLevel);
  amr->SetGridDescription(vtkStructuredData::VTK_STRUCTURED_XYZ_GRID);
#else
  const std::vector<int> counts(perLevel.begin(), perLevel.end());
  amr->Initialize(levels, counts.data());
  amr->SetGridDescription(VTK_XYZ_GRID);
#endif
  const double origin[3] = { 0.0, 0.0, 0.0 };
  amr->SetOrigin(origin);
  for (int level = 0; level < levels; ++level)
  {
    const double h = simulation.CellSize(level);
    const double spacing[3] = { h, h, h };
    amr->SetSpacing(level, spacing);
    if (level + 1 < levels)
    {
      amr->SetRefinementRatio(level, 2);
    }
  }
  std::vector<unsigned int> next(perLevel.size(), 0);
  for (Block& b : blocks)
  {
    const unsigned int level = static_cast<unsigned int>(b.Level);
    const unsigned int index = next[level]++;
    const int hi[3] = { b.Lo[0] + b.Cells[0] - 1, b.Lo[1] + b.Cells[1] - 1,
      b.Lo[2] + b.Cells[2] - 1 };
    amr->SetAMRBox(level, index, vtkAMRBox(b.Lo.data(), hi));
    if (b.Values.empty())
    {
      continue; // another rank's block
    }
    const double h = simulation.CellSize(b.Level);
    vtkNew<vtkUniformGrid> grid;
    grid->SetOrigin(b.Lo[0] * h, b.Lo[1] * h, b.Lo[2] * h);
    grid->SetSpacing(h, h, h);
    grid->SetDimensions(b.Cells[0] + 1, b.Cells[1] + 1, b.Cells[2] + 1);
    vtkNew<vtkFloatArray> density;
    density->SetName("density");
    // save = 1: VTK reads the simulation's memory and never frees it
    density->SetArray(b.Values.data(), static_cast<vtkIdType>(b.Values.size()), 1);
    grid->GetCellData()->SetScalars(density);
    amr->SetDataSet(level, index, grid);
  }
  return amr;
}

long long CatalystAdaptor::CountSimulationValues(
  vtkDataObject* handed, const BlobSimulation& simulation)
{
  auto* amr = vtkOverlappingAMR::SafeDownCast(handed);
  if (!amr)
  {
    return 0;
  }
  long long found = 0;
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(amr->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    auto* grid = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
    vtkDataArray* values = grid ? grid->GetCellData()->GetArray("density") : nullptr;
    if (!values || values->GetNumberOfTuples() == 0)
    {
      continue;
    }
    const void* memory = values->GetVoidPointer(0);
    for (const Block& b : simulation.Blocks())
    {
      if (memory == static_cast<const void*>(b.Values.data()) &&
        values->GetNumberOfTuples() == static_cast<vtkIdType>(b.Values.size()))
      {
        found += static_cast<long long>(b.Values.size());
        break;
      }
    }
  }
  return found;
}

namespace
{

/// ParaView's engine, started as Catalyst starts it (a batch process, symmetric MPI, no settings
/// files) but with `--disable-xdisplay-test`, as the Plugin.MPI tests start pvbatch. Catalyst's
/// own start runs ParaView's X display check on every rank: a rank whose XOpenDisplay is refused
/// (an Xvfb under load refuses now and then one of the connections opened at the same moment)
/// turns parallel rendering off on all ranks, and ParaView then deadlocks at the first render
/// (rank 0 in IceT's MPI_Comm_dup, the others in the data's gather to rank 0): a hang, not an
/// error (docs/paraview.md, "MPI runs and the X display check"). Without the check, a rank that
/// cannot open its window aborts with VTK's "bad X server connection" instead. vtkCPProcessor
/// finds the engine started and leaves starting and finishing it to its owner.
struct ParaViewEngine
{
  ParaViewEngine()
  {
    char executable[] = "amrsp_insitu_blobs";
    char noDisplayCheck[] = "--disable-xdisplay-test";
    char* argv[] = { executable, noDisplayCheck, nullptr };
    vtkInitializationHelper::SetLoadSettingsFilesDuringInitialization(false);
    vtkProcessModuleConfiguration::GetInstance()->SetSymmetricMPIMode(true);
    if (!vtkInitializationHelper::Initialize(2, argv, vtkProcessModule::PROCESS_BATCH))
    {
      throw std::runtime_error("ParaView's engine failed to start (vtkInitializationHelper)");
    }
  }
  ~ParaViewEngine() { vtkInitializationHelper::Finalize(); }
  ParaViewEngine(const ParaViewEngine&) = delete;
  ParaViewEngine& operator=(const ParaViewEngine&) = delete;
};

} // namespace

struct CatalystAdaptor::Internals
{
  ParaViewEngine Engine; // first: started before Catalyst, finished after it
  vtkNew<vtkCPProcessor> Processor;
  vtkNew<vtkFieldData> UserData;
};

CatalystAdaptor::CatalystAdaptor(
  const std::string& script, const std::string& plugin, const Settings& settings)
  : Internal(new Internals)
{
  if (!this->Internal->Processor->Initialize())
  {
    throw std::runtime_error("Catalyst (vtkCPProcessor) failed to initialise");
  }
  // Catalyst silences the other ranks' log on stderr; their errors stay visible (a rank that
  // cannot open its window says so before it aborts: "bad X server connection")
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetLocalProcessId() > 0)
  {
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_ERROR);
  }
  if (!plugin.empty() &&
    !vtkSMProxyManager::GetProxyManager()->GetPluginManager()->LoadLocalPlugin(plugin.c_str()))
  {
    throw std::runtime_error("ParaView could not load the plugin " + plugin);
  }
  vtkSmartPointer<vtkCPPythonPipeline> pipeline =
    vtkCPPythonPipeline::CreateAndInitializePipeline(script.c_str());
  if (!pipeline)
  {
    throw std::runtime_error("the Catalyst script " + script + " failed to load");
  }
  this->Internal->Processor->AddPipeline(pipeline);
  for (const auto& setting : settings)
  {
    vtkNew<vtkStringArray> value;
    value->SetName(setting.first.c_str());
    value->InsertNextValue(setting.second);
    this->Internal->UserData->AddArray(value);
  }
}

CatalystAdaptor::~CatalystAdaptor()
{
  this->Internal->Processor->Finalize();
}

CatalystAdaptor::StepCost CatalystAdaptor::CoProcess(BlobSimulation& simulation)
{
  StepCost cost;
  vtkNew<vtkCPDataDescription> description;
  description->AddInput("input");
  description->SetTimeData(simulation.Time(), simulation.StepIndex());
  description->SetUserData(this->Internal->UserData);
  if (!this->Internal->Processor->RequestDataDescription(description))
  {
    return cost;
  }
  auto start = std::chrono::steady_clock::now();
  vtkSmartPointer<vtkOverlappingAMR> amr = Describe(simulation);
  vtkCPInputDataDescription* input = description->GetInputDescriptionByName("input");
  input->SetGrid(amr);
  cost.DescribeSeconds = SecondsSince(start);
  // measured on what Catalyst holds, not on what Describe meant to hand over
  cost.BorrowedValues = CountSimulationValues(input->GetGrid(), simulation);
  start = std::chrono::steady_clock::now();
  this->Internal->Processor->CoProcess(description);
  cost.CoProcessSeconds = SecondsSince(start);
  cost.Processed = true;
  return cost;
}

} // namespace insitu
