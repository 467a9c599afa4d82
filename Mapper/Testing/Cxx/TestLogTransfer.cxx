// SPDX-License-Identifier: BSD-3-Clause
// Log-scaled colour and opacity functions (vtkColorTransferFunction::SetScaleToLog10,
// vtkPiecewiseFunction::UseLogScale) in both GPU mappers: the table is indexed by log10 of the
// scalar. Checked over the covered pixels against the CPU integrators (which evaluate the log
// interpolation exactly), against a linear map whose points sit at log-spaced positions, with
// empty-space skipping, for data at or below 0 (the first point: the same image as the data's
// own values below the first point; the shader taking them as the last point is rejected), and
// for a range that is not positive (drawn linearly, with a warning). The log scale ignored
// fails the bounds against both CPU integrators.
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
using mappertest::CoveredRmse;
using mappertest::Failures;
using mappertest::Fixed;
using mappertest::ShaderProperty;

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
  RenderSettings s = mappertest::Settings(
    h, mappertest::Request(96, 96, [](amrsp::harness::RenderRequest& r) { r.Scale = "linear"; }));
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
  SinglePassRenderer packing(h, s, ViewAngles(), DataStorage::PackedAtlas);
  const Image gpu = packing.Render(0.0, ms);
  SinglePassRenderer packingLinear(h, linear, ViewAngles(), DataStorage::PackedAtlas);
  const Image gpuLinear = packingLinear.Render(0.0, ms);
  MultipassRenderer multipass(h, s, ViewAngles());
  const Image multi = multipass.Render(0.0, ms);

  Check(Coverage(ref) > 0.05,
    "the CPU reference with the log map shows the data (coverage " + Fixed(Coverage(ref)) + ")");
  // over the pixels either image covers (mappertest::CoveredRmse); measured on llvmpipe: packing
  // and multipass vs the mirror 0.00, packing vs the reference 6.35 (the reference samples every
  // level at the finest cells' rate; ten decades of noisy density), the log map vs the log-spaced
  // linear map on the reference 0.18; bounds 1.5x
  const double gpuVsKd = CoveredRmse(gpu, kd), multiVsKd = CoveredRmse(multi, kd);
  Check(gpuVsKd < 0.3, "packing vs CPU kD-tree, log map: RMSE " + Fixed(gpuVsKd) + " < 0.3");
  Check(multiVsKd < 0.3, "multipass vs CPU kD-tree, log map: RMSE " + Fixed(multiVsKd) + " < 0.3");
  const double referenceBound = 9.5;
  const double gpuVsRef = CoveredRmse(gpu, ref);
  Check(gpuVsRef < referenceBound,
    "packing vs CPU reference, log map: RMSE " + Fixed(gpuVsRef) + " < " + Fixed(referenceBound));
  const double spacedVsLog = CoveredRmse(spacedRef, ref);
  Check(spacedVsLog < 0.3,
    "CPU reference: the log map vs a linear map with points at log-spaced positions: RMSE " +
      Fixed(spacedVsLog) + " < 0.3");
  const double gpuVsSpaced = CoveredRmse(gpu, spacedRef);
  Check(gpuVsSpaced < referenceBound,
    "packing with the log map vs the CPU reference of the log-spaced linear map: RMSE " +
      Fixed(gpuVsSpaced) + " < " + Fixed(referenceBound));
  // the wrong rule, the log scale ignored (the same points on a linear scale), fails the bounds
  const double linearVsRef = CoveredRmse(gpuLinear, ref), linearVsKd = CoveredRmse(gpuLinear, kd);
  Check(linearVsRef > 2.0 * referenceBound && linearVsKd > 10.0,
    "the same points on a linear scale (the log scale ignored) are rejected: RMSE " +
      Fixed(linearVsRef) + " against the reference, " + Fixed(linearVsKd) + " against the mirror");
  const Image kdLinear = RenderKdTree(h, enc, linear);
  Check(CoveredRmse(kd, kdLinear) > 10.0,
    "and on the CPU (RMSE " + Fixed(CoveredRmse(kd, kdLinear)) + " > 10)");

  // values at or below 0 take the first point (amrsp/TransferFunction.h; the shader maps them
  // below every log10): with an opaque first point, the data with its values below 1 made 0 or
  // negative must draw exactly the image of the data (they take the first point either way)
  RenderSettings firstOpaque = s;
  firstOpaque.Transfer.Opacity.front().Opacity = 0.2;
  Hierarchy signs = h;
  std::size_t changed = 0;
  for (GridValues& values : signs.Values)
  {
    for (std::size_t k = 0; k < values.size(); ++k)
    {
      const float v = values[k];
      if (v < 1.0f)
      {
        values[k] = k % 3 == 0 ? 0.0f : -v - 1.0f;
        ++changed;
      }
    }
  }
  SinglePassRenderer positiveGpu(h, firstOpaque, ViewAngles(), DataStorage::PackedAtlas);
  SinglePassRenderer signsGpu(signs, firstOpaque, ViewAngles(), DataStorage::PackedAtlas);
  const Image positive = positiveGpu.Render(0.0, ms);
  const Image withSigns = signsGpu.Render(0.0, ms);
  const double signsVsRef = CoveredRmse(withSigns, RenderReference(signs, firstOpaque));
  // measured 0.35 against the reference (the opaque first point hides the sampling differences)
  Check(changed > 1000 && Rmse(withSigns, positive) == 0.0 && signsVsRef < 0.6,
    std::to_string(changed) + " values below 1 made 0 or negative: the same image (RMSE " +
      Fixed(Rmse(withSigns, positive)) + "), " + Fixed(signsVsRef) + " from the reference");
  if (vtkOpenGLShaderProperty* shader = ShaderProperty(signsGpu))
  {
    // the wrong rule: values <= 0 taken as above every point
    shader->AddFragmentShaderReplacement(": -3.0e38;", false, ": 3.0e38;", false);
    const Image wrong = signsGpu.Render(0.0, ms);
    shader->ClearAllFragmentShaderReplacements();
    Check(CoveredRmse(wrong, positive) > 10.0,
      "the shader taking values <= 0 as the last point differs by RMSE " +
        Fixed(CoveredRmse(wrong, positive)) + " (rejected)");
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }

  // empty-space skipping maps the data nodes' ranges through the same log10: with no opacity
  // below 30 many nodes are skipped, and the image is exact
  RenderSettings sparse = s;
  sparse.Transfer.Opacity = { { 1.0, 0.0 }, { 30.0, 0.0 }, { 1e3, 0.9 } };
  SinglePassRenderer sparseGpu(h, sparse, ViewAngles(), DataStorage::PackedAtlas);
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
  SinglePassRenderer zeroGpu(h, zero, ViewAngles(), DataStorage::PackedAtlas);
  SinglePassRenderer zeroLinearGpu(h, zeroLinear, ViewAngles(), DataStorage::PackedAtlas);
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
