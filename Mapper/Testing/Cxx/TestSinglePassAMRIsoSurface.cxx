// SPDX-License-Identifier: BSD-3-Clause
// Two semi-transparent, shaded iso-surfaces (vtkVolumeMapper::ISOSURFACE_BLEND with two
// vtkVolumeProperty::GetIsoSurfaceValues()) of a three-level synthetic hierarchy: crossings are
// found between consecutive samples, also across brick and level boundaries, and refined by
// bisection through the kD-tree (the reference: through the finest-grid lookup).
#include "SinglePassAMRBaselineTest.h"

int TestSinglePassAMRIsoSurface(int argc, char* argv[])
{
  amrsp::test::BaselineCase c;
  c.Dataset = "synthetic:cosmo:grids=60,levels=3,cells=100k,seed=3";
  // iso-values at 0.4 and 0.7 of the transfer function's range (log10 of the density)
  c.Request.Width = 128;
  c.Request.Height = 128;
  c.Request.Zoom = 1.5;
  c.Request.UnitDistance = 0.005;
  c.Request.Blend = amrsp::BlendMode::IsoSurface;
  c.Request.Iso = std::vector<double>{ 0.4, 0.7 };
  c.Request.Tf = "grey";
  c.Request.Shade = true;
  // covered-pixel bounds close to what llvmpipe (LLVM 15) measures, each wrong image (level 0
  // alone included) rejected by the reference with at least twice the margin; measured:
  // reference 6.42, 16.03 % of the pixels off by more than 8 levels, mirror 0.00, stored baseline
  // 0.00; bisected surface positions differ at silhouettes
  c.ReferenceBound = 7.4;
  c.ReferenceOffBound = 0.321;
  c.MirrorBound = 0.3;
  c.BaselineBound = 0.3;
  c.WrongImages.push_back(
    { "no shading", [](amrsp::RenderSettings& s) { s.Light.Shade = false; }, nullptr });
  c.WrongImages.push_back({ "the second iso-value left out",
    [](amrsp::RenderSettings& s) { s.IsoValues.resize(1); }, nullptr });
  return amrsp::test::RunBaselineTest(argc, argv, c);
}
