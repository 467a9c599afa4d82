// SPDX-License-Identifier: BSD-3-Clause
//
// A time series through both GPU mappers and every storage: a new time step whose hierarchy has
// the structure of the one rendered last keeps the kD-tree, its encoding and the brick layout
// and uploads the values only (GetLastBuildRefreshedValues); its image must equal, byte for
// byte, a full build of the same step in a fresh mapper, and the step's own CPU kD-tree image
// within the usual bound. A regrid (another structure) is built in full. The steps come from
// the synthetic series (amrsp::GenerateCosmoStep: halos drift, regrid every 2 steps).
//
// Expectations that come from neither mirror: the refreshed image differs from the previous
// step's (the values did change: a refresh that kept the old bricks would be caught), and a
// step after a regrid is not refreshed. Exit codes: 0 pass, 1 fail, 125 skipped (no context).

#include "AmrspMultipass.h"
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"

#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"
#include "amrsp/SyntheticCosmo.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkAlgorithm.h"
#include "vtkCallbackCommand.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkCompositeDataIterator.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkRenderWindow.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::Check;
using mappertest::CoveredRmse;
using mappertest::Failures;
using mappertest::Fixed;
using mappertest::Settings;

/// The series' steps 0, 1 (same structure) and 2 (regridded).
std::vector<Hierarchy> Steps()
{
  const CosmoParameters p =
    ParseCosmoParameters("grids=60,levels=3,cells=120k,seed=5,steps=3,regrid=2");
  std::vector<Hierarchy> steps;
  for (int s = 0; s < p.Steps; ++s)
  {
    steps.push_back(GenerateCosmoStep(p, s));
    Settings(steps.back(),
      mappertest::Request(512, 512,
        [](amrsp::harness::RenderRequest& r)
        { r.Scale = "log"; })); // log10 of the density, every step alike
  }
  return steps;
}

/// The single-pass storage named `method` ("packing", ...: amrsp::DataStorageNames).
DataStorage StorageNamed(const std::string& method)
{
  DataStorage storage = DataStorage::None;
  if (!ParseIn(DataStorageNames, method.c_str(), storage))
  {
    throw std::invalid_argument("no single-pass storage is called " + method);
  }
  return storage;
}

std::unique_ptr<GpuRenderer> MakeRenderer(
  const std::string& method, const Hierarchy& h, const RenderSettings& s)
{
  if (method == "multipass")
  {
    return std::unique_ptr<GpuRenderer>(new MultipassRenderer(h, s, ViewAngles()));
  }
  return std::unique_ptr<GpuRenderer>(
    new SinglePassRenderer(h, s, ViewAngles(), StorageNamed(method)));
}

/// Bytes of the 8-bit RGB frames that differ (all of them when the sizes differ).
long long DifferingBytes(const Image& a, const Image& b)
{
  const std::vector<std::uint8_t> x = a.Rgb8(), y = b.Rgb8();
  if (x.size() != y.size())
  {
    return static_cast<long long>(std::max(x.size(), y.size()));
  }
  long long n = 0;
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    n += x[i] == y[i] ? 0 : 1;
  }
  return n;
}

/// `requireStorage`: the single-pass storage used must be `method` (no fallback). The
/// single-pass methods cast the series' rays with `caster` (their frames must say so).
void CheckMethod(const std::string& methodName, std::vector<Hierarchy>& steps,
  bool requireStorage = false, RayCaster caster = RayCaster::Auto)
{
  Hierarchy first = steps[0]; // shares the values; the settings leave them as they are
  RenderSettings s = Settings(first,
    mappertest::Request(96, 96, [](amrsp::harness::RenderRequest& r) { r.Scale = "linear"; }));
  s.GpuRayCaster = caster;
  const std::string method = methodName;
  const std::string label =
    caster == RayCaster::Auto ? methodName : methodName + " (" + RayCasterName(caster) + " caster)";
  double ms = 0.0;
  std::unique_ptr<GpuRenderer> series = MakeRenderer(method, steps[0], s);
  const Image firstImage = series->Render(0.0, ms);
  const int builds = series->NumberOfBuilds();
  series->SetData(steps[1]);
  const Image refreshed = series->Render(0.0, ms);
  SinglePassRenderer* packing = dynamic_cast<SinglePassRenderer*>(series.get());
  const std::string storage = packing ? " (" + packing->StorageUsedInWords() + ")" : std::string();
  if (packing && caster != RayCaster::Auto)
  {
    Check(packing->CasterUsed() == caster,
      label + ": the refreshed step was cast by the " + RayCasterName(packing->CasterUsed()) +
        " shader");
    const mappertest::RayCasterComparison other =
      mappertest::CompareOtherRayCaster(*packing, refreshed);
    Check(other.Same(), label + ": the refreshed step by the " + other.Describe());
  }
  if (requireStorage)
  {
    Check(packing && method == DataStorageName(packing->StorageUsed()),
      label + ": the series renders with the " + method + " storage" + storage);
  }
  Check(series->NumberOfValueRefreshes() == 1 && series->NumberOfBuilds() == builds + 1,
    label + storage + ": step 1 (same structure) refreshed the values: " +
      std::to_string(series->NumberOfValueRefreshes()) + " refresh(es), " +
      std::to_string(series->NumberOfBuilds()) + " builds");
  const Image full = MakeRenderer(method, steps[1], s)->Render(0.0, ms);
  const long long differing = DifferingBytes(refreshed, full);
  Check(differing == 0,
    label + ": step 1 refreshed equals a full build of step 1 byte for byte (" +
      std::to_string(differing) + " bytes differ)");
  const long long moved = DifferingBytes(refreshed, firstImage);
  Check(moved > 100,
    label + ": step 1's image is not step 0's (" + std::to_string(moved) + " bytes differ)");
  const Image cpu = RenderKdTree(steps[1], EncodeKdTree(steps[1], BuildKdTree(steps[1])), s);
  const double vsCpu = CoveredRmse(refreshed, cpu);
  Check(vsCpu < mappertest::BoundVsKdTree,
    label + ": step 1 refreshed against the CPU kD-tree image of step 1: RMSE " + Fixed(vsCpu) +
      " (bound " + Fixed(mappertest::BoundVsKdTree) + ")");

  series->SetData(steps[2]);
  const Image regridded = series->Render(0.0, ms);
  Check(series->NumberOfValueRefreshes() == 1,
    label + ": step 2 (regridded) was built in full (" +
      std::to_string(series->NumberOfValueRefreshes()) + " refresh(es))");
  const Image fullRegridded = MakeRenderer(method, steps[2], s)->Render(0.0, ms);
  Check(DifferingBytes(regridded, fullRegridded) == 0,
    label + ": step 2 after the series equals a fresh build of step 2");
}

/// The progress events of the mapper's build and upload phases while `render` runs: none when
/// nothing is built or uploaded. Each phase names itself (vtkAlgorithm::SetProgressText) before
/// its first event; the pipeline's own events around the mapper's update (0 and 1, no text after
/// the text is cleared here) are not counted.
int ProgressEventsDuring(vtkSinglePassAMRVolumeMapper* mapper, const std::function<void()>& render)
{
  int events = 0;
  vtkNew<vtkCallbackCommand> count;
  count->SetClientData(&events);
  count->SetCallback(
    [](vtkObject* caller, unsigned long, void* client, void*)
    {
      const char* text = static_cast<vtkAlgorithm*>(caller)->GetProgressText();
      *static_cast<int*>(client) += text && *text ? 1 : 0;
    });
  mapper->SetProgressText(nullptr);
  const unsigned long tag = mapper->AddObserver(vtkCommand::ProgressEvent, count);
  render();
  mapper->RemoveObserver(tag);
  return events;
}

/// Multiplies the named cell array of every block of `amr` by `factor` in place and marks the
/// data object modified (what a filter or a user changing a step in place does).
void ScaleInPlace(vtkOverlappingAMR* amr, const std::string& array, double factor)
{
  vtkSmartPointer<vtkCompositeDataIterator> it;
  it.TakeReference(amr->NewIterator());
  for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
  {
    vtkDataSet* block = vtkDataSet::SafeDownCast(it->GetCurrentDataObject());
    vtkDataArray* values = block ? block->GetCellData()->GetArray(array.c_str()) : nullptr;
    if (!values)
    {
      throw std::runtime_error("a block without the array '" + array + "'");
    }
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      values->SetTuple1(i, factor * values->GetTuple1(i));
    }
    values->Modified();
  }
  amr->Modified();
}

/// Steps shown again keep their textures (MaximumKeptStepBytes), most recently used first, keyed
/// by the input object and its modification time:
/// - going back to steps 1 and 0 shows them byte for byte as before, with no build or upload (no
///   progress event: counted by an observer, not by the mapper's own counters);
/// - a kept step changed in place (its values scaled, Modified()) is built again and drawn as a
///   fresh mapper draws it, not as kept;
/// - a budget of the largest step's textures keeps exactly one step, the most recently used: it
///   is a hit, the least recently used one is built again.
void CheckKeptSteps(const std::string& method, std::vector<Hierarchy>& steps)
{
  Hierarchy first = steps[0];
  const RenderSettings s = Settings(first,
    mappertest::Request(96, 96, [](amrsp::harness::RenderRequest& r) { r.Scale = "linear"; }));
  double ms = 0.0;
  SinglePassRenderer series(steps[0], s, ViewAngles(), StorageNamed(method));
  vtkSinglePassAMRVolumeMapper* mapper = series.GetMapper();
  mapper->SetMaximumKeptStepBytes(vtkIdType(1) << 30);
  std::vector<Image> shown{ series.Render(0.0, ms) };
  std::vector<long long> bytes{ series.TextureBytes() };
  std::vector<vtkSmartPointer<vtkOverlappingAMR>> objects{ series.GetData() };
  for (std::size_t k = 1; k < steps.size(); ++k)
  {
    series.SetData(steps[k]);
    objects.push_back(series.GetData());
    shown.push_back(series.Render(0.0, ms));
    bytes.push_back(series.TextureBytes());
  }
  Check(mapper->GetNumberOfKeptSteps() == 2 && mapper->GetNumberOfKeptStepHits() == 0,
    method + ": after three steps two are kept (" + std::to_string(mapper->GetNumberOfKeptSteps()) +
      ")");
  // show `k` again; returns whether it was a hit with no build or upload
  const auto showAgain = [&](int k, Image& image, int& events)
  {
    const int hits = mapper->GetNumberOfKeptStepHits();
    series.SetDataObject(objects[static_cast<std::size_t>(k)]);
    events = ProgressEventsDuring(mapper, [&] { image = series.Render(0.0, ms); });
    return mapper->GetNumberOfKeptStepHits() == hits + 1 && events == 0;
  };
  for (int k : { 1, 0 })
  {
    Image again;
    int events = 0;
    const bool hit = showAgain(k, again, events);
    const long long differing = DifferingBytes(again, shown[static_cast<std::size_t>(k)]);
    Check(hit && differing == 0,
      method + ": step " + std::to_string(k) + " shown again from its kept textures (" +
        std::to_string(events) + " build/upload progress events, " + std::to_string(differing) +
        " bytes differ from its first image)");
  }
  // kept now, most recent first: 1, 2 (0 is shown). Step 1 changed in place: not a hit
  ScaleInPlace(objects[1], steps[1].ArrayName, 0.5);
  {
    Image changed;
    int events = 0;
    const bool hit = showAgain(1, changed, events);
    SinglePassRenderer fresh(steps[1], s, ViewAngles(), StorageNamed(method));
    fresh.SetDataObject(objects[1]);
    const Image expected = fresh.Render(0.0, ms);
    const long long stale = DifferingBytes(changed, shown[1]);
    const long long differing = DifferingBytes(changed, expected);
    Check(!hit && events > 0 && differing == 0 && stale > 0,
      method + ": step 1 changed in place is built again (" + std::to_string(events) +
        " progress events), " + std::to_string(differing) + " bytes differ from a fresh mapper's " +
        "image, " + std::to_string(stale) + " from the kept one");
    shown[1] = expected;
  }
  // kept: 0, 2 (1 is shown). A budget of the largest step: showing 2 (a hit) keeps 1 only
  const long long budget = *std::max_element(bytes.begin(), bytes.end());
  mapper->SetMaximumKeptStepBytes(static_cast<vtkIdType>(budget));
  {
    Image image;
    int events = 0;
    const bool hit = showAgain(2, image, events);
    Check(hit && mapper->GetNumberOfKeptSteps() == 1 && mapper->GetKeptStepBytes() > 0 &&
        mapper->GetKeptStepBytes() <= static_cast<vtkIdType>(budget),
      method + ": with a budget of " + std::to_string(budget) + " bytes step 2 is a hit and " +
        std::to_string(mapper->GetNumberOfKeptSteps()) + " step is kept (" +
        std::to_string(mapper->GetKeptStepBytes()) + " bytes)");
  }
  {
    Image image;
    int events = 0;
    const bool hit = showAgain(1, image, events);
    Check(hit && DifferingBytes(image, shown[1]) == 0,
      method + ": the most recently used step (1) was kept: a hit, " + std::to_string(events) +
        " progress events");
  }
  {
    Image image;
    int events = 0;
    const bool hit = showAgain(0, image, events);
    Check(!hit && events > 0 && DifferingBytes(image, shown[0]) == 0,
      method + ": the least recently used step (0) was dropped: built again (" +
        std::to_string(events) + " progress events), the same image");
  }
}

} // namespace

/// The bindless storage's refresh on a context with bindless textures (CTest runs this mode on
/// Mesa's zink): the new values go into the resident textures, the image a full build's.
int RunBindless(std::vector<Hierarchy>& steps)
{
  vtkNew<vtkRenderWindow> probe;
  probe->SetOffScreenRendering(1);
  std::string why;
  const bool bindless = vtkSinglePassAMRVolumeMapper::IsBindlessSupported(probe, &why);
  probe->Finalize();
  if (!bindless)
  {
    // in CI zink offers bindless textures (scripts/install-deps.sh checks it): a failure there
    return mappertest::SkipOrFail(
      why + " (CTest runs this mode on Mesa's zink, which offers bindless textures from Mesa 25)");
  }
  try
  {
    for (RayCaster caster : { RayCaster::Fragment, RayCaster::Compute })
    {
      CheckMethod("bindless", steps, true, caster);
    }
  }
  catch (const std::exception& e)
  {
    Check(false, std::string("bindless: ") + e.what());
  }
  std::cout << (Failures() == 0 ? "PASSED" : "FAILED: " + std::to_string(Failures()) + " check(s)")
            << "\n";
  return Failures() == 0 ? 0 : 1;
}

int main(int argc, char* argv[])
{
  std::string why;
  if (!GpuRenderer::Available(why))
  {
    return mappertest::SkipOrFail(why);
  }
  std::vector<Hierarchy> steps = Steps();
  if (argc > 1 && std::string(argv[1]) == "bindless")
  {
    return RunBindless(steps);
  }
  Check(SameStructure(steps[0], steps[1]) && !SameStructure(steps[1], steps[2]),
    "the series keeps its structure for steps 0 and 1 and regrids at step 2");
  for (const char* method : { "packing", "bindless", "linear", "multipass" })
  {
    try
    {
      CheckMethod(method, steps);
    }
    catch (const std::exception& e)
    {
      Check(false, std::string(method) + ": " + e.what());
    }
  }
  // the single pass's series again with each caster explicitly (RayCaster)
  for (const char* method : { "packing", "linear" })
  {
    for (RayCaster caster : { RayCaster::Fragment, RayCaster::Compute })
    {
      try
      {
        CheckMethod(method, steps, false, caster);
      }
      catch (const std::exception& e)
      {
        Check(false, std::string(method) + " (" + RayCasterName(caster) + "): " + e.what());
      }
    }
  }
  for (const char* method : { "packing", "linear" })
  {
    try
    {
      CheckKeptSteps(method, steps);
    }
    catch (const std::exception& e)
    {
      Check(false, std::string(method) + " (kept steps): " + e.what());
    }
  }
  std::cout << (Failures() == 0 ? "PASSED" : "FAILED: " + std::to_string(Failures()) + " check(s)")
            << "\n";
  return Failures() == 0 ? 0 : 1;
}
