// SPDX-License-Identifier: BSD-3-Clause
// Level boundaries with gradient shading and smooth cell data: a paraboloid f = |x - c|^2 sampled
// at the cell centres of a two-level hierarchy (a level-0 grid of 16^3 cells over the unit cube
// and a ratio-2 patch of 16^3 cells over its middle [1/4, 3/4)^3) is rendered shaded and compared
// with the same field on ONE level of 32^3 cells (the finest resolution, no level boundary at all)
// in the same view. The transfer function shows a ball of radius about 0.3 about c, whose surface
// crosses the patch's faces (0.25 from c): a seam would show there. The central differences read
// the smooth reconstruction at the neighbours (amrspSampleNear in the shader,
// ShadingContext::Neighbours in the CPU integrators).
#include "SinglePassAMRBaselineTest.h"

#include "AmrspSinglePass.h"
#include "TestHierarchies.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include <cmath>
#include <ostream>

namespace
{
constexpr int Finest = 32;
const glm::dvec3 Centre(0.52, 0.47, 0.5);

double Field(const glm::dvec3& x)
{
  return glm::dot(x - Centre, x - Centre);
}

/// In the field's own values (the same for both hierarchies, whose value ranges differ).
void Transfer(amrsp::RenderSettings& s)
{
  s.Transfer.Color = { { 0.0, { 0.95, 0.75, 0.35 } }, { 0.1, { 0.35, 0.55, 0.95 } } };
  s.Transfer.Opacity = { { 0.0, 0.6 }, { 0.04, 0.6 }, { 0.1, 0.0 } };
  s.Transfer.UnitDistance = 0.02;
}

// Bounds (RMSE, 0-255; measured on llvmpipe at 128x128). The two-level image differs from the
// one-level image by 1.08, the CPU references of the two by 1.09 (the coarse cells outside the
// patch interpolate the curved field less exactly; the reconstruction is linear-exact across the
// level boundary). The earlier reconstruction (dual-cell corners from the finest cell containing
// them, not linear-exact at the boundary) gave 2.00 and 1.98; with the gradient's neighbours
// read nearest-cell the GPU images differed by 2.87; with nearest cells for values and gradients
// they differ by 3.96.
constexpr double SeamBound = 1.5;
constexpr double ExcessBound = 0.4; // the GPU's difference beyond the references' (0.02)
} // namespace

int TestSinglePassAMRLevelSeams(int argc, char* argv[])
{
  using namespace amrsp;
  test::BaselineCase c;
  c.Dataset = "paraboloid on a two-level patch hierarchy (16^3 + 16^3 cells)";
  c.Data = [] { return test::LevelPatch(2, Finest, Field); };
  c.Request.Width = 128;
  c.Request.Height = 128;
  c.Request.Zoom = 2.5;
  c.Request.SampleFactor = 0.5;
  c.Request.Scale = "linear";
  c.Request.Shade = true;
  c.Request.SmoothCells = true;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image (level 0
  // alone included) rejected by the reference with at least twice the margin; measured: reference
  // 0.49, 0.00 % of the pixels off by more than 8 levels, mirror 0.01, stored baseline 0.00
  c.ReferenceBound = 0.75;
  c.ReferenceOffBound = 0.005;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  c.Settings = Transfer;
  c.WrongImages.push_back(
    { "nearest-cell values", [](RenderSettings& s) { s.SmoothCellData = false; }, nullptr });
  c.Check = [](harness::SinglePassRenderer& gpu, const Image& image, const RenderSettings& s,
              std::ostream& log)
  {
    const Hierarchy two = test::LevelPatch(2, Finest, Field);
    const Hierarchy one = test::LevelPatch(1, Finest, Field);
    harness::ViewAngles same;
    same.UseSettingsCamera = true;
    harness::SinglePassRenderer flat(one, s, same);
    double ms = 0.0;
    const Image flatImage = flat.Render(0.0, ms);
    const double seam = Rmse(image, flatImage);
    // the CPU reference of both hierarchies: what the rule itself leaves
    const double referenceSeam = Rmse(RenderReference(two, s), RenderReference(one, s));
    // nearest cells (values and gradients) on both: the comparison can fail
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    mapper->SetCellInterpolationToNearest();
    flat.GetMapper()->SetCellInterpolationToNearest();
    const double nearest = Rmse(gpu.RenderAsIs(ms), flat.RenderAsIs(ms));
    mapper->SetCellInterpolationToSmooth();
    const bool excess = std::abs(seam - referenceSeam) < ExcessBound;
    const bool ok = seam < SeamBound && excess && nearest > SeamBound;
    log << (seam < SeamBound ? "ok" : "FAILED")
        << ": two-level vs one-level (finest) GPU image RMSE " << seam << " (bound " << SeamBound
        << ")\n"
        << (excess ? "ok" : "FAILED") << ": the CPU references of the two differ by "
        << referenceSeam << " (the GPU's difference may exceed it by " << ExcessBound << ")\n"
        << (nearest > SeamBound ? "ok" : "FAILED")
        << ": with nearest cells the two-level and one-level images differ by RMSE " << nearest
        << " (must exceed " << SeamBound << ")\n";
    return ok;
  };
  return test::RunBaselineTest(argc, argv, c);
}
