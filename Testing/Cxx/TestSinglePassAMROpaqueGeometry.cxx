// SPDX-License-Identifier: BSD-3-Clause
// Opaque geometry intersecting the volume: a white square through the centre of a synthetic
// hierarchy (the unit cube) ends the rays where it is, through the depth buffer.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMROpaqueGeometry(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=120,levels=4,cells=300k,seed=2";
  c.Options = { "--size", "200x200", "--unit-distance", "0.02" };
  c.Squares.push_back({ glm::dvec3(0.5, 0.5, 0.5), glm::dvec3(0.3, 0.2, 1.0),
    glm::dvec3(0.0, 1.0, 0.0), 0.3, 1.0 });
  // square edges are rasterized on the GPU and intersected exactly on the CPU
  c.ReferenceBound = 2.0; // measured 0.9
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
