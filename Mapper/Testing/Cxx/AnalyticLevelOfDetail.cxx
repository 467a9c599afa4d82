// SPDX-License-Identifier: BSD-3-Clause
// The level-of-detail rule, against discs computed per pixel (TestAnalyticImages.cxx's header says
// what is checked).
#include "AnalyticScenes.h"

#include "amrsp/KdTraversal.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace analytic
{
// ---- level of detail --------------------------------------------------------------------

/// Level 0: 8^3 cells of 1/8 holding 1; level 1 (ratio 2) over [1/4, 3/4)^3 holding 2.
Hierarchy LevelPatch()
{
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 8.0);
  h.RefinementRatio.push_back(glm::ivec3(2));
  h.ArrayName = "level";
  AddGrid(h, 0, Cube(0, 8), [](const glm::dvec3&) { return 1.0f; });
  AddGrid(h, 1, Cube(4, 12), [](const glm::dvec3&) { return 2.0f; });
  return h;
}

/// Maximum intensity through a transfer function red at 1, green at 2, opaque.
RenderSettings LevelSettings(int size, const Camera& view, float lod)
{
  RenderSettings s;
  s.Width = s.Height = size;
  s.View = view;
  s.Blend = BlendMode::Maximum;
  s.Transfer.Color = { { 1.0, glm::dvec3(1.0, 0.0, 0.0) }, { 2.0, glm::dvec3(0.0, 1.0, 0.0) } };
  s.Transfer.Opacity = { { 1.0, 1.0 }, { 2.0, 1.0 } };
  s.Transfer.UnitDistance = 0.1;
  s.LodThresholdPixels = lod;
  s.OpacityThreshold = 0.999;
  return s;
}

/// Pixels showing the fine level (green above red) and the coarse one (red above green).
void CountLevels(const Image& img, std::size_t& fine, std::size_t& coarse)
{
  fine = coarse = 0;
  for (const glm::vec4& p : img.Pixels)
  {
    fine += p.g > 0.5f && p.r < 0.5f ? 1 : 0;
    coarse += p.r > 0.5f && p.g < 0.5f ? 1 : 0;
  }
}

/// Where the ray through pixel (i, j) enters the patch [1/4, 3/4)^3, or infinity.
double PatchEntry(const RenderSettings& s, int i, int j)
{
  glm::dvec3 o, d;
  s.View.Ray(s.Width, s.Height, i + 0.5, j + 0.5, o, d);
  float t0, t1;
  if (!IntersectBox(glm::vec3(0.25f), glm::vec3(0.75f), glm::vec3(o), glm::vec3(d), t0, t1))
  {
    return std::numeric_limits<double>::infinity();
  }
  return t0;
}

/// Pixels whose fine/coarse class differs from the disc expected for threshold `lod` (pixels
/// whose entry lies within `band` of the boundary distance count for neither), and the pixels
/// the expectation covers.
std::size_t PerspectiveMismatches(
  const Image& img, const RenderSettings& s, double lod, double band, std::size_t& expectedFine)
{
  const double perDistance = 2.0 * std::tan(glm::radians(s.View.ViewAngle) * 0.5) / s.Height;
  const double boundary = (1.0 / 8.0) / (lod * perDistance); // c0 / (T x pixel per distance)
  std::size_t wrong = 0;
  expectedFine = 0;
  for (int j = 0; j < s.Height; ++j)
  {
    for (int i = 0; i < s.Width; ++i)
    {
      const double t = PatchEntry(s, i, j);
      if (!std::isfinite(t) || std::fabs(t - boundary) < band)
      {
        continue;
      }
      const bool fine = t < boundary;
      expectedFine += fine ? 1 : 0;
      const glm::vec4& p = img.Pixels[static_cast<std::size_t>(j) * s.Width + i];
      const bool shownFine = p.g > 0.5f && p.r < 0.5f;
      wrong += shownFine != fine ? 1 : 0;
    }
  }
  return wrong;
}

void TestLevelOfDetail()
{
  std::cout << "level of detail\n";
  Hierarchy h = LevelPatch();
  // parallel: 64 px over the unit square, a level-0 cell is 8 px, the patch 32 x 32 = 1024 px
  {
    RenderSettings s = WithCaster(LevelSettings(64, TopView(true), 0.0f));
    SinglePassRenderer gpu(h, s, SettingsCamera());
    vtkSinglePassAMRVolumeMapper* m = gpu.GetMapper();
    const struct
    {
      float Threshold;
      bool Fine;
    } cases[] = { { 0.0f, true }, { 6.0f, true }, { 10.0f, false }, { 16.0f, false } };
    std::size_t fine = 0, coarse = 0;
    for (const auto& c : cases)
    {
      m->SetLODThreshold(c.Threshold);
      CountLevels(RenderAsSet(gpu), fine, coarse);
      Check(fine == (c.Fine ? 1024u : 0u) && fine + coarse == 4096u,
        "parallel, threshold " + Fixed(c.Threshold) + " px (level-0 cells 8 px): " +
          std::to_string(fine) + " px show level 1, " + std::to_string(coarse) +
          " level 0 (expected " + (c.Fine ? "1024 and 3072" : "0 and 4096") + ")");
    }
    // the rule off by a factor 2 (the pixel size halved) takes threshold 10 for 5: rejected
    if (vtkOpenGLShaderProperty* shader = ShaderProperty(gpu))
    {
      shader->AddFragmentShaderReplacement("if (cellWorld < amrspLodThreshold * pixel)", false,
        "if (cellWorld < amrspLodThreshold * 0.5 * pixel)", false);
      m->SetLODThreshold(10.0f);
      CountLevels(RenderAsSet(gpu), fine, coarse);
      shader->ClearAllFragmentShaderReplacements();
      Check(fine == 1024u,
        "the rule off by a factor 2 shows level 1 at threshold 10 (" + std::to_string(fine) +
          " px): the check above rejects it");
    }
    else
    {
      Check(false, "the volume has a vtkOpenGLShaderProperty");
    }
  }
  // perspective, 0.35 above the patch, 90 degrees: level 1 where the ray enters the patch before
  // c0 / (10 x pixel size per distance) = 0.4, a disc of about 18 px radius inside its 46 px square
  {
    RenderSettings s = WithCaster(LevelSettings(64, TopView(false, 0.1, 90.0), 10.0f));
    SinglePassRenderer gpu(h, s, SettingsCamera());
    const Image img = RenderAsSet(gpu);
    const double band = 0.004; // about half a pixel's change of entry distance at the boundary
    std::size_t expectedFine = 0;
    const std::size_t wrong = PerspectiveMismatches(img, s, 10.0, band, expectedFine);
    std::size_t fine = 0, coarse = 0;
    CountLevels(img, fine, coarse);
    Check(wrong <= 4 && expectedFine > 700 && expectedFine < 1300,
      "perspective, threshold 10 px: " + std::to_string(fine) + " px show level 1, " +
        std::to_string(wrong) + " px differ from the disc of entries nearer than c0 / (10 x " +
        "pixel size per distance) (" + std::to_string(expectedFine) + " px; at most 4 may)");
    // what a rule twice as eager would show: its disc is the one of threshold 20 / 2 ... the
    // expectation of another threshold must not match the image
    std::size_t otherFine = 0;
    const std::size_t wrongFor7 = PerspectiveMismatches(img, s, 7.0, band, otherFine);
    const std::size_t wrongFor14 = PerspectiveMismatches(img, s, 14.0, band, otherFine);
    Check(wrongFor7 > 8 * (wrong + 1) && wrongFor14 > 8 * (wrong + 1),
      "the discs of thresholds 7 and 14 differ from the image by " + std::to_string(wrongFor7) +
        " and " + std::to_string(wrongFor14) + " px: the check tells the thresholds apart");
    vtkSinglePassAMRVolumeMapper* m = gpu.GetMapper();
    m->SetLODThreshold(0.0);
    std::size_t offExpected = 0;
    const std::size_t wrongOff =
      PerspectiveMismatches(RenderAsSet(gpu), s, 10.0, band, offExpected);
    Check(wrongOff > 8 * (wrong + 1),
      "with the level of detail off the image differs from the disc by " +
        std::to_string(wrongOff) + " px: rejected");
  }
}

} // namespace analytic
