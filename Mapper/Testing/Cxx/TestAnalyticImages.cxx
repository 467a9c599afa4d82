// SPDX-License-Identifier: BSD-3-Clause
//
// Features of vtkSinglePassAMRVolumeMapper checked against expectations that come from neither
// the shader's CPU mirror nor the CPU reference: hand-made hierarchies and views whose right image
// is known from the geometry and the rule's definition, pixel by pixel.
//
//   lod         the level-of-detail rule (docs/design.md): a type (a) node stops the descent when
//               one cell of its data level is smaller than LODThreshold pixels at the ray's entry.
//               Level 0 holds 1 (red), a level-1 patch over the middle holds 2 (green); maximum
//               intensity shows which level a ray sampled. Parallel view, level-0 cells of 8
//               pixels: thresholds 6 and off show the patch green, 10 and 16 red. Perspective view
//               close to the patch: green exactly where the ray enters the patch nearer than
//               c0 / (threshold x pixel size per distance), a disc computed per pixel here.
//   iso         iso-surfaces of f = distance from the centre at two iso-values: two spheres of
//               known radius seen along an axis; red (the inner value's colour) only inside the
//               inner ring, blue inside the outer, background beyond.
//               Then eight iso-values, up to three crossed between two samples: every pixel is
//               the textbook composite of the eight layers in the order the ray meets them.
//   nan         a column of NaN cells through the whole volume shows the background exactly, the
//               rest of the volume is drawn. Then slabs across the rays: NaN cells are skipped
//               (the ray goes on behind them), +Inf cells take the transfer function's last
//               point; each pixel is the composite computed here from the segment lengths.
//
// Each mode runs its checks twice, with the fragment and the compute caster (RayCaster), and
// shows in the test that the wrong rule fails its check: the shader with the LOD rule
// off by a factor 2 or dropped, one iso-value dropped, the crossings of a sample pair in
// ascending value or beyond the second dropped, NaN samples made opaque or ending the ray, +Inf
// treated as NaN (shader replacements, as TestLinearStorage breaks its layer stride). The layer
// and slab expectations are also required of the CPU reference and the CPU mirror.

#include "AnalyticScenes.h"

#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode != "lod" && mode != "iso" && mode != "nan")
  {
    std::cerr << "usage: TestAnalyticImages lod|iso|nan\n";
    return 2;
  }
  std::string why;
  if (!amrsp::harness::GpuRenderer::Available(why))
  {
    return mappertest::SkipOrFail(why);
  }
  try
  {
    // every check with each caster (vtkSinglePassAMRVolumeMapper::RayCaster)
    for (amrsp::RayCaster caster : { amrsp::RayCaster::Fragment, amrsp::RayCaster::Compute })
    {
      analytic::Caster = caster;
      std::cout << "cast by the " << amrsp::RayCasterName(caster) << " shader\n";
      if (mode == "lod")
      {
        analytic::TestLevelOfDetail();
      }
      else if (mode == "iso")
      {
        analytic::TestIsoSurfaces();
        analytic::TestIsoLayers();
      }
      else
      {
        analytic::TestNaN();
        analytic::TestMissingAndInfiniteSlabs();
        analytic::TestMissingDataInOtherModes();
      }
    }
  }
  catch (const std::exception& e)
  {
    std::cout << "  FAILED  " << e.what() << "\n";
    return 1;
  }
  return mappertest::Failures() == 0 ? 0 : 1;
}
