// SPDX-License-Identifier: BSD-3-Clause
// Opaque geometry intersecting the volume: a white square through the centre of a synthetic
// hierarchy (the unit cube) ends the rays where it is, through the depth buffer.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMROpaqueGeometry(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=120,levels=4,cells=300k,seed=2";
  c.Request.Width = 200;
  c.Request.Height = 200;
  c.Request.UnitDistance = 0.02;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image (level 0
  // alone included) rejected by the reference with at least twice the margin; measured:
  // reference 1.33, 0.67 % of the pixels off by more than 8 levels, mirror 0.26, stored baseline
  // 0.02; square edges rasterized on the GPU, intersected exactly on the CPU
  c.ReferenceBound = 2.0;
  c.ReferenceOffBound = 0.009;
  c.MirrorBound = 0.5;
  c.BaselineBound = 0.3;
  c.Squares.push_back(
    { glm::dvec3(0.5, 0.5, 0.5), glm::dvec3(0.3, 0.2, 1.0), glm::dvec3(0.0, 1.0, 0.0), 0.3, 1.0 });
  c.WrongImages.push_back(
    { "the square ignored", [](amrsp::RenderSettings& s) { s.Opaque = nullptr; }, nullptr });
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
