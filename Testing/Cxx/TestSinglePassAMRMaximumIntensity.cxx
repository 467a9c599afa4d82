// SPDX-License-Identifier: BSD-3-Clause
// Maximum-intensity projection of a real Enzo hierarchy (vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND).
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRMaximumIntensity(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Options = { "--array", "Density", "--size", "200x200", "--blend", "maximum", "--tf", "grey-opaque" };
  // measured 2.5: at one sample per cell the ray misses some of the maxima the reference's two
  // samples per cell find
  c.ReferenceBound = 3.0;
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
