// SPDX-License-Identifier: BSD-3-Clause
// A real AMReX plotfile (3 levels, 73 boxes, each level covering the domain): H2 mass fraction.
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRAMReX(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "data:amrex_plt1_Y";
  c.Array = "Y(H2)";
  c.Request.Width = 200;
  c.Request.Height = 200;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image rejected
  // by the reference with at least twice the margin; measured: reference 2.42, 1.62 % of
  // the pixels off by more than 8 levels, mirror 0.25, stored baseline 0.05;
  // one sample per cell against the reference's two
  c.ReferenceBound = 3.7;
  c.ReferenceOffBound = 0.032;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
