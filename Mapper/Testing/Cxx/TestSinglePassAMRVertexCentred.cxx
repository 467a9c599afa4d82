// SPDX-License-Identifier: BSD-3-Clause
// Vertex-centred data (trilinear, continuous across levels) of a real Enzo hierarchy.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRVertexCentred(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Array = "Density";
  c.Centering = "vertex";
  c.Request.Width = 200;
  c.Request.Height = 200;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image rejected
  // by the reference with at least twice the margin; measured: reference 0.32, 0.00 % of
  // the pixels off by more than 8 levels, mirror 0.02, stored baseline 0.00
  c.ReferenceBound = 0.6;
  c.ReferenceOffBound = 0.005;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
