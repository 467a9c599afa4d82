// SPDX-License-Identifier: BSD-3-Clause
// A deep synthetic hierarchy: 8 levels of clustered refinement.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRDeepSynthetic(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=300,levels=8,cells=600k,seed=4";
  c.Options = { "--size", "200x200", "--unit-distance", "0.01" };
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
