// SPDX-License-Identifier: BSD-3-Clause
// Early ray termination at opacity 0.95 on a real AMReX plotfile made dense (a short unit
// distance, so that most rays become nearly opaque): the CPU reference and the CPU mirror stop
// at the same threshold; without termination no 8-bit channel differs by more than
// (1 - 0.95) * 255 + 1, and the threshold visibly matters (the test can fail).
#include "SinglePassAMRBaselineTest.h"

#include "AmrspSinglePass.h"

#include "amrsp/ImageDifference.h"

#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>

int TestSinglePassAMREarlyTermination(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:amrex_plt1_Y";
  c.Array = "Y(H2)";
  c.Request.Width = 200;
  c.Request.Height = 200;
  c.Request.UnitDistance = 0.0002;
  c.Request.OpacityThreshold = 0.95;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image rejected
  // by the reference with at least twice the margin; measured: reference 2.75, 1.94 % of
  // the pixels off by more than 8 levels, mirror 0.32, stored baseline 0.04
  c.ReferenceBound = 4.2;
  c.ReferenceOffBound = 0.039;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  c.WrongImages.push_back({ "rays stopped at opacity 0.5",
    [](amrsp::RenderSettings& s) { s.OpacityThreshold = 0.5; }, nullptr });
  // the shader's own counts against the CPU mirror's, and zero with the feature off
  c.CheckWorkCounters = true;
  c.ExpectTerminated = true;
  c.Check = [](amrsp::harness::SinglePassRenderer& gpu, const amrsp::Image& image,
              const amrsp::RenderSettings&, std::ostream& log)
  {
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    double ms = 0.0;
    mapper->SetOpacityThreshold(1.0);
    const amrsp::Image full = gpu.RenderAsIs(ms);
    mapper->SetOpacityThreshold(0.5);
    const amrsp::Image half = gpu.RenderAsIs(ms);
    mapper->SetOpacityThreshold(0.95);
    const int bound = static_cast<int>(std::ceil(0.05 * 255.0)) + 1;
    const int difference = amrsp::Compare(image, full).Largest;
    const int halfDifference = amrsp::Compare(half, full).Largest;
    log << (difference <= bound ? "ok" : "FAILED") << ": threshold 0.95 vs no termination: largest "
        << "channel difference " << difference << " (bound " << bound << "), RMSE "
        << amrsp::Rmse(image, full) << "\n"
        << (halfDifference > 2 * bound ? "ok" : "FAILED")
        << ": threshold 0.5 vs no termination: largest channel difference " << halfDifference
        << " (must exceed " << 2 * bound << ")\n";
    return difference <= bound && halfDifference > 2 * bound;
  };
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
