// SPDX-License-Identifier: BSD-3-Clause
#include "SinglePassAMRBaselineTest.h"

#include "AmrspRenderOptions.h"
#include "AmrspDataset.h"
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"
#include "RendererChecks.h"

#include "amrsp/ImageDifference.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"
#include "amrsp/WorkCounters.h"

#include "vtkActor.h"
#include "vtkImageData.h"
#include "vtkPNGReader.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkTesting.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

namespace amrsp
{
namespace test
{

namespace
{
/// The square's corner and its two unit edge directions.
void Frame(const BaselineCase::Square& q, glm::dvec3& corner, glm::dvec3& right, glm::dvec3& up)
{
  const glm::dvec3 n = glm::normalize(q.Normal);
  up = glm::normalize(q.Up - glm::dot(q.Up, n) * n);
  right = glm::cross(up, n);
  corner = q.Centre - q.Half * right - q.Half * up;
}

void AddSquare(vtkRenderer* renderer, const BaselineCase::Square& q)
{
  renderer->AddActor(mappertest::OpaqueSquare(q.Centre, q.Normal, q.Up, q.Half, q.Grey));
}

/// Nearest hit of a world ray with the squares, for the CPU images.
bool HitSquares(const std::vector<BaselineCase::Square>& squares, const glm::dvec3& origin,
  const glm::dvec3& direction, double& distance, glm::dvec3& colour)
{
  bool any = false;
  for (const BaselineCase::Square& q : squares)
  {
    glm::dvec3 o, r, u;
    Frame(q, o, r, u);
    const glm::dvec3 n = glm::normalize(q.Normal);
    const double denominator = glm::dot(direction, n);
    if (denominator == 0.0)
    {
      continue;
    }
    const double t = glm::dot(q.Centre - origin, n) / denominator;
    const glm::dvec3 local = origin + t * direction - q.Centre;
    if (t > 0.0 && std::abs(glm::dot(local, r)) <= q.Half &&
      std::abs(glm::dot(local, u)) <= q.Half && (!any || t < distance))
    {
      any = true;
      distance = t;
      colour = glm::dvec3(q.Grey);
    }
  }
  return any;
}
} // namespace

namespace
{
/// The shader's work counts summed over a frame rendered with AccelerationCountsOutput (exact 8-bit
/// channels: red skipped segments, green 255 per terminated ray, blue data segments).
struct AccelerationCounts
{
  long long Skipped = 0;
  long long Terminated = 0;
  long long DataSegments = 0;
};

AccelerationCounts RenderAccelerationCounts(harness::SinglePassRenderer& gpu)
{
  vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
  mapper->AccelerationCountsOutputOn();
  double ms = 0.0;
  const Image counts = gpu.RenderAsIs(ms);
  mapper->AccelerationCountsOutputOff();
  AccelerationCounts w;
  for (const glm::vec4& p : counts.Pixels)
  {
    w.Skipped += std::lround(p.r * 255.0f);
    w.Terminated += p.g > 0.5f ? 1 : 0;
    w.DataSegments += std::lround(p.b * 255.0f);
  }
  return w;
}

bool Agree(long long gpu, long long cpu)
{
  return std::llabs(gpu - cpu) <= 2 + cpu / 100;
}

/// The shader's own counts of its loops (LoopCountOutput) against the cost model's CPU mirror
/// of the same frame (amrsp::MeasureSinglePassWork), and that the comparison rejects the counts
/// of another sampling distance.
bool CompareLoopCounts(harness::SinglePassRenderer& gpu, const Hierarchy& h,
  const RenderSettings& mirrorSettings, std::ostream& log)
{
  using M = vtkSinglePassAMRVolumeMapper;
  RenderSettings s = mirrorSettings;
  s.Stats = nullptr;
  const EncodedKdTree tree = EncodeKdTree(h, BuildKdTree(h));
  const WorkSummary w = MeasureSinglePassWork(h, tree, s, FetchModel());
  const auto total = [&w](const WorkDistribution& d) { return std::llround(d.Mean * w.Rays); };
  bool ok = true;
  const auto compare = [&](int count, const char* what, long long mirror)
  {
    const long long shader = gpu.RenderWorkCount(count);
    const bool pass = Agree(shader, mirror);
    log << (pass ? "ok" : "FAILED") << ": the shader counts " << shader << " " << what
        << ", the CPU mirror " << mirror << "\n";
    ok = ok && pass;
    return shader;
  };
  compare(M::SEGMENT_COUNT, "segment-loop iterations", total(w.Segments));
  compare(M::DESCENT_STEP_COUNT, "descent steps", total(w.DescentSteps));
  const long long samples = compare(M::SAMPLE_COUNT, "samples", total(w.Samples));
  // AUTO_LOOP takes the nested loops on every driver (they measured faster on a GPU too)
  vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
  mapper->SetRayLoop(M::AUTO_LOOP);
  double ms = 0.0;
  gpu.RenderAsIs(ms);
  const bool autoLoop = mapper->GetLastRayLoop() == M::NESTED_LOOPS;
  log << (autoLoop ? "ok" : "FAILED") << ": the automatic loop is the "
      << (mapper->GetLastRayLoop() == M::FLAT_LOOP ? "flat loop" : "nested loops") << "\n";
  ok = ok && autoLoop;
  // without ropes: the same image, and the mirror's longer descents (the nested loops)
  mapper->SetRayLoop(M::NESTED_LOOPS);
  const Image roped = gpu.RenderAsIs(ms);
  mapper->RopesOff();
  const Image unroped = gpu.RenderAsIs(ms);
  s.Ropes = false;
  const WorkSummary pushDown = MeasureSinglePassWork(h, tree, s, FetchModel());
  const long long ropedDescent = total(w.DescentSteps);
  const long long descent =
    compare(M::DESCENT_STEP_COUNT, "descent steps without ropes", total(pushDown.DescentSteps));
  mapper->RopesOn();
  const bool same = Rmse(roped, unroped) == 0.0;
  log << (same ? "ok" : "FAILED") << ": ropes off renders the same image (RMSE "
      << Rmse(roped, unroped) << ")\n";
  const bool rejectedDescent = !Agree(descent, ropedDescent);
  log << (rejectedDescent ? "ok" : "FAILED") << ": the descent count with ropes (" << ropedDescent
      << ") is rejected for the frame without\n";
  // the flat loop: the same image and the same loop counts as the nested loops
  mapper->SetRayLoop(M::FLAT_LOOP);
  const Image flat = gpu.RenderAsIs(ms);
  const bool flatUsed = mapper->GetLastRayLoop() == M::FLAT_LOOP;
  log << (flatUsed ? "ok" : "FAILED") << ": FLAT_LOOP renders with the flat loop\n";
  ok = ok && flatUsed;
  const bool flatSame = Rmse(roped, flat) == 0.0;
  log << (flatSame ? "ok" : "FAILED") << ": the flat loop renders the same image (RMSE "
      << Rmse(roped, flat) << ")\n";
  compare(M::SEGMENT_COUNT, "segment-loop iterations in the flat loop", total(w.Segments));
  compare(M::DESCENT_STEP_COUNT, "descent steps in the flat loop", ropedDescent);
  compare(M::SAMPLE_COUNT, "samples in the flat loop", total(w.Samples));
  mapper->SetRayLoop(M::NESTED_LOOPS);
  s.Ropes = true;
  s.SampleDistanceFactor *= 2.0;
  const WorkSummary coarse = MeasureSinglePassWork(h, tree, s, FetchModel());
  const long long wrong = std::llround(coarse.Samples.Mean * coarse.Rays);
  const bool rejected = !Agree(samples, wrong);
  log << (rejected ? "ok" : "FAILED") << ": the mirror's samples at twice the sampling distance ("
      << wrong << ") are rejected\n";
  return ok && rejected && same && rejectedDescent && flatSame;
}

bool CompareWorkCounters(harness::SinglePassRenderer& gpu, const RenderStats& cpu,
  const Hierarchy& h, const RenderSettings& mirrorSettings, const BaselineCase& c,
  std::ostream& log)
{
  vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
  const AccelerationCounts w = RenderAccelerationCounts(gpu);
  bool ok = true;
  auto report = [&](bool pass, const std::string& what)
  {
    log << (pass ? "ok" : "FAILED") << ": " << what << "\n";
    ok = ok && pass;
  };
  report(Agree(w.DataSegments, cpu.DataSegments),
    "shader counts " + std::to_string(w.DataSegments) + " data segments, the CPU mirror " +
      std::to_string(cpu.DataSegments));
  report(Agree(w.Skipped, cpu.SkippedSegments),
    "shader skips " + std::to_string(w.Skipped) + " segments as empty space, the CPU mirror " +
      std::to_string(cpu.SkippedSegments));
  report(Agree(w.Terminated, cpu.TerminatedRays),
    "shader stops " + std::to_string(w.Terminated) + " rays early, the CPU mirror " +
      std::to_string(cpu.TerminatedRays));
  if (c.ExpectSkipped)
  {
    report(w.Skipped > 0, "the shader skips segments (" + std::to_string(w.Skipped) + ")");
    mapper->EmptySpaceSkippingOff();
    const AccelerationCounts off = RenderAccelerationCounts(gpu);
    mapper->EmptySpaceSkippingOn();
    report(off.Skipped == 0 && off.DataSegments == w.DataSegments,
      "with skipping off the shader skips " + std::to_string(off.Skipped) +
        " segments and reaches " + std::to_string(off.DataSegments));
  }
  if (c.ExpectTerminated)
  {
    report(w.Terminated > 0, "the shader stops rays early (" + std::to_string(w.Terminated) + ")");
    const double threshold = mapper->GetOpacityThreshold();
    mapper->SetOpacityThreshold(1.0);
    const AccelerationCounts off = RenderAccelerationCounts(gpu);
    mapper->SetOpacityThreshold(threshold);
    report(off.Terminated == 0 && off.DataSegments >= w.DataSegments,
      "with threshold 1 the shader stops " + std::to_string(off.Terminated) +
        " rays early and reaches " + std::to_string(off.DataSegments) + " data segments");
  }
  ok = CompareLoopCounts(gpu, h, mirrorSettings, log) && ok;
  // one ordinary frame, so that the mapper's per-frame state (e.g. its transparent data nodes)
  // is that of the test's own settings again
  double ms = 0.0;
  gpu.RenderAsIs(ms);
  return ok;
}
} // namespace

namespace
{
bool Report(
  std::ostream& log, const std::string& what, const ImageDifference& d, const BaselineCase& c)
{
  const bool ok = d.Rmse <= c.ReferenceBound && d.OffShare <= c.ReferenceOffBound;
  log << (ok ? "ok" : "FAILED") << ": " << what << ": " << d.Describe() << " (bounds "
      << c.ReferenceBound << " and " << 100.0 * c.ReferenceOffBound << " %)\n";
  return ok;
}

/// The grids of levels 0..last (a hierarchy of last + 1 levels).
Hierarchy UpToLevel(const Hierarchy& h, int last)
{
  Hierarchy out = h;
  out.Grids.clear();
  out.Values.clear();
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    if (h.Grids[g].Level <= last)
    {
      out.Grids.push_back(h.Grids[g]);
      if (!h.Values.empty())
      {
        out.Values.push_back(h.Values[g]);
      }
    }
  }
  out.RefinementRatio.resize(static_cast<std::size_t>(last) + 1);
  return out;
}

/// A GPU image with a defect renders as the CPU kD-tree integrator (the shader's mirror) renders
/// the scene with that defect: each such wrong image must fail the test's bounds against the
/// reference or against the mirror of the right scene.
/// Whether `wrong` is rejected by a bound with a clear margin: above the bound by at least
/// twice what separates the bound from what the right image measures (`measured`).
bool ClearlyAbove(double wrong, double bound, double measured)
{
  return wrong > bound && wrong - bound >= 2.0 * (bound - measured);
}

/// Every wrong image (BaselineCase::WrongImages, and level 0 alone) must be rejected with a clear
/// margin (ClearlyAbove) by the reference's RMSE or off share, or by the mirror's RMSE, given what
/// the GPU image measures against each (`gpuToReference`, `gpuToMirror`).
bool RejectsWrongImages(const Hierarchy& h, const RenderSettings& settings, const Image& reference,
  const Image& mirror, const ImageDifference& gpuToReference, double gpuToMirror,
  const BaselineCase& c, std::ostream& log)
{
  std::vector<BaselineCase::WrongImage> wrong = c.WrongImages;
  const int levels = h.NumberOfLevels();
  if (levels > 1)
  {
    wrong.push_back({ "level 0 alone (a renderer resampling to the coarse grid)", nullptr,
      [](const Hierarchy& x) { return UpToLevel(x, 0); } });
  }
  bool ok = true;
  for (const BaselineCase::WrongImage& w : wrong)
  {
    RenderSettings s = settings;
    if (w.Settings)
    {
      w.Settings(s);
    }
    const Hierarchy data = w.Data ? w.Data(h) : h;
    const Image image = RenderKdTree(data, EncodeKdTree(data, BuildKdTree(data)), s);
    const ImageDifference toReference = Compare(image, reference);
    const ImageDifference toMirror = Compare(image, mirror);
    const bool byRmse = ClearlyAbove(toReference.Rmse, c.ReferenceBound, gpuToReference.Rmse);
    const bool byOff =
      ClearlyAbove(toReference.OffShare, c.ReferenceOffBound, gpuToReference.OffShare);
    const bool byMirror = ClearlyAbove(toMirror.Rmse, c.MirrorBound, gpuToMirror);
    const bool rejected = byRmse || byOff || (w.ReferenceBlind && byMirror);
    log << (rejected ? "ok" : "FAILED") << ": the bounds reject the image with " << w.What
        << ": against the reference " << toReference.Describe() << "; against the mirror RMSE "
        << toMirror.Rmse << " (by at least twice the margin: " << (byRmse ? "reference RMSE " : "")
        << (byOff ? "reference off share " : "") << (byMirror ? "mirror RMSE" : "")
        << (rejected ? "" : "none") << ")\n";
    ok = ok && rejected;
  }
  return ok;
}

/// 8-bit RGB rows bottom to top, as Image::Rgb8; empty when the file cannot be read.
std::vector<std::uint8_t> ReadPng(const std::string& path, int width, int height)
{
  vtkNew<vtkPNGReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    return {};
  }
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkImageData* png = reader->GetOutput();
  int dims[3];
  png->GetDimensions(dims);
  vtkUnsignedCharArray* pixels =
    vtkUnsignedCharArray::SafeDownCast(png->GetPointData()->GetScalars());
  if (!pixels || dims[0] != width || dims[1] != height || pixels->GetNumberOfComponents() < 3)
  {
    return {};
  }
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  const int n = pixels->GetNumberOfComponents();
  for (std::size_t i = 0; i < rgb.size() / 3; ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      rgb[3 * i + k] = pixels->GetValue(static_cast<vtkIdType>(i) * n + k);
    }
  }
  return rgb;
}

/// The stored baseline against the CPU reference (it must be a right image) and against the
/// GPU image, with covered-pixel RMSE bounds; vtkRegressionTestImage compares them too.
bool CompareWithStoredBaseline(int argc, char* argv[], const Image& image, const Image& reference,
  const BaselineCase& c, std::ostream& log)
{
  vtkNew<vtkTesting> testing;
  for (int i = 0; i < argc; ++i)
  {
    testing->AddArgument(argv[i]);
  }
  const char* valid = testing->GetValidImageFileName();
  const std::string path = valid ? valid : "";
  // AMRSP_WRITE_BASELINE_DIR: this run's image is written there under the baseline's name, for
  // replacing a baseline after a deliberate change (docs/testing.md, "Baselines")
  if (const char* dir = std::getenv("AMRSP_WRITE_BASELINE_DIR"))
  {
    const std::string name = path.substr(path.find_last_of('/') + 1);
    const std::vector<std::uint8_t> rgb = image.Rgb8();
    vtkNew<vtkImageData> data;
    data->SetDimensions(image.Width, image.Height, 1);
    data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    std::copy(rgb.begin(), rgb.end(), static_cast<std::uint8_t*>(data->GetScalarPointer()));
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName((std::string(dir) + "/" + name).c_str());
    writer->SetInputData(data);
    writer->Write();
    log << "wrote " << dir << "/" << name << "\n";
  }
  const std::vector<std::uint8_t> baseline = ReadPng(path, image.Width, image.Height);
  if (baseline.empty())
  {
    log << "FAILED: no readable " << image.Width << "x" << image.Height << " baseline image '"
        << path << "'\n";
    return false;
  }
  bool ok =
    Report(log, "stored baseline vs CPU reference", CompareRgb8(baseline, reference.Rgb8()), c);
  const ImageDifference d = CompareRgb8(image.Rgb8(), baseline);
  const bool same = d.Rmse <= c.BaselineBound;
  log << (same ? "ok" : "FAILED") << ": GPU image vs stored baseline: " << d.Describe()
      << " (RMSE bound " << c.BaselineBound << ")\n";
  return ok && same;
}
} // namespace

int RunBaselineTest(int argc, char* argv[], const BaselineCase& c)
{
  using namespace amrsp::harness;
  std::string why;
  if (!SinglePassRenderer::Available(why))
  {
    return mappertest::SkipOrFail(why);
  }
  std::string spec = c.Dataset;
  if (!c.Data && spec.rfind("data:", 0) == 0)
  {
    spec = std::string(AMRSP_DATA_DIR) + "/" + spec.substr(5);
    if (std::FILE* f = std::fopen(spec.c_str(), "r"))
    {
      std::fclose(f);
    }
    else
    {
      return mappertest::SkipOrFail(spec + " not found (set AMRSP_DATA_DIR)");
    }
  }

  try
  {
    DatasetRequest request;
    request.Spec = spec;
    request.Array = c.Array;
    request.Centering = c.Centering;
    request.NeedVTK = false;
    LoadedDataset d;
    if (c.Data)
    {
      d.Data = c.Data();
    }
    else
    {
      d = LoadDataset(request);
    }
    RenderSettings s = MakeSettings(d.Data, c.Request);
    if (c.Settings)
    {
      c.Settings(s);
    }
    ViewAngles view;
    view.Azimuth = c.Request.Azimuth.value_or(30.0);
    view.Elevation = c.Request.Elevation.value_or(20.0);
    view.Zoom = c.Request.Zoom.value_or(1.0);

    SinglePassRenderer gpu(d.Data, s, view);
    for (const BaselineCase::Square& q : c.Squares)
    {
      AddSquare(gpu.GetRenderer(), q);
    }
    if (!c.Squares.empty())
    {
      s.Opaque = [&c](const glm::dvec3& o, const glm::dvec3& dir, double& t, glm::dvec3& colour)
      { return HitSquares(c.Squares, o, dir, t, colour); };
    }
    double ms = 0.0;
    gpu.Render(0.0, ms);
    if (c.Adjust)
    {
      c.Adjust(gpu.GetRenderer());
      gpu.GetRenderer()->ResetCameraClippingRange();
    }
    const Image image = gpu.RenderAsIs(ms);

    // the independent check: the CPU reference of the very same view (no kD-tree), and the CPU
    // mirror of the shader (same segments, same level of detail)
    RenderSettings ref = s;
    ref.View = gpu.LastCamera();
    const Image reference = RenderReference(d.Data, ref);
    RenderStats mirrorStats;
    RenderSettings mirrorSettings = ref;
    mirrorSettings.Stats = &mirrorStats;
    const Image mirrorImage =
      RenderKdTree(d.Data, EncodeKdTree(d.Data, BuildKdTree(d.Data)), mirrorSettings);
    const ImageDifference mirror = Compare(image, mirrorImage);
    bool agrees = Report(std::cout, "GPU image vs CPU reference", Compare(image, reference), c);
    const bool mirrorAgrees = mirror.Rmse <= c.MirrorBound;
    std::cout << (mirrorAgrees ? "ok" : "FAILED")
              << ": GPU image vs CPU kD-tree integrator: " << mirror.Describe() << " (RMSE bound "
              << c.MirrorBound << ")\n";
    agrees = mirrorAgrees && agrees;
    agrees = RejectsWrongImages(d.Data, ref, reference, mirrorImage, Compare(image, reference),
               mirror.Rmse, c, std::cout) &&
      agrees;
    agrees = CompareWithStoredBaseline(argc, argv, image, reference, c, std::cout) && agrees;

    // the image above is the default loop's (nested): the flat loop must render the same image
    // (to a level of rounding)
    {
      const bool flatUsed =
        gpu.GetMapper()->GetLastRayLoop() == vtkSinglePassAMRVolumeMapper::FLAT_LOOP;
      const mappertest::RayLoopComparison loops = mappertest::CompareOtherRayLoop(gpu, image);
      std::cout << (loops.Same() ? "ok" : "FAILED") << ": the "
                << (flatUsed ? "nested loops render" : "flat loop renders")
                << " the same image as the " << (flatUsed ? "flat loop" : "nested loops") << ": "
                << loops.Describe() << "\n";
      agrees = loops.Same() && agrees;
      // and on its own against the CPU reference, under the test's bounds (not only through the
      // default loop's image)
      agrees =
        Report(std::cout,
          std::string(flatUsed ? "nested loops'" : "flat loop's") + " image vs CPU reference",
          Compare(loops.Other, reference), c) &&
        agrees;
      // the other caster (compute on a CPU driver, where AUTO_CASTER takes the fragment shader)
      const mappertest::RayCasterComparison casters =
        mappertest::CompareOtherRayCaster(gpu, image, &mirrorImage);
      std::cout << (casters.Same() ? "ok" : "FAILED") << ": the " << casters.Describe()
                << " renders the same image\n";
      agrees = casters.Same() && agrees;
      gpu.RenderAsIs(ms); // the window holds the default loop's and caster's frame again
    }

    if (c.CheckWorkCounters)
    {
      agrees =
        CompareWorkCounters(gpu, mirrorStats, d.Data, mirrorSettings, c, std::cout) && agrees;
    }
    if (c.Check)
    {
      agrees = c.Check(gpu, image, ref, std::cout) && agrees;
      const double again = Rmse(image, gpu.RenderAsIs(ms));
      if (again != 0.0)
      {
        std::cout << "FAILED: the checks left the mapper changed (RMSE " << again << ")\n";
        agrees = false;
      }
    }

    vtkRenderWindow* window = gpu.GetRenderer()->GetRenderWindow();
    // vtkImageDifference ignores per-pixel differences below its own threshold and averages
    // the rest; 0.15 is under one badly wrong pixel (a wrong transfer function scores > 1)
    const int baseline = vtkRegressionTestImageThreshold(window, 0.15);
    return (agrees && baseline == vtkTesting::PASSED) ? 0 : 1;
  }
  catch (const std::exception& e)
  {
    std::cout << "FAILED: " << e.what() << "\n";
    return 1;
  }
}

} // namespace test
} // namespace amrsp
