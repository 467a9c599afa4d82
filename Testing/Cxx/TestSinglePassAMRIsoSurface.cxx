// SPDX-License-Identifier: BSD-3-Clause
// Two semi-transparent, shaded iso-surfaces (vtkVolumeMapper::ISOSURFACE_BLEND with two
// vtkVolumeProperty::GetIsoSurfaceValues()) of a three-level synthetic hierarchy: crossings are
// found between consecutive samples, also across brick and level boundaries, and refined by
// bisection through the kD-tree (the reference: through the finest-grid lookup).
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRIsoSurface(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=60,levels=3,cells=100k,seed=3";
  // iso-values at 0.4 and 0.7 of the transfer function's range (log10 of the density)
  c.Options = { "--size", "128x128", "--zoom", "1.5", "--unit-distance", "0.005", "--blend",
    "iso", "--iso", "0.4,0.7", "--tf", "grey", "--shade", "on" };
  // measured 2.3; the same surfaces unshaded score 9.9 against this image
  c.ReferenceBound = 3.0;
  c.MirrorBound = 1.0; // measured 0
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
