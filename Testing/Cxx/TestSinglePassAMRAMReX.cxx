// SPDX-License-Identifier: BSD-3-Clause
// A real AMReX plotfile (3 levels, 73 boxes, each level covering the domain): H2 mass fraction.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRAMReX(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:amrex_plt1_Y";
  c.Options = { "--array", "Y(H2)", "--size", "200x200" };
  c.ReferenceBound = 2.5; // measured 1.7 on llvmpipe: one sample per cell vs the finer reference
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
