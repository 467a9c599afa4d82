// SPDX-License-Identifier: BSD-3-Clause
// Gradient shading (vtkVolumeProperty::ShadeOn, the renderer's headlight) of the procedural field
// of a three-level synthetic hierarchy (60 grids): the central differences reach into neighbouring
// grids and other levels through the kD-tree; the reference takes them from the finest grid
// containing each point, with no tree, so a seam at a grid or level boundary shows up as a
// difference along it. (Testing/Core/TestShading checks the two lookups agree point by point.)
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRGradientShading(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=60,levels=3,cells=100k,seed=3";
  c.Options = { "--size", "128x128", "--zoom", "1.5", "--unit-distance", "0.005", "--shade",
    "on" };
  // measured 2.9 (the same view unshaded: 3.8, from the reference's two samples per cell); the
  // unshaded reference scores 52 against this image, the light moved to (1.2, 1.5, 1.2) 11
  c.ReferenceBound = 3.5;
  c.MirrorBound = 1.0; // measured 0.07
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
