// SPDX-License-Identifier: BSD-3-Clause
// Empty-space skipping on a real Enzo hierarchy (dark-matter density, log scale) with the
// "sparse" transfer function, transparent below 60 % of the range: the skipped image equals the
// unskipped one, the mapper reports the data nodes it skips, a transfer-function change updates
// them without a rebuild, and the CPU mirror of the shader counts the samples skipping saves.
#include "SinglePassAMRBaselineTest.h"

#include "AmrspSinglePass.h"

#include "vtkPiecewiseFunction.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkVolumeProperty.h"

#include <ostream>

int TestSinglePassAMREmptySpaceSkipping(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Array = "Dark_Matter_Density";
  c.Request.Width = 200;
  c.Request.Height = 200;
  c.Request.Zoom = 3.0;
  c.Request.UnitDistance = 0.004;
  c.Request.Tf = "sparse";
  c.Request.SkipEmptySpace = true;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image rejected
  // by the reference with at least twice the margin; measured: reference 6.04, 31.51 % of
  // the pixels off by more than 8 levels, mirror 0.58, stored baseline 0.15;
  // the noisy particle-deposited field at one sample per cell against the reference's two
  c.ReferenceBound = 8.5;
  c.ReferenceOffBound = 0.630;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  // the shader's own counts against the CPU mirror's, and zero with the feature off
  c.CheckWorkCounters = true;
  c.ExpectSkipped = true;
  c.Check = [](amrsp::harness::SinglePassRenderer& gpu, const amrsp::Image& image,
              const amrsp::RenderSettings&, std::ostream& log)
  {
    vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
    bool ok = true;
    const long long transparent = mapper->GetNumberOfTransparentDataNodes();
    const long long nodes = mapper->GetNumberOfDataNodes();
    const bool skips = transparent > 0 && transparent < nodes;
    log << (skips ? "ok" : "FAILED") << ": " << transparent << " of " << nodes
        << " data nodes are skipped as transparent\n";
    ok = ok && skips;

    // skipping off: the same image (every skipped sample had zero opacity in the table)
    const int builds = mapper->GetNumberOfBuilds();
    double ms = 0.0;
    mapper->EmptySpaceSkippingOff();
    const double offRmse = amrsp::Rmse(image, gpu.RenderAsIs(ms));
    const bool same = offRmse <= 0.05;
    log << (same ? "ok" : "FAILED") << ": skipping on vs off RMSE " << offRmse << " (bound 0.05)\n";
    ok = ok && same && mapper->GetNumberOfTransparentDataNodes() == 0;
    mapper->EmptySpaceSkippingOn();

    // a transfer function with opacity everywhere: nothing is transparent, no rebuild
    vtkRenderer* renderer = gpu.GetRenderer();
    vtkVolumeCollection* volumes = renderer->GetVolumes(); // rebuilt by every call
    volumes->InitTraversal();
    vtkVolumeProperty* property = volumes->GetNextVolume()->GetProperty();
    vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
    vtkNew<vtkPiecewiseFunction> saved;
    saved->DeepCopy(opacity);
    double range[2];
    opacity->GetRange(range);
    opacity->RemoveAllPoints();
    opacity->AddPoint(range[0], 0.01);
    opacity->AddPoint(range[1], 0.5);
    gpu.RenderAsIs(ms);
    const long long opaqueTransparent = mapper->GetNumberOfTransparentDataNodes();
    log << (opaqueTransparent == 0 ? "ok" : "FAILED")
        << ": with opacity everywhere, transparent data nodes " << opaqueTransparent << "\n";
    opacity->DeepCopy(saved);
    gpu.RenderAsIs(ms);
    const bool noRebuild = mapper->GetNumberOfBuilds() == builds &&
      mapper->GetNumberOfTransparentDataNodes() == transparent;
    log << (noRebuild ? "ok" : "FAILED")
        << ": transfer-function changes rebuilt nothing and restored the skipped nodes\n";
    return ok && opaqueTransparent == 0 && noRebuild;
  };
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
