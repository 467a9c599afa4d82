// SPDX-License-Identifier: BSD-3-Clause
// Interactive frames of vtkSinglePassAMRVolumeMapper (AutoAdjustSampleDistances and friends): a
// frame with less than a second allocated casts its rays into a reduced image magnified over the
// viewport, with a longer sample distance; still frames stay bit for bit what they were.
#include "AmrspDataset.h"
#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"
#include "MapperTestScenes.h"

#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
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
// vtkRenderWindow's default (still) and a rate that leaves every prop far below a second
constexpr double StillRate = 0.0001;
constexpr double InteractiveRate = 1000.0;

/// RMSE over the pixels either image covers (the tool's background is black).
double VolumeRmse(const Image& a, const Image& b)
{
  return mappertest::CoveredRmse(a, b);
}

void TestInteractiveFrames()
{
  Hierarchy h = mappertest::LoadHierarchy("synthetic:cosmo:grids=200,levels=4,cells=2M,seed=5");
  const RenderSettings s = mappertest::Settings(h, mappertest::Request(128, 128));
  SinglePassRenderer gpu(h, s, ViewAngles(), DataStorage::PackedAtlas);
  vtkSinglePassAMRVolumeMapper* mapper = gpu.GetMapper();
  vtkRenderWindow* window = gpu.GetRenderer()->GetRenderWindow();
  double ms = 0.0;

  // still frames: full quality, as before this feature
  const Image still = gpu.Render(0.0, ms);
  Check(!mapper->GetLastFrameInteractive() && mapper->GetLastImageSampleDistance() == 1.0 &&
      mapper->GetLastFrameBudget() >= 1.0 && mapper->GetLastFrameSeconds() > 0.0,
    "a still frame (" + Fixed(mapper->GetLastFrameBudget()) + " s allocated, " +
      Fixed(mapper->GetLastFrameSeconds()) + " s measured) is full quality");
  const Image turned = gpu.Render(30.0, ms); // the camera turned by 30 degrees
  gpu.Render(0.0, ms);

  // interactive frames: the budget nothing fits, so the coarsest rung (MaximumImageSampleDistance)
  mapper->SetMaximumImageSampleDistance(2.0f);
  window->SetDesiredUpdateRate(InteractiveRate);
  const Image interactive = gpu.RenderAsIs(ms);
  const double rmse = VolumeRmse(interactive, still);
  // the other caster casts the same reduced image (and composites it the same way)
  const auto sameByOtherCaster = [&gpu, mapper](const Image& frame, const std::string& what)
  {
    const mappertest::RayCasterComparison c = mappertest::CompareOtherRayCaster(gpu, frame);
    Check(c.Same() && mapper->GetLastImageSampleDistance() == 2.0,
      what + " by the " + c.Describe() + " (image sample distance " +
        Fixed(mapper->GetLastImageSampleDistance()) + ")");
  };
  sameByOtherCaster(interactive, "the interactive frame");
  Check(mapper->GetLastFrameInteractive() && mapper->GetLastImageSampleDistance() == 2.0 &&
      mapper->GetLastSampleDistanceScale() == 2.0,
    "an interactive frame (" + Fixed(mapper->GetLastFrameBudget()) +
      " s allocated) casts a ray every 2 pixels, samples every 2 steps (" +
      Fixed(mapper->GetLastImageSampleDistance()) + ", " +
      Fixed(mapper->GetLastSampleDistanceScale()) + ")");
  const double coverageRatio = Coverage(interactive) / std::max(1e-9, Coverage(still));
  std::cout << "  interactive frame vs still frame: RMSE over the volume " << Fixed(rmse)
            << ", coverage " << Fixed(Coverage(interactive)) << " vs " << Fixed(Coverage(still))
            << "; the turned camera: RMSE " << Fixed(VolumeRmse(turned, still)) << "\n";
  // The bounds: measured 3.3 (RMSE over the covered pixels) and 1.00 (coverage) here. They reject
  // what a reduced frame drawn wrong gives: no composite (the background alone), and a still frame
  // of another view.
  const auto faithful = [&still](const Image& img)
  {
    const double c = Coverage(img) / std::max(1e-9, Coverage(still));
    return VolumeRmse(img, still) < 6.0 && c > 0.97 && c < 1.03;
  };
  Check(faithful(interactive),
    "the interactive frame is the still frame at a lower resolution (RMSE " + Fixed(rmse) +
      " < 6, coverage ratio " + Fixed(coverageRatio) + ")");
  Image background = still;
  std::fill(background.Pixels.begin(), background.Pixels.end(), glm::vec4(0.0f));
  Check(!faithful(background) && !faithful(turned),
    "the check rejects the background alone and another view (RMSE " +
      Fixed(VolumeRmse(turned, still)) + ")");
  Check(Rmse(interactive, still) > 0.0, "the interactive frame is not the still frame");

  // the next still frame is full quality again, bit for bit
  window->SetDesiredUpdateRate(StillRate);
  const Image again = gpu.RenderAsIs(ms);
  Check(Rmse(again, still) == 0.0 && !mapper->GetLastFrameInteractive(),
    "the still frame after interactive ones is bit-identical (RMSE " + Fixed(Rmse(again, still)) +
      ")");

  // AutoAdjustSampleDistances off: every frame at ImageSampleDistance, the sample distance as set
  mapper->AutoAdjustSampleDistancesOff();
  mapper->SetImageSampleDistance(2.0f);
  const Image fixed = gpu.RenderAsIs(ms);
  sameByOtherCaster(fixed, "ImageSampleDistance 2");
  Check(mapper->GetLastImageSampleDistance() == 2.0 &&
      mapper->GetLastSampleDistanceScale() == 1.0 && mapper->GetLastFrameSeconds() == 0.0 &&
      faithful(fixed),
    "ImageSampleDistance 2 without auto-adjusting: RMSE " + Fixed(VolumeRmse(fixed, still)));
  mapper->SetImageSampleDistance(1.0f);
  Check(Rmse(gpu.RenderAsIs(ms), still) == 0.0, "ImageSampleDistance 1: the still frame");
  mapper->AutoAdjustSampleDistancesOn();

  // opaque geometry: the reduced frame reads the viewport-sized depth at its own pixels
  mappertest::AddCentralSphere(gpu.GetRenderer(), h);
  const Image stillSphere = gpu.RenderAsIs(ms);
  window->SetDesiredUpdateRate(InteractiveRate);
  const Image interactiveSphere = gpu.RenderAsIs(ms);
  const double sphereSampleDistance = mapper->GetLastImageSampleDistance();
  sameByOtherCaster(interactiveSphere, "the interactive frame with opaque geometry");
  window->SetDesiredUpdateRate(StillRate);
  // without the sphere's depth the volume in front of it and behind it would both show; with the
  // depth read at the reduced image's own pixel (the scale to the viewport ignored) the RMSE
  // was 11.7 here (measured over the whole frame, scaled by the coverage; this RMSE is 4.0)
  const double sphereRmse = VolumeRmse(interactiveSphere, stillSphere);
  const double noDepthRmse = VolumeRmse(still, stillSphere);
  std::cout << "  with an opaque sphere: interactive vs still RMSE " << Fixed(sphereRmse)
            << "; the volume without the sphere vs with it: " << Fixed(noDepthRmse) << "\n";
  Check(sphereSampleDistance == 2.0 && sphereRmse < 8.0 && noDepthRmse > 8.0,
    "with opaque geometry the interactive frame stops its rays at the geometry (RMSE " +
      Fixed(sphereRmse) + " < 8; the image ignoring it: " + Fixed(noDepthRmse) + ")");
}

} // namespace

int main()
{
  return mappertest::RunChecks(TestInteractiveFrames);
}
