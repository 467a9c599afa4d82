// SPDX-License-Identifier: BSD-3-Clause
// vtkVolumeMapper's cropping of the central sub-volume (VTK_CROP_SUBVOLUME) on a real Enzo
// hierarchy, with smooth cell data: the rays are integrated inside the cropping box only, while
// smooth corners read the cells beyond its faces (as an MPI rank reads its ghost cells). The
// CPU reference and the CPU mirror clip their rays to the same box (RenderSettings::Clip).
// Checks: the uncropped image differs; unsupported cropping flags are ignored (the whole
// volume, with a warning); the multi-pass mapper, cropped the same way, gives the same image.
#include "SinglePassAMRBaselineTest.h"

#include "AmrspSinglePass.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include <ostream>

int TestSinglePassAMRCropping(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Array = "Density";
  c.Request.Width = 160;
  c.Request.Height = 160;
  c.Request.UnitDistance = 0.01;
  c.Request.SmoothCells = true;
  c.Request.Crop = std::array<double, 6>{ 0.2, 0.75, 0.3, 0.9, 0.25, 0.8 };
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image rejected
  // by the reference with at least twice the margin; measured: reference 0.42, 0.00 % of
  // the pixels off by more than 8 levels, mirror 0.02, stored baseline 0.00
  c.ReferenceBound = 0.7;
  c.ReferenceOffBound = 0.005;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  c.WrongImages.push_back(
    { "no cropping", [](amrsp::RenderSettings& s) { s.Clip = false; }, nullptr });
  c.Check = [](amrsp::harness::SinglePassRenderer& gpu, const amrsp::Image& image,
              const amrsp::RenderSettings&, std::ostream& log)
  {
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    double ms = 0.0;
    mapper->SetCropping(0);
    const amrsp::Image whole = gpu.RenderAsIs(ms);
    const double uncropped = amrsp::Rmse(image, whole);
    mapper->SetCropping(1);
    mapper->SetCroppingRegionFlagsToFence();
    const double unsupported = amrsp::Rmse(whole, gpu.RenderAsIs(ms));
    mapper->SetCroppingRegionFlagsToSubVolume();
    const bool ok = uncropped > 3.0 && unsupported < 0.01;
    log << (uncropped > 3.0 ? "ok" : "FAILED") << ": cropped vs uncropped image RMSE " << uncropped
        << " (must exceed 3)\n"
        << (unsupported < 0.01 ? "ok" : "FAILED")
        << ": unsupported cropping flags (fence) vs uncropped RMSE " << unsupported
        << " (must be below 0.01: ignored)\n";
    return ok;
  };
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
