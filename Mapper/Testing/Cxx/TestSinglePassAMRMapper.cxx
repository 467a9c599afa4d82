// SPDX-License-Identifier: BSD-3-Clause
//
// Image test of vtkSinglePassAMRVolumeMapper (packing path) on an offscreen vtkRenderWindow.
//
// Every GPU image is checked against independent CPU renderings of the same view, so a wrong
// image cannot pass by agreeing with itself:
//   - amrsp::RenderReference (no kD-tree, finest cell found from the grid boxes):   RMSE < 2.0
//   - amrsp::RenderKdTree (the CPU mirror of the shader's traversal and sampling):  RMSE < 1.0
// (RMSE over the RGB channels in 0-255 units. The first bound is the one the core tests use for
// the CPU kD-tree integrator against the reference; the largest GPU-vs-reference value measured
// on llvmpipe is 1.45. The second is about three times the largest GPU-vs-kD-tree value measured
// on llvmpipe, 0.31: the remaining differences are the 4096-entry transfer table, float rounding
// at cell faces and the early ray termination at alpha 0.999.)
// Further checks: the textures are built once across camera and transfer-function changes; a
// camera inside the volume; parallel projection; a translated volume (vtkProp3D matrix); opaque
// geometry in front of and inside the volume (depth buffer);
// hand-made hierarchies for the shader's three ways to the per-level constants (refinement
// ratios 3 x 2 x 3 and 3; 2 x 4 x 2 and 4; 4 and 4);
// a missing array and an atlas over the size limit report an error and draw nothing.
//
// Exit code 125 (CTest SKIP) with "SKIPPED: ..." when no suitable OpenGL context can be created
// (no X display for this GLX-only VTK, or an OpenGL older than 3.2 core).

#include "AmrspRenderOptions.h"
#include "MapperTestHelpers.h"
#include "RendererChecks.h"
#include "AmrspDataset.h"
#include "AmrspMultipass.h"
#include "AmrspSinglePass.h"

#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include "vtkActor.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkImageData.h"
#include "vtkPointData.h"
#include "vtkRenderWindow.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::BoundVsKdTree;
using mappertest::BoundVsReference;
using mappertest::Check;
using mappertest::CheckSquareInFrontHides;
using mappertest::CheckTransferChangeRebuildsNothing;
using mappertest::Coverage;
using mappertest::CoveredRmse;
using mappertest::Failures;
using mappertest::Fixed;
using mappertest::LoadHierarchy;
using mappertest::OccluderView;
using mappertest::Settings;

/// The camera inside the volume, parallel projection and a moved volume, opaque geometry and
/// errors, on the renderer `gpu` of TestDataset (`before`: its image of the default view).
void TestViewsAndErrors(Hierarchy& h, const EncodedKdTree& enc, const RenderSettings& s,
  SinglePassRenderer& gpu, const Image& before)
{
  double ms = 0.0;
  vtkVolume* volume = vtkVolume::SafeDownCast(gpu.GetRenderer()->GetVolumes()->GetItemAsObject(0));
  // camera inside the volume: the CPU integrator gets VTK's camera as it is
  {
    vtkCamera* camera = gpu.GetRenderer()->GetActiveCamera();
    gpu.Render(0.0, ms);
    camera->Dolly(12.0);
    gpu.GetRenderer()->ResetCameraClippingRange();
    const Image inside = gpu.RenderAsIs(ms);
    RenderSettings is = s;
    is.View = gpu.LastCamera();
    double b[6];
    volume->GetBounds(b);
    const glm::dvec3 p = is.View.Position;
    const bool isInside =
      p.x > b[0] && p.x < b[1] && p.y > b[2] && p.y < b[3] && p.z > b[4] && p.z < b[5];
    const double e = Rmse(inside, RenderKdTree(h, enc, is));
    Check(isInside && Coverage(inside) > 0.5,
      "camera inside the volume renders (coverage " + Fixed(Coverage(inside)) + ")");
    Check(e < BoundVsKdTree,
      "camera inside: GPU vs CPU kD-tree RMSE " + Fixed(e) + " < " + Fixed(BoundVsKdTree));
  }

  // parallel projection, and a volume moved by its vtkProp3D transform (camera moved alike)
  {
    vtkCamera* camera = gpu.GetRenderer()->GetActiveCamera();
    gpu.Render(0.0, ms);
    camera->ParallelProjectionOn();
    gpu.GetRenderer()->ResetCameraClippingRange();
    const Image parallel = gpu.RenderAsIs(ms);
    RenderSettings ps = s;
    ps.View = gpu.LastCamera();
    camera->ParallelProjectionOff();
    const double e = Rmse(parallel, RenderKdTree(h, enc, ps));
    Check(ps.View.Parallel && Coverage(parallel) > 0.05 && e < BoundVsKdTree,
      "parallel projection: GPU vs CPU kD-tree RMSE " + Fixed(e) + " < " + Fixed(BoundVsKdTree));

    const Image unmoved = gpu.Render(0.0, ms);
    double b[6];
    volume->GetBounds(b);
    const double shift[3] = { 0.75 * (b[1] - b[0]), -0.5 * (b[3] - b[2]), 0.25 * (b[5] - b[4]) };
    volume->SetPosition(shift[0], shift[1], shift[2]);
    gpu.Render(0.0, ms);
    double p[3], f[3];
    camera->GetPosition(p);
    camera->GetFocalPoint(f);
    camera->SetPosition(p[0] + shift[0], p[1] + shift[1], p[2] + shift[2]);
    camera->SetFocalPoint(f[0] + shift[0], f[1] + shift[1], f[2] + shift[2]);
    gpu.GetRenderer()->ResetCameraClippingRange();
    const Image moved = gpu.RenderAsIs(ms);
    volume->SetPosition(0.0, 0.0, 0.0);
    const double m = Rmse(moved, unmoved);
    Check(m < 0.5, "volume and camera translated together: RMSE to the unmoved image " + Fixed(m));
  }

  // opaque geometry: a white square in front of the volume hides it completely; one through the
  // centre hides the back half only
  {
    OccluderView view;
    const Image plain = CheckSquareInFrontHides(gpu, view);

    vtkSmartPointer<vtkActor> middle = view.SquareThroughCentre();
    gpu.GetRenderer()->AddActor(middle);
    const Image frontHalf = gpu.Render(0.0, ms);
    gpu.GetMapper()->UseDepthBufferOff();
    const Image ignoring = gpu.Render(0.0, ms);
    gpu.GetMapper()->UseDepthBufferOn();
    gpu.GetRenderer()->RemoveActor(middle);
    // black square: without depth the full ray shows (as with no square at all), with depth only
    // the part in front of the square
    Check(Rmse(ignoring, plain) < 0.5 && Rmse(frontHalf, plain) > 1.0,
      "opaque square through the centre clips the rays (RMSE to the unclipped image " +
        Fixed(Rmse(frontHalf, plain)) + "; with UseDepthBuffer off " +
        Fixed(Rmse(ignoring, plain)) + ")");
  }

  // errors: nothing drawn, no crash, and rendering recovers
  {
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    const std::string array = mapper->GetArrayName();
    mapper->SelectScalarArray("NoSuchArray");
    bool threw = false;
    std::string message;
    try
    {
      gpu.Render(0.0, ms);
    }
    catch (const GpuError& e)
    {
      threw = true;
      message = e.what();
    }
    Check(threw && message.find("no cell array named 'NoSuchArray'") != std::string::npos,
      "a missing array is an error: " + message);
    mapper->SelectScalarArray(array.c_str());
    Check(Rmse(gpu.Render(0.0, ms), before) < 0.01, "selecting the array again renders again");

    mapper->SetMaximumAtlasSize(4);
    threw = false;
    message.clear();
    try
    {
      gpu.Render(0.0, ms);
    }
    catch (const GpuError& e)
    {
      threw = true;
      message = e.what();
    }
    Check(threw && message.find("cannot pack the bricks") != std::string::npos &&
        message.find("bindless") != std::string::npos,
      "an atlas over the size limit is an error: " + message);
    mapper->SetMaximumAtlasSize(0);
    Check(Rmse(gpu.Render(0.0, ms), before) < 0.01, "with the limit lifted it renders again");
  }
}

void TestDataset(const std::string& spec)
{
  std::cout << "dataset " << spec << "\n";
  Hierarchy h = LoadHierarchy(spec);
  const RenderSettings s = Settings(h, mappertest::Request(128, 128));
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));

  SinglePassRenderer gpu(h, s, ViewAngles());
  double ms = 0.0;
  Image img = gpu.Render(0.0, ms);
  const Image ref = RenderReference(h, s);
  const Image kd = RenderKdTree(h, enc, s);
  const double coverage = Coverage(ref);
  Check(coverage > 0.05, "the CPU reference shows the data (coverage " + Fixed(coverage) + ")");
  Check(CameraDifference(gpu.LastCamera(), s.View) < 1e-6,
    "VTK's ResetCamera/Azimuth/Elevation/Zoom match the tool's camera conventions");
  const double vsRef = CoveredRmse(img, ref), vsKd = CoveredRmse(img, kd);
  Check(vsRef < BoundVsReference,
    "GPU vs CPU reference: RMSE " + Fixed(vsRef) + " < " + Fixed(BoundVsReference));
  Check(vsKd < BoundVsKdTree,
    "GPU vs CPU kD-tree integrator: RMSE " + Fixed(vsKd) + " < " + Fixed(BoundVsKdTree));

  // another view: the orbit of the bench, compared again; no rebuild on camera changes
  for (double orbit : { 90.0, 200.0 })
  {
    RenderSettings fs = s;
    fs.View.Azimuth(orbit);
    img = gpu.Render(orbit, ms);
    const double e = Rmse(img, RenderKdTree(h, enc, fs));
    Check(e < BoundVsKdTree,
      "orbit " + Fixed(orbit) + " deg: GPU vs CPU kD-tree RMSE " + Fixed(e) + " < " +
        Fixed(BoundVsKdTree));
  }

  // the other blend modes against the CPU kD-tree integrator (no rebuild either)
  for (BlendMode mode : { BlendMode::Maximum, BlendMode::Minimum, BlendMode::Average })
  {
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    mapper->SetBlendMode(mode == BlendMode::Maximum ? vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND
        : mode == BlendMode::Minimum                ? vtkVolumeMapper::MINIMUM_INTENSITY_BLEND
                                                    : vtkVolumeMapper::AVERAGE_INTENSITY_BLEND);
    RenderSettings bs = s;
    bs.Blend = mode;
    const double e = Rmse(gpu.Render(0.0, ms), RenderKdTree(h, enc, bs));
    Check(e < BoundVsKdTree,
      "blend mode " + std::to_string(static_cast<int>(mode)) + ": GPU vs CPU kD-tree RMSE " +
        Fixed(e) + " < " + Fixed(BoundVsKdTree));
    mapper->SetBlendModeToComposite();
  }
  gpu.GetMapper()->SetBlendMode(vtkVolumeMapper::ADDITIVE_BLEND);
  {
    bool threw = false;
    try
    {
      gpu.Render(0.0, ms);
    }
    catch (const GpuError& e)
    {
      threw = std::string(e.what()).find("not supported") != std::string::npos;
    }
    Check(threw, "an unsupported blend mode (additive) is a clear error");
  }
  gpu.GetMapper()->SetBlendModeToComposite();

  // a transfer-function change is visible and rebuilds nothing
  const Image before = CheckTransferChangeRebuildsNothing(gpu, s, "6 frames");

  TestViewsAndErrors(h, enc, s, gpu, before);
}

} // namespace

/// Vertex-centred data (trilinear atlas sampling) against the CPU integrators.
void TestVertexCentred(const std::string& spec)
{
  std::cout << "dataset " << spec << " (vertex-centred)\n";
  Hierarchy h = LoadHierarchy(spec, "vertex");
  Check(h.VertexCentred, "the data was converted to vertices");
  const RenderSettings s = Settings(h, mappertest::Request(96, 96));
  SinglePassRenderer gpu(h, s, ViewAngles());
  double ms = 0.0;
  const Image img = gpu.Render(0.0, ms);
  const Image kd = RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), s);
  const Image ref = RenderReference(h, s);
  const double vsKd = CoveredRmse(img, kd), vsRef = CoveredRmse(img, ref);
  Check(Coverage(ref) > 0.05, "the CPU reference shows the data");
  Check(vsKd < BoundVsKdTree,
    "vertex-centred: GPU vs CPU kD-tree RMSE " + Fixed(vsKd) + " < " + Fixed(BoundVsKdTree));
  Check(vsRef < BoundVsReference,
    "vertex-centred: GPU vs CPU reference RMSE " + Fixed(vsRef) + " < " + Fixed(BoundVsReference));
}

/// Fills every grid of `h` with a smooth field of the cell centre p (level-0 index units), as
/// array "f"; NaN where hole(grid, p).
void FillSmoothField(Hierarchy& h, const std::function<bool(const Grid&, const glm::dvec3&)>& hole)
{
  h.ArrayName = "f";
  h.Values.clear();
  for (const Grid& g : h.Grids)
  {
    const glm::i64vec3 e = g.Cells.Extent();
    GridValues v(static_cast<std::size_t>(g.Cells.Cells()));
    for (int64_t k = 0; k < e.z; ++k)
      for (int64_t j = 0; j < e.y; ++j)
        for (int64_t i = 0; i < e.x; ++i)
        {
          const glm::dvec3 p =
            (glm::dvec3(g.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * h.CellSize(g.Level);
          v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] = hole(g, p)
            ? std::numeric_limits<float>::quiet_NaN()
            : static_cast<float>(1.0 + std::sin(1.3 * p.x) * std::cos(0.9 * p.y) + 0.1 * p.z);
        }
    h.Values.push_back(std::move(v));
  }
}

/// A hand-made three-level hierarchy with the given refinement ratios and grids, rendered against
/// both CPU integrators. The shader has three ways to the per-level constants: computed from the
/// level (every level refines by the same 2^k on every axis, as in every dataset of the other
/// tests), read from the per-level arrays with leaf cells by shifts (powers of two that differ
/// by level or axis), or with leaf cells by integer division (other ratios).
void TestRefinementRatios(
  const std::string& what, const std::vector<glm::ivec3>& ratios, const std::vector<Grid>& grids)
{
  std::cout << "hand-made hierarchy: refinement ratios " << what << "\n";
  Hierarchy h;
  h.RefinementRatio = ratios;
  h.Grids = grids;
  FillSmoothField(h, [](const Grid&, const glm::dvec3&) { return false; });
  // Level-0 cells are a sixth of the volume: at the default sampling (one sample per cell, the
  // reference two per finest cell) and opacity, the step alone puts the kD-tree integrator 7.6
  // RMSE from the reference on a single 6^3 grid. Finer steps and a thinner medium measure the
  // cells instead (GPU vs reference 0.92, GPU vs kD-tree 0.06 with ratios 3 x 2 x 3 and 3).
  const RenderSettings s = Settings(h,
    mappertest::Request(96, 96,
      [](amrsp::harness::RenderRequest& r)
      {
        r.Scale = "linear";
        r.SampleFactor = 0.25;
        r.ReferenceSampleFactor = 0.125;
        r.UnitDistance = 2.0;
      }));
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  SinglePassRenderer gpu(h, s, ViewAngles());
  double ms = 0.0;
  const Image img = gpu.Render(0.0, ms);
  const Image ref = RenderReference(h, s);
  const double coverage = Coverage(ref);
  Check(coverage > 0.05, "the CPU reference shows the data (coverage " + Fixed(coverage) + ")");
  const double vsRef = CoveredRmse(img, ref), vsKd = CoveredRmse(img, RenderKdTree(h, enc, s));
  Check(vsRef < BoundVsReference,
    "GPU vs CPU reference: RMSE " + Fixed(vsRef) + " < " + Fixed(BoundVsReference));
  Check(vsKd < BoundVsKdTree,
    "GPU vs CPU kD-tree integrator: RMSE " + Fixed(vsKd) + " < " + Fixed(BoundVsKdTree));
}

void TestRefinementRatios()
{
  using B = Box;
  using V = glm::i64vec3;
  // 3 x 2 x 3, then 3: leaves of levels 0 and 1 have 9 x 6 x 9 and 3 x 3 x 3 finest cells per cell
  TestRefinementRatios("3 x 2 x 3 and 3 (integer division)",
    { glm::ivec3(1), glm::ivec3(3, 2, 3), glm::ivec3(3) },
    { Grid{ 0, B{ V(0), V(6) } }, Grid{ 1, B{ V(3, 2, 3), V(12, 8, 12) } },
      Grid{ 1, B{ V(12, 6, 3), V(15, 10, 9) } }, Grid{ 2, B{ V(15, 9, 15), V(27, 21, 30) } } });
  // 2 x 4 x 2, then 4: powers of two, different per axis and level (shifts, per-level arrays)
  TestRefinementRatios("2 x 4 x 2 and 4 (shifts)",
    { glm::ivec3(1), glm::ivec3(2, 4, 2), glm::ivec3(4) },
    { Grid{ 0, B{ V(0), V(6) } }, Grid{ 1, B{ V(2, 4, 2), V(8, 16, 8) } },
      Grid{ 1, B{ V(8, 12, 2), V(10, 20, 6) } }, Grid{ 2, B{ V(12, 24, 12), V(24, 48, 28) } } });
  // 4, then 4: the uniform refinement the shader computes from the level
  TestRefinementRatios("4 and 4 (computed from the level)",
    { glm::ivec3(1), glm::ivec3(4), glm::ivec3(4) },
    { Grid{ 0, B{ V(0), V(6) } }, Grid{ 1, B{ V(4), V(16) } },
      Grid{ 1, B{ V(16, 8, 4), V(20, 16, 12) } }, Grid{ 2, B{ V(24), V(48, 40, 56) } } });
}

/// A root grid refined everywhere by two finer grids: its root is a type (a) node, so level of
/// detail can show level 0 instead of level 1. One finer grid holds NaN in a corner.
void TestLevelOfDetailAndNaN()
{
  std::cout << "hand-made hierarchy: level of detail and NaN\n";
  Hierarchy h;
  h.RefinementRatio = { glm::ivec3(1), glm::ivec3(4) };
  h.Grids = { Grid{ 0, Box{ glm::i64vec3(0), glm::i64vec3(8) } },
    Grid{ 1, Box{ glm::i64vec3(0), glm::i64vec3(16, 32, 32) } },
    Grid{ 1, Box{ glm::i64vec3(16, 0, 0), glm::i64vec3(32, 32, 32) } } };
  FillSmoothField(h,
    [](const Grid& g, const glm::dvec3& p)
    { return g.Level == 1 && p.x < 2.0 && p.y < 2.0 && p.z < 2.0; });
  RenderSettings s = Settings(
    h, mappertest::Request(96, 96, [](amrsp::harness::RenderRequest& r) { r.Scale = "linear"; }));
  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  SinglePassRenderer gpu(h, s, ViewAngles());
  double ms = 0.0;
  const Image finest = gpu.Render(0.0, ms);
  const double nanVsKd = Rmse(finest, RenderKdTree(h, enc, s));
  Check(nanVsKd < BoundVsKdTree,
    "NaN cells are transparent on the GPU as on the CPU: RMSE " + Fixed(nanVsKd));
  gpu.GetMapper()->SetLODThreshold(1000.0); // every level-1 cell is "too small": show level 0
  const Image coarse = gpu.Render(0.0, ms);
  s.LodThresholdPixels = 1000.0f;
  const double lodVsKd = Rmse(coarse, RenderKdTree(h, enc, s));
  Check(Rmse(finest, coarse) > 1.0,
    "LOD changes the image (RMSE to the finest image " + Fixed(Rmse(finest, coarse)) + ")");
  Check(lodVsKd < BoundVsKdTree,
    "LOD: GPU vs CPU kD-tree with the same threshold RMSE " + Fixed(lodVsKd));
  Check(gpu.NumberOfBuilds() == 1, "changing the LOD threshold rebuilds nothing");
}

/// Bricks spread over several atlas pages (MaximumAtlasPageBytes below the one atlas's size)
/// give the one atlas's image bit for bit: nearest and smooth cells, vertex data, multipass.
void TestAtlasPages()
{
  std::cout << "atlas pages\n";
  for (const char* centering : { "cell", "vertex" })
  {
    Hierarchy h = LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3",
      std::string(centering) == "vertex" ? "vertex" : "auto");
    const std::string name = std::string(centering) + " data";
    const RenderSettings base = Settings(h, mappertest::Request(96, 96));
    for (const char* interpolation : { "nearest", "smooth" })
    {
      RenderSettings s = base;
      s.SmoothCellData = std::string(interpolation) == "smooth";
      if (h.VertexCentred && s.SmoothCellData)
      {
        continue; // the smooth reconstruction is for cell data
      }
      double ms = 0.0;
      SinglePassRenderer one(h, s, ViewAngles(), DataStorage::PackedAtlas);
      const Image single = one.Render(0.0, ms);
      SinglePassRenderer paged(h, s, ViewAngles(), DataStorage::PackedAtlas);
      paged.GetMapper()->SetMaximumAtlasPageBytes(one.GetMapper()->GetTextureBytes() / 2);
      const Image pages = paged.Render(0.0, ms);
      const int count = paged.GetMapper()->GetNumberOfAtlasPages();
      Check(one.GetMapper()->GetNumberOfAtlasPages() == 1 && count >= 2,
        name + ", " + interpolation + ": " + std::to_string(count) +
          " atlas pages under half the one atlas's bytes");
      Check(Coverage(single) > 0.05 && Rmse(single, pages) == 0.0,
        name + ", " + interpolation + ": the pages' image equals the one atlas's (RMSE " +
          Fixed(Rmse(single, pages)) + ", coverage " + Fixed(Coverage(single)) + ")");
    }
    double ms = 0.0;
    MultipassRenderer one(h, base, ViewAngles());
    const Image single = one.Render(0.0, ms);
    MultipassRenderer paged(h, base, ViewAngles());
    paged.GetMapper()->SetMaximumAtlasPageBytes(one.GetMapper()->GetTextureBytes() / 2);
    const Image pages = paged.Render(0.0, ms);
    Check(Coverage(single) > 0.05 && Rmse(single, pages) == 0.0,
      name + ", multipass: the pages' image equals the one atlas's (RMSE " +
        Fixed(Rmse(single, pages)) + ")");
  }
}

/// The mappers' ProgressEvents: the build from 0 to 1 through named steps, then the upload from
/// 0 to 1, never decreasing within either.
void TestProgressEvents()
{
  std::cout << "progress events\n";
  Hierarchy h = LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3");
  const RenderSettings s = Settings(h, mappertest::Request(48, 48));
  struct Event
  {
    double Fraction;
    std::string Text;
  };
  const auto watch = [](vtkAlgorithm* mapper, std::vector<Event>& events)
  {
    vtkNew<vtkCallbackCommand> record;
    record->SetClientData(&events);
    record->SetCallback(
      [](vtkObject* caller, unsigned long, void* client, void* call)
      {
        const char* text = static_cast<vtkAlgorithm*>(caller)->GetProgressText();
        static_cast<std::vector<Event>*>(client)->push_back(
          { *static_cast<double*>(call), text ? text : "" });
      });
    mapper->AddObserver(vtkCommand::ProgressEvent, record);
  };
  const auto check = [](const std::vector<Event>& all, const std::string& name,
                       const std::vector<std::string>& steps)
  {
    // VTK's pipeline reports 0 and 1 without text around the mapper's own update: left out
    std::vector<Event> events;
    for (const Event& e : all)
    {
      if (!e.Text.empty())
      {
        events.push_back(e);
      }
    }
    // two passes: the build, then the upload (which starts again at 0)
    std::size_t upload = events.size();
    for (std::size_t i = 1; i < events.size(); ++i)
    {
      if (events[i].Text.rfind("uploading", 0) == 0)
      {
        upload = i;
        break;
      }
    }
    bool monotone = true;
    for (std::size_t i = 1; i < events.size(); ++i)
    {
      monotone = monotone && (i == upload || events[i].Fraction >= events[i - 1].Fraction);
    }
    std::string texts;
    for (const Event& e : events)
    {
      texts += (texts.empty() ? "" : ", ") + e.Text + " " + Fixed(e.Fraction);
    }
    bool named = true;
    for (const std::string& step : steps)
    {
      named = named && texts.find(step) != std::string::npos;
    }
    Check(!events.empty() && upload < events.size() && events.front().Fraction == 0.0 &&
        events[upload - 1].Fraction == 1.0 && events[upload].Fraction == 0.0 &&
        events.back().Fraction == 1.0 && monotone && named,
      name + ": " + std::to_string(events.size()) +
        " ProgressEvents, build 0 to 1 then upload 0 to 1, never decreasing (" + texts + ")");
  };
  double ms = 0.0;
  std::vector<Event> single, multi;
  SinglePassRenderer packing(h, s, ViewAngles(), DataStorage::PackedAtlas);
  watch(packing.GetMapper(), single);
  packing.Render(0.0, ms);
  check(single, "single-pass", { "converting", "kD-tree", "packing the bricks", "uploading" });
  MultipassRenderer multipass(h, s, ViewAngles());
  watch(multipass.GetMapper(), multi);
  multipass.Render(0.0, ms);
  check(multi, "multi-pass", { "converting", "uploading" });
}

/// Reads the window back as an amrsp::Image of the pixels [x0, x0 + w) x [0, h).
Image Grab(vtkRenderWindow* window, int x0, int w, int h)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->ShouldRerenderOff();
  grab->Update();
  vtkUnsignedCharArray* rgb =
    vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
  int dims[3];
  grab->GetOutput()->GetDimensions(dims);
  Image img;
  img.Width = w;
  img.Height = h;
  for (int j = 0; j < h; ++j)
  {
    for (int i = 0; i < w; ++i)
    {
      const unsigned char* p = rgb->GetPointer(3 * (static_cast<vtkIdType>(j) * dims[0] + x0 + i));
      img.Pixels.push_back(glm::vec4(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, 1.0f));
    }
  }
  return img;
}

/// Two volumes in two renderers of one window render as they do alone; the input can change
/// again and again (each change rebuilds once), and the graphics resources can be released and
/// rebuilt.
void TestTwoRenderersAndDataChanges()
{
  std::cout << "two renderers in one window; repeated data changes\n";
  std::vector<std::unique_ptr<SinglePassRenderer>> alone;
  std::vector<Hierarchy> data;
  std::vector<Image> images;
  for (const char* spec : { "synthetic:cosmo:grids=40,levels=3,cells=100k,seed=3",
         "synthetic:cosmo:grids=40,levels=3,cells=100k,seed=8" })
  {
    DatasetRequest request;
    request.Spec = spec;
    request.NeedVTK = false;
    data.push_back(LoadDataset(request).Data);
    const RenderSettings s = Settings(data.back(), mappertest::Request(96, 96));
    alone.emplace_back(new SinglePassRenderer(data.back(), s, ViewAngles()));
    double ms = 0.0;
    images.push_back(alone.back()->Render(0.0, ms));
  }

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(192, 96);
  std::vector<vtkSmartPointer<vtkSinglePassAMRVolumeMapper>> mappers;
  for (int k = 0; k < 2; ++k)
  {
    vtkVolume* original =
      vtkVolume::SafeDownCast(alone[k]->GetRenderer()->GetVolumes()->GetItemAsObject(0));
    auto mapper = vtkSmartPointer<vtkSinglePassAMRVolumeMapper>::New();
    mapper->SetInputData(alone[k]->GetMapper()->GetAMRInput());
    mapper->SelectScalarArray(data[k].ArrayName.c_str());
    vtkNew<vtkVolume> volume;
    volume->SetMapper(mapper);
    volume->SetProperty(original->GetProperty());
    vtkNew<vtkRenderer> renderer;
    renderer->SetViewport(0.5 * k, 0.0, 0.5 * (k + 1), 1.0);
    renderer->AddVolume(volume);
    renderer->GetActiveCamera()->DeepCopy(alone[k]->GetRenderer()->GetActiveCamera());
    window->AddRenderer(renderer);
    mappers.push_back(mapper);
  }
  window->Render();
  for (int k = 0; k < 2; ++k)
  {
    const double e = Rmse(Grab(window, 96 * k, 96, 96), images[k]);
    Check(e < 0.5,
      "volume " + std::to_string(k) + " in a shared window matches its own image: RMSE " +
        Fixed(e));
  }

  // repeated data changes: one rebuild each, and the image follows the data (the second
  // dataset is shown with the first one's transfer function here, so its first image is kept)
  vtkSinglePassAMRVolumeMapper* mapper = mappers[0];
  const int builds = mapper->GetNumberOfBuilds();
  Image second;
  for (int change = 1; change <= 4; ++change)
  {
    mapper->SetInputData(alone[change % 2]->GetMapper()->GetAMRInput());
    window->Render();
    const Image img = Grab(window, 0, 96, 96);
    if (change == 1)
    {
      second = img;
    }
    const double changed = Rmse(img, images[0]);
    const double e = change % 2 ? Rmse(img, second) : changed;
    Check(std::string(mapper->GetLastError()).empty() && e < 0.5 &&
        (change % 2 == 0 || changed > 1.0) && mapper->GetNumberOfBuilds() == builds + change,
      "data change " + std::to_string(change) + ": rebuilt once, the image follows the data");
  }
  mapper->ReleaseGraphicsResources(window);
  window->Render();
  Check(
    std::string(mapper->GetLastError()).empty() && Rmse(Grab(window, 0, 96, 96), images[0]) < 0.5,
    "after ReleaseGraphicsResources the textures are uploaded again and the image is unchanged");
  window->Finalize();
}

int main()
{
  return mappertest::RunChecks(
    []
    {
      TestDataset("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3");
      TestLevelOfDetailAndNaN();
      TestAtlasPages();
      TestProgressEvents();
      TestRefinementRatios();
      TestTwoRenderersAndDataChanges();
      TestVertexCentred("synthetic:cosmo:grids=40,levels=3,cells=100k,seed=5");
      mappertest::WithEnzo(
        [](const std::string& enzo)
        {
          TestDataset(enzo);
          TestVertexCentred(enzo);
        });
    });
}
