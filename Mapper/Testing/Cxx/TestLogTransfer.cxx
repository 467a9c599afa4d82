// SPDX-License-Identifier: BSD-3-Clause
// Log-scaled colour and opacity functions (vtkColorTransferFunction::SetScaleToLog10,
// vtkPiecewiseFunction::UseLogScale) in both GPU mappers: the table is indexed by log10 of the
// scalar. Checked against the CPU integrators (which evaluate the log interpolation exactly),
// against a linear map whose points sit at log-spaced positions, with empty-space skipping, and
// for a range that is not positive (drawn linearly, with a warning).
#include "AmrspRenderOptions.h"
#include "AmrspDataset.h"
#include "AmrspMultipass.h"
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"

#include "amrsp/EmptySpace.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkMultiPassAMRVolumeMapper.h"
#include "vtkNew.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include <cmath>
#include <iostream>
#include <string>

using namespace amrsp;
using namespace amrsp::harness;
using mappertest::Check;
using mappertest::Coverage;
using mappertest::Failures;
using mappertest::Fixed;

namespace
{

/// Colours and opacities over eight decades of density, log-scaled.
TransferFunction LogFunction()
{
  TransferFunction tf;
  tf.Color = { { 1.0, { 0.2, 0.3, 0.9 } }, { 1e3, { 0.9, 0.9, 0.9 } }, { 1e6, { 0.9, 0.1, 0.1 } } };
  tf.Opacity = { { 1.0, 0.0 }, { 1e2, 0.3 }, { 1e5, 0.9 } };
  tf.ColorLogScale = true;
  tf.OpacityLogScale = true;
  return tf;
}

/// The same mapping as a linear map: 161 points at log-spaced positions over [1, 1e8].
TransferFunction LogSpacedLinearFunction(const TransferFunction& log)
{
  TransferFunction tf;
  for (int k = 0; k <= 160; ++k)
  {
    const double x = std::pow(10.0, k / 20.0);
    tf.Color.push_back({ x, log.EvaluateColor(x) });
    tf.Opacity.push_back({ x, log.EvaluateOpacity(x) });
  }
  return tf;
}

void TestLogTransfer()
{
  Hierarchy h = mappertest::LoadHierarchy("synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3");
  // the densities themselves (positive, about ten decades), not their log10
  RenderSettings s = mappertest::Settings(h, { "--size", "96x96", "--scale", "linear" });
  s.Transfer = LogFunction();
  s.Transfer.UnitDistance = 0.02 * (h.WorldHi(h.RootCells(), 0) - h.Origin).x;
  RenderSettings linear = s;
  linear.Transfer.ColorLogScale = linear.Transfer.OpacityLogScale = false;
  RenderSettings spaced = s;
  spaced.Transfer = LogSpacedLinearFunction(s.Transfer);
  spaced.Transfer.UnitDistance = s.Transfer.UnitDistance;

  const EncodedKdTree enc = EncodeKdTree(h, BuildKdTree(h));
  const Image kd = RenderKdTree(h, enc, s);
  const Image ref = RenderReference(h, s);
  const Image spacedRef = RenderReference(h, spaced);
  double ms = 0.0;
  SinglePassRenderer packing(h, s, ViewAngles(), "packing");
  const Image gpu = packing.Render(0.0, ms);
  SinglePassRenderer packingLinear(h, linear, ViewAngles(), "packing");
  const Image gpuLinear = packingLinear.Render(0.0, ms);
  MultipassRenderer multipass(h, s, ViewAngles());
  const Image multi = multipass.Render(0.0, ms);

  Check(Coverage(ref) > 0.05,
    "the CPU reference with the log map shows the data (coverage " + Fixed(Coverage(ref)) + ")");
  Check(
    Rmse(gpu, kd) < 1.0, "packing vs CPU kD-tree, log map: RMSE " + Fixed(Rmse(gpu, kd)) + " < 1");
  Check(Rmse(multi, kd) < 1.0,
    "multipass vs CPU kD-tree, log map: RMSE " + Fixed(Rmse(multi, kd)) + " < 1");
  // the CPU kD-tree integrator samples each segment at its level's rate as the shaders do; the
  // reference samples at the finest cell everywhere: the GPU is as close to it as the CPU
  // kD-tree integrator is
  const double kdVsRef = Rmse(kd, ref), gpuVsRef = Rmse(gpu, ref);
  Check(gpuVsRef < kdVsRef + 0.25 && gpuVsRef < 3.0,
    "packing vs CPU reference, log map: RMSE " + Fixed(gpuVsRef) + " (CPU kD-tree vs reference " +
      Fixed(kdVsRef) + ")");
  Check(Rmse(spacedRef, ref) < 0.5,
    "CPU reference: the log map vs a linear map with points at log-spaced positions: RMSE " +
      Fixed(Rmse(spacedRef, ref)) + " < 0.5");
  Check(Rmse(gpu, spacedRef) < kdVsRef + 0.25,
    "packing with the log map vs the CPU reference of the log-spaced linear map: RMSE " +
      Fixed(Rmse(gpu, spacedRef)));
  // the checks above would pass for a mapper (or an integrator) that ignored the log scale only
  // if the two maps drew alike: they do not
  Check(Rmse(gpu, gpuLinear) > 5.0,
    "the same points on a linear scale draw another image on the GPU (RMSE " +
      Fixed(Rmse(gpu, gpuLinear)) + " > 5)");
  const Image kdLinear = RenderKdTree(h, enc, linear);
  Check(Rmse(kd, kdLinear) > 5.0, "and on the CPU (RMSE " + Fixed(Rmse(kd, kdLinear)) + " > 5)");

  // empty-space skipping maps the data nodes' ranges through the same log10: with no opacity
  // below 30 many nodes are skipped, and the image is exact
  RenderSettings sparse = s;
  sparse.Transfer.Opacity = { { 1.0, 0.0 }, { 30.0, 0.0 }, { 1e3, 0.9 } };
  SinglePassRenderer sparseGpu(h, sparse, ViewAngles(), "packing");
  sparseGpu.GetMapper()->SetEmptySpaceSkipping(true);
  const Image skipped = sparseGpu.Render(0.0, ms);
  const long long flagged = sparseGpu.GetMapper()->GetNumberOfTransparentDataNodes();
  sparseGpu.GetMapper()->SetEmptySpaceSkipping(false);
  const Image full = sparseGpu.Render(0.0, ms);
  // the data nodes whose whole value range is transparent under the exact log map (the GPU's
  // table flags the same ones, less at most those within one table entry of an opaque value)
  const std::vector<glm::vec2> ranges = ComputeDataNodeRanges(h, enc);
  long long expected = 0;
  for (std::size_t k = 1; k < ranges.size(); ++k)
  {
    expected += TransparentRange(sparse.Transfer, ranges[k].x, ranges[k].y) ? 1 : 0;
  }
  Check(flagged >= expected * 9 / 10 && flagged <= expected,
    "the GPU flags " + std::to_string(flagged) + " data nodes transparent, the exact log map " +
      std::to_string(expected));
  Check(flagged > 0 && Rmse(skipped, full) == 0.0 && Coverage(full) > 0.01,
    "empty-space skipping with a log map: " + std::to_string(flagged) +
      " transparent data nodes skipped, image unchanged (RMSE " + Fixed(Rmse(skipped, full)) + ")");

  // a log map whose range reaches 0 cannot be indexed by log10: drawn as the same map on a linear
  // scale, and the mapper says so once
  RenderSettings zero = s;
  zero.Transfer.Color.front().X = 0.0;
  zero.Transfer.Opacity.front().X = 0.0;
  RenderSettings zeroLinear = zero;
  zeroLinear.Transfer.ColorLogScale = zeroLinear.Transfer.OpacityLogScale = false;
  SinglePassRenderer zeroGpu(h, zero, ViewAngles(), "packing");
  SinglePassRenderer zeroLinearGpu(h, zeroLinear, ViewAngles(), "packing");
  std::string warnings;
  vtkNew<vtkCallbackCommand> collect;
  collect->SetClientData(&warnings);
  collect->SetCallback([](vtkObject*, unsigned long, void* client, void* call)
    { *static_cast<std::string*>(client) += static_cast<const char*>(call); });
  zeroGpu.GetMapper()->AddObserver(vtkCommand::WarningEvent, collect);
  const Image zeroImage = zeroGpu.Render(0.0, ms);
  zeroGpu.Render(0.0, ms);
  const Image zeroLinearImage = zeroLinearGpu.Render(0.0, ms);
  const std::size_t said = warnings.find("which is not positive");
  Check(said != std::string::npos &&
      warnings.find("which is not positive", said + 1) == std::string::npos,
    "a log map over [0, 1e6] warns once: '" + warnings + "'");
  Check(Rmse(zeroImage, zeroLinearImage) == 0.0 && Coverage(zeroImage) > 0.01,
    "and is drawn as the same map on a linear scale (RMSE " +
      Fixed(Rmse(zeroImage, zeroLinearImage)) + ", coverage " + Fixed(Coverage(zeroImage)) + ")");
}

} // namespace

int main()
{
  return mappertest::RunChecks(TestLogTransfer);
}
