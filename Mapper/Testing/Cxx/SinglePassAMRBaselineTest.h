// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The scene of every baseline-image test: a dataset rendered by vtkSinglePassAMRVolumeMapper
/// with the amrsp tool's conventions, compared with VTK's baseline image AND with the CPU
/// reference image of the same view.

#include "AmrspRenderRequest.h"

#include "amrsp/Render.h"

#include <glm/glm.hpp>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

class vtkRenderer;

namespace amrsp
{
namespace harness
{
class SinglePassRenderer;
}
namespace test
{

struct BaselineCase
{
  /// A dataset argument of the amrsp tool; a path relative to AMRSP_DATA_DIR starts with "data:".
  std::string Dataset;
  /// The array and centring to load (amrsp's --array, --centering; empty array: the first).
  std::string Array;
  std::string Centering = "auto";
  /// The render options as values (size, view, transfer function, blending, lighting, ...);
  /// the tool's defaults where not set.
  harness::RenderRequest Request;
  /// Optional: the hierarchy to render (cell-centred values as displayed) instead of loading
  /// Dataset, which then only names it in the log.
  std::function<Hierarchy()> Data;
  /// Optional change of the settings after the amrsp options were applied (e.g. a transfer
  /// function written in the data's own values); used by the GPU and the CPU images alike.
  std::function<void(RenderSettings&)> Settings;
  /// Largest RMSE (0-255 units) allowed between the GPU image and the CPU reference, over the
  /// pixels the volume covers (amrsp::ImageDifference), and the largest share of those pixels
  /// off by more than ImageDifference::OffLevels. Each about twice what is measured.
  double ReferenceBound = 2.0;
  double ReferenceOffBound = 0.05;
  /// Largest covered RMSE allowed between the GPU image and the CPU kD-tree integrator (its
  /// mirror: same segments, same sample positions).
  double MirrorBound = 1.0;
  /// Largest covered RMSE allowed between the GPU image and the stored baseline image (which
  /// must also pass ReferenceBound against the CPU reference): llvmpipe of LLVM 15 to 21.
  double BaselineBound = 1.0;

  /// Wrong images the bounds must reject: the scene with one thing broken (the feature under
  /// test switched off, the data changed), rendered by the CPU kD-tree integrator as a shader
  /// with that defect would render it. Each must exceed ReferenceBound or ReferenceOffBound
  /// against the reference by at least twice the margin between the bound and what the GPU image
  /// measures, in the test itself. The harness adds one of its own: level 0 alone (what a
  /// renderer resampling to the coarse grid shows).
  struct WrongImage
  {
    std::string What;
    std::function<void(RenderSettings&)> Settings;   // optional
    std::function<Hierarchy(const Hierarchy&)> Data; // optional
    /// The reference cannot tell this image (it is as close to it as the right one): MirrorBound
    /// may reject it instead, and a test of its own must check the rule independently (say which).
    bool ReferenceBlind = false;
  };
  std::vector<WrongImage> WrongImages;
  /// Optional change of the scene before rendering (camera moves); the CPU reference uses the
  /// resulting VTK camera.
  std::function<void(vtkRenderer*)> Adjust;

  /// Opaque, unlit squares added to the scene (as vtkPlaneSource actors for the GPU, and as
  /// analytic surfaces that end the rays of the CPU images): centre, normal, up direction, half
  /// edge length and grey level, in world units.
  struct Square
  {
    glm::dvec3 Centre;
    glm::dvec3 Normal;
    glm::dvec3 Up;
    double Half;
    double Grey;
  };
  std::vector<Square> Squares;

  /// Optional further checks after the GPU image `image` was rendered (e.g. the same view with
  /// an option switched off); `settings` are those of the image, with the camera of the frame.
  /// They may render other frames but must leave the mapper as they found it: the harness
  /// renders again and requires the very same image before comparing with the baseline.
  /// Returns false (after printing why to `log`) to fail the test.
  std::function<bool(harness::SinglePassRenderer& gpu, const Image& image,
    const RenderSettings& settings, std::ostream& log)>
    Check;

  /// Compare the shader's own work counts (vtkSinglePassAMRVolumeMapper::AccelerationCountsOutput,
  /// summed over the frame) with the CPU kD-tree integrator's RenderStats of the same view: data
  /// segments reached, segments skipped as empty space, rays terminated early. Each must agree to
  /// within 1 % (+ 2). With ExpectSkipped / ExpectTerminated that count must also be positive, and
  /// zero again with the feature switched off (EmptySpaceSkipping off; OpacityThreshold 1), so a
  /// shader that ignored the feature fails.
  bool CheckWorkCounters = false;
  bool ExpectSkipped = false;
  bool ExpectTerminated = false;
};

/// Runs the test; returns the test driver's exit code (0 pass, 1 fail, 125 skipped).
int RunBaselineTest(int argc, char* argv[], const BaselineCase& c);

} // namespace test
} // namespace amrsp
