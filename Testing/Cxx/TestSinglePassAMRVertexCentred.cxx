// SPDX-License-Identifier: BSD-3-Clause
// Vertex-centred data (trilinear, continuous across levels) of a real Enzo hierarchy.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRVertexCentred(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Options = { "--array", "Temperature", "--centering", "vertex", "--size", "200x200" };
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
