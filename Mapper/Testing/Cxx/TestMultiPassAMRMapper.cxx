// SPDX-License-Identifier: BSD-3-Clause
//
// Image test of vtkMultiPassAMRVolumeMapper (the paper's multi-pass baseline: the kD-tree ordered
// front to back on the CPU, one draw per data node, blended) on an offscreen vtkRenderWindow.
//
// Every image is checked against renderings that do not share its code path:
//   - amrsp::RenderKdTree (CPU kD-tree integrator, the same segments and samples): RMSE < 1.0
//   - vtkSinglePassAMRVolumeMapper (GPU, one pass, the same segments and samples): RMSE < 1.0
//   - amrsp::RenderReference (no kD-tree, finest cell found from the grid boxes):  RMSE < 2.0
// (RMSE over the RGB channels in 0-255 units, images of at most 128 x 128.) All three sample
// exactly the same segments, so the first two bounds only absorb float rounding at cell faces, the
// 4096-entry transfer table and the single-pass shader's early ray termination at alpha 0.999.
// The largest values measured on llvmpipe: 0.28 against the CPU kD-tree integrator and 0.40
// against the single-pass mapper (Enzo, zoom 3, an opaque transfer function); the reference bound
// is the one the core tests and the single-pass test use.
// Further checks: one draw per leaf with data, in an order that matters (an opaque transfer
// function); textures built once across camera and transfer-function changes; a camera inside
// the volume (nodes around and behind the eye, faces between the eye and the near plane);
// parallel projection; a translated volume; a viewport that does not start at the window's
// corner; opaque geometry in front of and through the volume (depth buffer); vertex-centred
// data; a missing array, an atlas over the size limit and a blend mode other than composite are
// errors and draw nothing; --lod is refused.
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

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPlaneSource.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
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

constexpr double BoundVsSinglePass = 1.0;
double LargestVsKdTree = 0.0;
double LargestVsSinglePass = 0.0;

/// Checks `img` against the CPU kD-tree integrator's image of `s` and records the largest RMSE.
void CheckVsKdTree(const Image& img, const Hierarchy& h, const EncodedKdTree& enc,
  const RenderSettings& s, const std::string& what)
{
  const double e = Rmse(img, RenderKdTree(h, enc, s));
  LargestVsKdTree = std::max(LargestVsKdTree, e);
  Check(e < BoundVsKdTree,
    what + ": multi-pass vs CPU kD-tree RMSE " + Fixed(e) + " < " + Fixed(BoundVsKdTree));
}

void CheckVsSinglePass(const Image& multi, const Image& single, const std::string& what)
{
  const double e = Rmse(multi, single);
  LargestVsSinglePass = std::max(LargestVsSinglePass, e);
  Check(e < BoundVsSinglePass,
    what + ": multi-pass vs single-pass RMSE " + Fixed(e) + " < " + Fixed(BoundVsSinglePass));
}

/// Expects `render` to throw a GpuError whose message contains every string of `needles`.
template <typename F>
void CheckError(F render, const std::vector<std::string>& needles, const std::string& what)
{
  std::string message;
  bool threw = false;
  try
  {
    render();
  }
  catch (const GpuError& e)
  {
    threw = true;
    message = e.what();
  }
  bool found = threw;
  for (const std::string& n : needles)
  {
    found = found && message.find(n) != std::string::npos;
  }
  Check(found, what + ": " + (threw ? message : "no error"));
}

/// Opaque geometry in front of and through the volume, and errors, on the renderers of
/// TestDataset (multi-pass `gpu`, single-pass `single`; `before`: the default view's image).
void TestOccludersAndErrors(MultipassRenderer& gpu, SinglePassRenderer& single, const Image& before)
{
  double ms = 0.0;
  // opaque geometry: a white square in front of the volume hides it; a black one through the
  // centre hides the back half only
  {
    OccluderView view;
    const Image plain = CheckSquareInFrontHides(gpu, view);

    vtkSmartPointer<vtkActor> middle = view.SquareThroughCentre();
    vtkSmartPointer<vtkActor> middleSingle = view.SquareThroughCentre();
    gpu.GetRenderer()->AddActor(middle);
    single.GetRenderer()->AddActor(middleSingle);
    const Image frontHalf = gpu.Render(0.0, ms);
    const Image singleFrontHalf = single.Render(0.0, ms);
    gpu.GetMapper()->UseDepthBufferOff();
    const Image ignoring = gpu.Render(0.0, ms);
    gpu.GetMapper()->UseDepthBufferOn();
    gpu.GetRenderer()->RemoveActor(middle);
    single.GetRenderer()->RemoveActor(middleSingle);
    Check(Rmse(ignoring, plain) < 0.5 && Rmse(frontHalf, plain) > 1.0,
      "opaque square through the centre clips the rays (RMSE to the unclipped image " +
        Fixed(Rmse(frontHalf, plain)) + "; with UseDepthBuffer off " +
        Fixed(Rmse(ignoring, plain)) + ")");
    CheckVsSinglePass(frontHalf, singleFrontHalf, "opaque square through the centre");
  }

  // errors: nothing drawn, no crash, and rendering recovers
  {
    vtkMultiPassAMRVolumeMapper* mapper = gpu.GetMapper();
    const std::string array = mapper->GetArrayName();
    mapper->SelectScalarArray("NoSuchArray");
    CheckError([&] { gpu.Render(0.0, ms); }, { "no cell array named 'NoSuchArray'" },
      "a missing array is an error");
    mapper->SelectScalarArray(array.c_str());
    Check(Rmse(gpu.Render(0.0, ms), before) < 0.01, "selecting the array again renders again");
    mapper->SetMaximumAtlasSize(4);
    CheckError([&] { gpu.Render(0.0, ms); }, { "cannot pack the bricks" },
      "an atlas over the size limit is an error");
    mapper->SetMaximumAtlasSize(0);
    Check(Rmse(gpu.Render(0.0, ms), before) < 0.01, "with the limit lifted it renders again");
    mapper->SetBlendModeToMaximumIntensity();
    CheckError([&] { gpu.Render(0.0, ms); }, { "composite blending only" },
      "a blend mode other than composite is an error");
    mapper->SetBlendModeToComposite();
    Check(Rmse(gpu.Render(0.0, ms), before) < 0.01, "composite blending renders again");
  }
}

/// The camera inside the volume, parallel projection and a moved volume, a viewport, opaque
/// geometry and errors, on the renderers of TestDataset (multi-pass `gpu`, single-pass `single`;
/// `before`: the multi-pass image of the default view).
void TestViewsAndErrors(Hierarchy& h, const EncodedKdTree& enc, const RenderSettings& s,
  MultipassRenderer& gpu, SinglePassRenderer& single, const Image& before)
{
  double ms = 0.0;
  vtkVolume* volume = vtkVolume::SafeDownCast(gpu.GetRenderer()->GetVolumes()->GetItemAsObject(0));
  // camera inside the volume: nodes around and behind the eye, faces in front of the near plane
  {
    vtkCamera* camera = gpu.GetRenderer()->GetActiveCamera();
    vtkCamera* singleCamera = single.GetRenderer()->GetActiveCamera();
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
    Check(isInside && Coverage(inside) > 0.5,
      "camera inside the volume renders (coverage " + Fixed(Coverage(inside)) + ")");
    CheckVsKdTree(inside, h, enc, is, "camera inside");
    single.Render(0.0, ms);
    singleCamera->DeepCopy(camera);
    single.GetRenderer()->ResetCameraClippingRange();
    CheckVsSinglePass(inside, single.RenderAsIs(ms), "camera inside");

    // a near plane a quarter of the volume away: rays still start at the eye, so the nodes
    // between the eye and the near plane must still be drawn (depth clamping)
    const double nearDistance = 0.25 * std::min(b[1] - b[0], std::min(b[3] - b[2], b[5] - b[4]));
    camera->SetClippingRange(nearDistance, 4.0 * (b[1] - b[0] + b[3] - b[2] + b[5] - b[4]));
    const Image farNear = gpu.RenderAsIs(ms);
    CheckVsKdTree(farNear, h, enc, is, "camera inside, near plane a quarter of the volume away");
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
    Check(ps.View.Parallel && Coverage(parallel) > 0.05, "parallel projection renders");
    CheckVsKdTree(parallel, h, enc, ps, "parallel projection");

    const Image unmoved = gpu.Render(0.0, ms);
    double b[6];
    volume->GetBounds(b);
    const double shift[3] = { 0.75 * (b[1] - b[0]), -0.5 * (b[3] - b[2]), 0.25 * (b[5] - b[4]) };
    volume->SetPosition(shift[0], shift[1], shift[2]);
    gpu.Render(0.0, ms);
    double pos[3], f[3];
    camera->GetPosition(pos);
    camera->GetFocalPoint(f);
    camera->SetPosition(pos[0] + shift[0], pos[1] + shift[1], pos[2] + shift[2]);
    camera->SetFocalPoint(f[0] + shift[0], f[1] + shift[1], f[2] + shift[2]);
    gpu.GetRenderer()->ResetCameraClippingRange();
    const Image moved = gpu.RenderAsIs(ms);
    volume->SetPosition(0.0, 0.0, 0.0);
    const double m = Rmse(moved, unmoved);
    Check(m < 0.5, "volume and camera translated together: RMSE to the unmoved image " + Fixed(m));
  }

  // a viewport in the right half of the window: the accumulation target covers the viewport
  // only, and the composite must land there
  {
    // (an empty black renderer clears the left half, which the volume's renderer leaves alone)
    vtkNew<vtkRenderer> leftOfGpu, leftOfSingle;
    leftOfGpu->SetViewport(0.0, 0.0, 0.5, 1.0);
    leftOfSingle->SetViewport(0.0, 0.0, 0.5, 1.0);
    gpu.GetRenderer()->GetRenderWindow()->AddRenderer(leftOfGpu);
    single.GetRenderer()->GetRenderWindow()->AddRenderer(leftOfSingle);
    gpu.GetRenderer()->SetViewport(0.5, 0.0, 1.0, 1.0);
    single.GetRenderer()->SetViewport(0.5, 0.0, 1.0, 1.0);
    const Image m = gpu.Render(0.0, ms);
    const Image p = single.Render(0.0, ms);
    gpu.GetRenderer()->SetViewport(0.0, 0.0, 1.0, 1.0);
    single.GetRenderer()->SetViewport(0.0, 0.0, 1.0, 1.0);
    gpu.GetRenderer()->GetRenderWindow()->RemoveRenderer(leftOfGpu);
    single.GetRenderer()->GetRenderWindow()->RemoveRenderer(leftOfSingle);
    const std::vector<std::uint8_t> rgb = m.Rgb8();
    int leftLit = 0;
    for (int j = 0; j < m.Height; ++j)
    {
      for (int i = 0; i < m.Width / 2; ++i)
      {
        const std::size_t k = 3 * (static_cast<std::size_t>(j) * m.Width + i);
        leftLit += (rgb[k] + rgb[k + 1] + rgb[k + 2] > 0) ? 1 : 0;
      }
    }
    Check(leftLit == 0 && Coverage(m) > 0.02,
      "viewport (0.5, 0, 1, 1): nothing drawn left of it (" + std::to_string(leftLit) +
        " lit pixels), the volume inside it");
    CheckVsSinglePass(m, p, "viewport (0.5, 0, 1, 1)");
  }

  TestOccludersAndErrors(gpu, single, before);
}

void TestDataset(const std::string& spec)
{
  std::cout << "dataset " << spec << "\n";
  Hierarchy h = LoadHierarchy(spec);
  const RenderSettings s = Settings(h, mappertest::Request(128, 128));
  const KdTree tree = BuildKdTree(h);
  const EncodedKdTree enc = EncodeKdTree(h, tree);

  MultipassRenderer gpu(h, s, ViewAngles());
  SinglePassRenderer single(h, s, ViewAngles());
  double ms = 0.0;
  const Image img = gpu.Render(0.0, ms);
  const Image ref = RenderReference(h, s);
  Check(Coverage(ref) > 0.05,
    "the CPU reference shows the data (coverage " + Fixed(Coverage(ref)) + ")");
  Check(CameraDifference(gpu.LastCamera(), s.View) < 1e-6,
    "VTK's ResetCamera/Azimuth/Elevation/Zoom match the tool's camera conventions");
  const double vsRef = CoveredRmse(img, ref);
  Check(vsRef < BoundVsReference,
    "multi-pass vs CPU reference: RMSE " + Fixed(vsRef) + " < " + Fixed(BoundVsReference));
  CheckVsKdTree(img, h, enc, s, "default view");
  CheckVsSinglePass(img, single.Render(0.0, ms), "default view");

  // one draw per leaf with data (the finest level everywhere)
  long long leaves = 0;
  for (const KdNode& n : tree.Nodes)
  {
    leaves += (n.IsLeaf() && n.HasData()) ? 1 : 0;
  }
  Check(gpu.Passes() == leaves && leaves > 0,
    "one draw per data leaf: " + std::to_string(gpu.Passes()) + " draws, " +
      std::to_string(leaves) + " leaves with data");

  // the orbit of the bench and a zoomed view
  for (double orbit : { 90.0, 200.0 })
  {
    RenderSettings fs = s;
    fs.View.Azimuth(orbit);
    const Image o = gpu.Render(orbit, ms);
    CheckVsKdTree(o, h, enc, fs, "orbit " + Fixed(orbit) + " deg");
    CheckVsSinglePass(o, single.Render(orbit, ms), "orbit " + Fixed(orbit) + " deg");
  }
  {
    RenderSettings zs = Settings(
      h, mappertest::Request(128, 128, [](amrsp::harness::RenderRequest& r) { r.Zoom = 3.0; }));
    ViewAngles zoomed;
    zoomed.Zoom = 3.0;
    MultipassRenderer mz(h, zs, zoomed);
    SinglePassRenderer sz(h, zs, zoomed);
    const Image z = mz.Render(0.0, ms);
    CheckVsKdTree(z, h, enc, zs, "zoom 3");
    CheckVsSinglePass(z, sz.Render(0.0, ms), "zoom 3");
  }

  // an opaque transfer function: the segments' order decides the image
  {
    RenderSettings os = Settings(h,
      mappertest::Request(96, 96,
        [](amrsp::harness::RenderRequest& r)
        {
          r.Azimuth = -60.0;
          r.Elevation = 35.0;
          r.UnitDistance = 1e-3;
        }));
    ViewAngles view;
    view.Azimuth = -60.0;
    view.Elevation = 35.0;
    MultipassRenderer mo(h, os, view);
    SinglePassRenderer so(h, os, view);
    const Image o = mo.Render(0.0, ms);
    const Image back = mo.Render(180.0, ms);
    CheckVsKdTree(o, h, enc, os, "opaque transfer function");
    CheckVsSinglePass(o, so.Render(0.0, ms), "opaque transfer function");
    RenderSettings bs = os;
    bs.View.Azimuth(180.0);
    CheckVsKdTree(back, h, enc, bs, "opaque transfer function, seen from behind");
    Check(Rmse(o, back) > 5.0,
      "front and back views differ (the order matters): RMSE " + Fixed(Rmse(o, back)));
  }

  // a transfer-function change is visible and rebuilds nothing
  const Image before = CheckTransferChangeRebuildsNothing(gpu, s, "the frames");

  TestViewsAndErrors(h, enc, s, gpu, single, before);
}

/// Vertex-centred data (trilinear atlas sampling) against the CPU kD-tree integrator and the
/// single-pass mapper.
void TestVertexCentred(const std::string& spec)
{
  std::cout << "dataset " << spec << " (vertex-centred)\n";
  Hierarchy h = LoadHierarchy(spec, "vertex");
  Check(h.VertexCentred, "the data was converted to vertices");
  const RenderSettings s = Settings(h, mappertest::Request(96, 96));
  MultipassRenderer gpu(h, s, ViewAngles());
  SinglePassRenderer single(h, s, ViewAngles());
  double ms = 0.0;
  const Image img = gpu.Render(0.0, ms);
  CheckVsKdTree(img, h, EncodeKdTree(h, BuildKdTree(h)), s, "vertex-centred");
  CheckVsSinglePass(img, single.Render(0.0, ms), "vertex-centred");
  const double vsRef = CoveredRmse(img, RenderReference(h, s));
  Check(vsRef < BoundVsReference,
    "vertex-centred: multi-pass vs CPU reference RMSE " + Fixed(vsRef) + " < " +
      Fixed(BoundVsReference));
}

} // namespace

int main()
{
  const int code = mappertest::RunChecks(
    []
    {
      TestDataset("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3");
      TestVertexCentred("synthetic:cosmo:grids=40,levels=3,cells=100k,seed=5");
      std::cout << "level of detail\n";
      Hierarchy small = LoadHierarchy("synthetic:cosmo:grids=20,levels=2,cells=50k,seed=1");
      RenderSettings s = Settings(small, mappertest::Request(32, 32));
      s.LodThresholdPixels = 2.0f;
      CheckError([&] { MultipassRenderer refused(small, s, ViewAngles()); },
        { "finest level only" }, "--lod is refused by the multipass method");
      mappertest::WithEnzo(
        [](const std::string& enzo)
        {
          TestDataset(enzo);
          TestVertexCentred(enzo);
        });
    });
  std::cout << "largest RMSE (0-255): multi-pass vs CPU kD-tree " << Fixed(LargestVsKdTree)
            << ", vs single-pass " << Fixed(LargestVsSinglePass) << "\n";
  return code;
}
