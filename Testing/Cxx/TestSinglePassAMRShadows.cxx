// SPDX-License-Identifier: BSD-3-Clause
// Shadow rays toward a point light at (1.2, 1.5, 1.2) (a scene vtkLight; the data is the unit
// cube) with gradient shading: each composite sample's light is attenuated by the transmittance
// toward the light, sampled through the kD-tree every 0.08 world units
// (vtkSinglePassAMRVolumeMapper::SetShadows, SetShadowSampleDistance).
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRShadows(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=60,levels=3,cells=100k,seed=3";
  c.Options = { "--size", "96x96", "--zoom", "1.5", "--unit-distance", "0.005", "--shade", "on",
    "--light", "1.2,1.5,1.2", "--shadows", "0.08" };
  // measured 2.3; the reference of the same light without shadows scores 19 against this image
  c.ReferenceBound = 3.0;
  c.MirrorBound = 1.0; // measured 0.05
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
