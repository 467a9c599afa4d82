// SPDX-License-Identifier: BSD-3-Clause
// A real Enzo hierarchy (8 levels), gas density.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMREnzo(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:enzo_moving7/DD0010/moving7_0010.hierarchy";
  c.Options = { "--array", "Density", "--size", "200x200", "--unit-distance", "0.01" };
  c.ReferenceBound = 2.5; // measured 1.8 on llvmpipe: one sample per cell vs the finer reference
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
