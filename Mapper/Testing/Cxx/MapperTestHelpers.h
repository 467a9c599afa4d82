// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Helpers shared by the mapper image tests: a check counter that prints every check, number
/// formatting, image coverage and render settings built from `amrsp render` options.

#include "AmrspDataset.h"
#include "AmrspRenderOptions.h"
#include "AmrspSinglePass.h"

#include "amrsp/ImageDifference.h"
#include "amrsp/Render.h"

#include "vtkOpenGLShaderProperty.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace mappertest
{

/// The GPU mappers' image bounds (RMSE over RGB, 0-255, over the pixels either image covers)
/// against the CPU kD-tree integrator (the shader's mirror) and the tree-free CPU reference, as
/// TestSinglePassAMRMapper measures them (largest: 0.49 and 2.10).
constexpr double BoundVsKdTree = 1.0;
constexpr double BoundVsReference = 2.6;

/// The storage tests' datasets at 96 x 96 (TestLinearStorage, TestBindlessStorage): bounds on the
/// GPU image's covered-pixel RMSE against the CPU reference, fixed from what llvmpipe measures
/// (not from the CPU mirror's own distance, which would let a mirror and shader wrong the same way
/// through).
/// Measured (LLVM 15): one grid 6.83, Enzo moving7 1.21, AMReX plt1_Y 12.82 (its thin sharp
/// species fronts, sampled once per cell against the reference's two), synthetic vertex-centred
/// 0.41, smooth cells 0.38.
constexpr double RefOneGrid = 7.5;
constexpr double RefEnzo = 1.5;
constexpr double RefAmrex = 14.0;
constexpr double RefVertex = 0.6;
constexpr double RefSmooth = 0.55;

/// RMSE (0-255) over the pixels either image covers (amrsp::ImageDifference), the measure of the
/// image tests' bounds against the CPU reference and the CPU kD-tree integrator.
inline double CoveredRmse(const amrsp::Image& a, const amrsp::Image& b)
{
  return amrsp::Compare(a, b).Rmse;
}

/// The shader property of the renderer's volume, where the tests put the replacements that break
/// a rule of the shader (to show that a check rejects the image the broken rule draws).
inline vtkOpenGLShaderProperty* ShaderProperty(amrsp::harness::GpuRenderer& gpu)
{
  vtkVolumeCollection* volumes = gpu.GetRenderer()->GetVolumes();
  volumes->InitTraversal();
  vtkVolume* volume = volumes->GetNextVolume();
  return volume ? vtkOpenGLShaderProperty::SafeDownCast(volume->GetShaderProperty()) : nullptr;
}

/// Whether everything a test needs must be here (AMRSP_REQUIRE_GPU=1, set in CI).
inline bool EverythingRequired()
{
  const char* require = std::getenv("AMRSP_REQUIRE_GPU");
  return require && std::string(require) == "1";
}

/// For a test that cannot run here: prints "SKIPPED: why" and returns CTest's skip code 125. With
/// AMRSP_REQUIRE_GPU=1 (scripts/run-tests.sh sets it in CI, where everything a test needs is
/// installed) the same condition fails the test (returns 1) and names what is missing.
inline int SkipOrFail(const std::string& why)
{
  if (EverythingRequired())
  {
    std::cout << "FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: " << why << "\n";
    return 1;
  }
  std::cout << "SKIPPED: " << why << "\n";
  return 125;
}

/// Failed checks so far (the test's exit code is non-zero when any failed).
inline int& Failures()
{
  static int failures = 0;
  return failures;
}

/// Prints "ok" or "FAILED" with `what` and counts failures.
inline void Check(bool ok, const std::string& what)
{
  std::cout << (ok ? "  ok      " : "  FAILED  ") << what << "\n";
  if (!ok)
  {
    ++Failures();
  }
}

/// `v` with three decimals.
inline std::string Fixed(double v)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.3f", v);
  return buffer;
}

/// Share of the image's pixels the volume covers (amrsp::IsCovered over a black background).
inline double Coverage(const amrsp::Image& img)
{
  return amrsp::CoveredShare(img.Rgb8());
}

/// The settings `amrsp render` would use for `h` (which gets the scale applied) with the options
/// of `r` (harness::MakeSettings, the tool's conventions; no option words are parsed).
inline amrsp::RenderSettings Settings(amrsp::Hierarchy& h, const amrsp::harness::RenderRequest& r)
{
  return amrsp::harness::MakeSettings(h, r);
}

/// A render request of `width` x `height` pixels with the tool's defaults otherwise, which `edit`
/// may change (e.g. [](RenderRequest& r) { r.Scale = "linear"; }).
inline amrsp::harness::RenderRequest Request(
  int width, int height, const std::function<void(amrsp::harness::RenderRequest&)>& edit = nullptr)
{
  amrsp::harness::RenderRequest r;
  r.Width = width;
  r.Height = height;
  if (edit)
  {
    edit(r);
  }
  return r;
}

/// The hierarchy of a dataset spec (`amrsp render`'s DATASET), without the VTK objects;
/// `centering` as --centering.
inline amrsp::Hierarchy LoadHierarchy(
  const std::string& spec, const std::string& centering = "auto")
{
  amrsp::harness::DatasetRequest request;
  request.Spec = spec;
  request.NeedVTK = false;
  request.Centering = centering;
  return amrsp::harness::LoadDataset(request).Data;
}

/// The Enzo moving7 hierarchy file of ../shared/data (AMRSP_DATA_DIR).
inline std::string EnzoPath()
{
  return std::string(AMRSP_DATA_DIR) + "/enzo_moving7/DD0010/moving7_0010.hierarchy";
}

/// Calls `test(path)` with the Enzo file when it is there. Without it the Enzo half is left out
/// and said by hand, and is a failed check in CI (AMRSP_REQUIRE_GPU=1), where it must run.
template <class Test>
void WithEnzo(Test test)
{
  const std::string enzo = EnzoPath();
  if (std::FILE* f = std::fopen(enzo.c_str(), "r"))
  {
    std::fclose(f);
    test(enzo);
    return;
  }
  const bool required = EverythingRequired();
  Check(!required,
    "the Enzo dataset " + enzo + " is " +
      (required ? "missing (required here: AMRSP_REQUIRE_GPU=1)" : "missing: left out"));
}

/// Whether `window` renders on a CPU driver (Mesa's llvmpipe, softpipe, or zink on lavapipe),
/// read from its capabilities here, apart from the mapper's own test (AUTO_STORAGE, AUTO_LOOP).
inline bool IsCpuDriver(vtkRenderWindow* window)
{
  const std::string caps = window->ReportCapabilities();
  return caps.find("llvmpipe") != std::string::npos || caps.find("softpipe") != std::string::npos ||
    caps.find("lavapipe") != std::string::npos;
}

/// Two frames of one scene, 8-bit channel by channel.
struct FrameComparison
{
  double Rmse = 0.0;
  int LargestDifference = 0;     ///< of one 8-bit channel
  long long DifferentPixels = 0; ///< pixels with any channel different
  long long OffPixels = 0;       ///< pixels with a channel more than one level apart
  long long CoveredPixels = 0;   ///< pixels with a channel above 4 in either image
  std::string Describe() const
  {
    return "RMSE " + Fixed(this->Rmse) + ", " + std::to_string(this->DifferentPixels) +
      " pixels different, " + std::to_string(this->OffPixels) + " of " +
      std::to_string(this->CoveredPixels) +
      " covered pixels more than one level apart, largest channel difference " +
      std::to_string(this->LargestDifference);
  }
};

/// `a` against `b` (FrameComparison); a size mismatch is a difference of 256.
inline FrameComparison CompareFrames(const amrsp::Image& a, const amrsp::Image& b)
{
  FrameComparison c;
  c.Rmse = amrsp::Rmse(a, b);
  const std::vector<std::uint8_t> x = a.Rgb8(), y = b.Rgb8();
  if (x.size() != y.size())
  {
    c.LargestDifference = 256;
    return c;
  }
  for (std::size_t i = 0; i + 2 < x.size(); i += 3)
  {
    int largest = 0;
    const bool covered = amrsp::IsCovered(&x[i]) || amrsp::IsCovered(&y[i]);
    for (std::size_t k = i; k < i + 3; ++k)
    {
      largest = std::max(largest, std::abs(static_cast<int>(x[k]) - static_cast<int>(y[k])));
    }
    c.LargestDifference = std::max(c.LargestDifference, largest);
    c.DifferentPixels += largest > 0 ? 1 : 0;
    c.OffPixels += largest > 1 ? 1 : 0;
    c.CoveredPixels += covered ? 1 : 0;
  }
  return c;
}

/// The other ray loop's frame against the mapper's own. The two loops run the same steps in
/// another order, and the shader compiler may round their arithmetic differently: where a
/// rounding moves a sample or a segment boundary, a pixel changes. Measured: the same bytes with
/// Mesa 25 (LLVM 15) in every test; with Mesa 26 (LLVM 21), smooth cells, 3 of 9,216 pixels (2 by
/// more than one level, the largest 11), where the flat loop's pixel is the CPU mirror's and the
/// nested loops' is not. A step missing from one loop changes whole segments, i.e. most pixels.
struct RayLoopComparison : FrameComparison
{
  /// The other loop's frame (checked against the CPU reference on its own by the baseline tests).
  amrsp::Image Other;
  /// At most 0.1 % of the covered pixels (at least one) more than one level apart.
  bool Same() const
  {
    return this->CoveredPixels > 0 &&
      this->OffPixels <= std::max<long long>(1, this->CoveredPixels / 1000);
  }
};

/// Renders the frame `gpu` rendered last (`image`) again with the other loop than the one it ran
/// and compares; the mapper's RayLoop setting is restored.
inline RayLoopComparison CompareOtherRayLoop(
  amrsp::harness::SinglePassRenderer& gpu, const amrsp::Image& image)
{
  using Mapper = vtkSinglePassAMRVolumeMapper;
  Mapper* m = gpu.GetMapper();
  const int setting = m->GetRayLoop();
  m->SetRayLoop(
    m->GetLastRayLoop() == Mapper::FLAT_LOOP ? Mapper::NESTED_LOOPS : Mapper::FLAT_LOOP);
  double ms = 0.0;
  const amrsp::Image other = gpu.RenderAsIs(ms);
  m->SetRayLoop(setting);
  RayLoopComparison c;
  static_cast<FrameComparison&>(c) = CompareFrames(other, image);
  c.Other = other;
  return c;
}

/// The other caster's frame against the mapper's own (vtkSinglePassAMRVolumeMapper::RayCaster).
/// Both casters run the same ray code on the same pixel centres and blend alike, so the bytes
/// must be the same: measured so on llvmpipe (Mesa 22.3, 25 and 26) in every test, with one
/// exception that is the compiler's: llvmpipe of Mesa 26.1 (LLVM 21) miscompiles the nested-loop
/// fragment shader of smooth cells on a few samples (2 of 4,470 pixels of Mapper.LinearImage's
/// smooth scene by up to 11 levels, a third by one), where the compute caster, the flat loop and
/// the CPU mirror agree. Given the mirror's image, a pixel where the casters differ is excused
/// when the other caster's pixel is within one level of the mirror's and nearer to it than the
/// own caster's; at most 0.1 %
/// of the covered pixels (at least one) may be excused, and each is counted. A caster that misses
/// pixels, shifts the image or blends otherwise changes most covered pixels.
struct RayCasterComparison : FrameComparison
{
  int Caster = -1;       ///< the other caster, as it ran (GetLastRayCaster)
  int OtherCaster = -1;  ///< the caster it was asked for
  std::string NoCompute; ///< why compute fell back to fragment (empty: it did not)
  long long Excused =
    0; ///< different pixels where the other caster is the mirror's and the own not
  /// The other caster ran, on a frame with covered pixels, and every pixel is the same but the
  /// excused ones (at most 0.1 %); or the context has no compute shaders.
  bool Same() const
  {
    if (!this->NoCompute.empty())
    {
      return this->Caster == vtkSinglePassAMRVolumeMapper::FRAGMENT_CASTER;
    }
    return this->Caster == this->OtherCaster && this->CoveredPixels > 0 &&
      this->DifferentPixels == this->Excused &&
      this->Excused <= std::max<long long>(1, this->CoveredPixels / 1000);
  }
  std::string Describe() const
  {
    const std::string other = vtkSinglePassAMRVolumeMapper::GetRayCasterName(this->OtherCaster);
    if (!this->NoCompute.empty())
    {
      return other + " caster: not compared, " + this->NoCompute;
    }
    return other + " caster (ran: " + vtkSinglePassAMRVolumeMapper::GetRayCasterName(this->Caster) +
      "): " + FrameComparison::Describe() +
      (this->Excused > 0 ? ", of which " + std::to_string(this->Excused) +
            " where only the other caster is the CPU mirror's (the own caster miscompiled)"
                         : std::string());
  }
};

/// Renders the frame `gpu` rendered last (`image`) again with the other caster than the one it
/// ran and compares; the mapper's RayCaster setting is restored. `mirror`: the CPU mirror's image
/// of the same view, to excuse pixels the own caster got wrong (RayCasterComparison).
inline RayCasterComparison CompareOtherRayCaster(amrsp::harness::SinglePassRenderer& gpu,
  const amrsp::Image& image, const amrsp::Image* mirror = nullptr)
{
  using Mapper = vtkSinglePassAMRVolumeMapper;
  Mapper* m = gpu.GetMapper();
  const int setting = m->GetRayCaster();
  const int other = m->GetLastRayCaster() == Mapper::COMPUTE_CASTER ? Mapper::FRAGMENT_CASTER
                                                                    : Mapper::COMPUTE_CASTER;
  m->SetRayCaster(other);
  double ms = 0.0;
  const amrsp::Image otherImage = gpu.RenderAsIs(ms);
  RayCasterComparison c;
  c.OtherCaster = other;
  c.Caster = m->GetLastRayCaster();
  c.NoCompute = m->GetRayCasterFallbackReason();
  m->SetRayCaster(setting);
  static_cast<FrameComparison&>(c) = CompareFrames(otherImage, image);
  if (mirror && c.DifferentPixels > 0 && mirror->Pixels.size() == image.Pixels.size())
  {
    const std::vector<std::uint8_t> own = image.Rgb8(), theirs = otherImage.Rgb8(),
                                    cpu = mirror->Rgb8();
    for (std::size_t i = 0; i + 2 < own.size(); i += 3)
    {
      int ownOff = 0, otherOff = 0, differ = 0;
      for (std::size_t k = i; k < i + 3; ++k)
      {
        differ = std::max(differ, std::abs(int(own[k]) - int(theirs[k])));
        ownOff = std::max(ownOff, std::abs(int(own[k]) - int(cpu[k])));
        otherOff = std::max(otherOff, std::abs(int(theirs[k]) - int(cpu[k])));
      }
      c.Excused += differ > 0 && otherOff <= 1 && otherOff < ownOff ? 1 : 0;
    }
  }
  return c;
}

/// A mapper test's main: SKIPPED (or, in CI, FAILED) when the GPU renderers cannot run
/// here; otherwise runs `body`, counts an exception escaping it as a failed check, prints PASSED
/// or "FAILED: N check(s)" and returns the exit code.
template <class Body>
int RunChecks(Body body)
{
  std::string why;
  if (!amrsp::harness::GpuRenderer::Available(why))
  {
    return SkipOrFail(why);
  }
  try
  {
    body();
  }
  catch (const std::exception& e)
  {
    std::cout << "  FAILED  " << e.what() << "\n";
    ++Failures();
  }
  std::cout << (Failures() == 0 ? "PASSED" : "FAILED: " + std::to_string(Failures()) + " check(s)")
            << "\n";
  return Failures() == 0 ? 0 : 1;
}

} // namespace mappertest
