// SPDX-License-Identifier: BSD-3-Clause
// Iso-surfaces: spheres of known radius and layers composited by hand (TestAnalyticImages.cxx's
// header says what is checked).
#include "AnalyticScenes.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace analytic
{
// ---- iso-surfaces -----------------------------------------------------------------------

void TestIsoSurfaces()
{
  std::cout << "iso-surfaces\n";
  // f = distance from the centre, 64^3 cells of 1/64; spheres of radius 0.2 (red) and 0.35
  // (blue), each crossing half opaque; parallel view down z, 96 px over the unit square
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 64.0);
  h.ArrayName = "radius";
  const glm::dvec3 centre(0.5);
  AddGrid(h, 0, Cube(0, 64),
    [&](const glm::dvec3& p) { return static_cast<float>(glm::length(p - centre)); });
  RenderSettings s;
  s.Width = s.Height = 96;
  s.View = TopView(true);
  s.Blend = BlendMode::IsoSurface;
  s.Transfer.Color = { { 0.2, glm::dvec3(1.0, 0.0, 0.0) }, { 0.35, glm::dvec3(0.0, 0.0, 1.0) } };
  s.Transfer.Opacity = { { 0.2, 0.5 }, { 0.35, 0.5 } };
  s.IsoValues = { 0.2, 0.35 };
  s = WithCaster(s);
  SinglePassRenderer gpu(h, s, SettingsCamera());
  const Image img = RenderAsSet(gpu);

  // per pixel the distance rho of its ray from the centre; nearest cells quantise the field by
  // up to half a cell diagonal (0.014): zones keep 2 cells (0.031) from each radius
  const double margin = 2.0 / 64.0;
  const auto zones = [&](const Image& image, std::size_t counts[3], std::size_t wrong[3])
  {
    for (int z = 0; z < 3; ++z)
    {
      counts[z] = wrong[z] = 0;
    }
    for (int j = 0; j < s.Height; ++j)
    {
      for (int i = 0; i < s.Width; ++i)
      {
        const double x = (i + 0.5) / s.Width - 0.5, y = (j + 0.5) / s.Height - 0.5;
        const double rho = std::sqrt(x * x + y * y);
        const glm::vec4& p = image.Pixels[static_cast<std::size_t>(j) * s.Width + i];
        const bool red = p.r > 0.08f, blue = p.b > 0.08f, dark = p.r + p.g + p.b < 0.02f;
        int zone = -1;
        bool right = false;
        if (rho < 0.2 - margin)
        {
          zone = 0; // both spheres in front: red and blue
          right = red && blue;
        }
        else if (rho > 0.2 + margin && rho < 0.35 - margin)
        {
          zone = 1; // the outer sphere only
          right = blue && !red;
        }
        else if (rho > 0.35 + margin)
        {
          zone = 2; // nothing
          right = dark;
        }
        if (zone >= 0)
        {
          ++counts[zone];
          wrong[zone] += right ? 0 : 1;
        }
      }
    }
  };
  std::size_t counts[3], wrong[3];
  zones(img, counts, wrong);
  const char* names[3] = { "inside radius 0.2: red and blue", "between the radii: blue only",
    "outside radius 0.35: background" };
  for (int z = 0; z < 3; ++z)
  {
    Check(counts[z] > 300 && wrong[z] == 0,
      std::string(names[z]) + ": " + std::to_string(wrong[z]) + " of " + std::to_string(counts[z]) +
        " px differ");
  }
  // the wrong images: one iso-value dropped
  vtkSinglePassAMRVolumeMapper* m = gpu.GetMapper();
  for (const double kept : { 0.2, 0.35 })
  {
    RenderSettings one = s;
    one.IsoValues = { kept };
    SinglePassRenderer single(h, one, SettingsCamera());
    std::size_t c[3], w[3];
    zones(RenderAsSet(single), c, w);
    Check(w[0] + w[1] + w[2] > 300,
      "iso-value " + Fixed(kept) + " alone: " + std::to_string(w[0] + w[1] + w[2]) +
        " px in the wrong zone (rejected)");
  }
  (void)m;
}

/// One iso-surface layer of TestIsoLayers: its value, colour and opacity (flat in the transfer
/// function around the value, so that the table's resolution cannot blend neighbours).
struct IsoLayer
{
  double Value;
  glm::dvec3 Colour;
  double Opacity;
};

/// Front to back over `layers` in the given order: the textbook composite, C = sum_k T_k a_k c_k,
/// T_{k+1} = T_k (1 - a_k), over a black background.
glm::dvec3 CompositeLayers(const std::vector<IsoLayer>& layers)
{
  glm::dvec3 c(0.0);
  double t = 1.0;
  for (const IsoLayer& l : layers)
  {
    c += t * l.Opacity * l.Colour;
    t *= 1.0 - l.Opacity;
  }
  return c;
}

void TestIsoLayers()
{
  std::cout << "eight iso-surfaces, several between two samples\n";
  // f = z (world) on 16^3 cells: nearest cells hold (k + 1/2) / 16, so the ray down -z crosses
  // 0.62 and 0.60 between two samples (cells 0.656 and 0.594), 0.40, 0.38, 0.36 between two
  // (0.406, 0.344) and 0.14, 0.12, 0.10 between two (0.156, 0.094). Every pixel is then the same
  // composite of the eight layers, met in descending value: known from the rule alone.
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 16.0);
  h.ArrayName = "height";
  AddGrid(h, 0, Cube(0, 16), [](const glm::dvec3& p) { return static_cast<float>(p.z); });
  const std::vector<IsoLayer> layers = { { 0.10, { 1.0, 0.0, 0.0 }, 0.30 },
    { 0.12, { 0.0, 1.0, 0.0 }, 0.45 }, { 0.14, { 0.0, 0.0, 1.0 }, 0.35 },
    { 0.36, { 1.0, 1.0, 0.0 }, 0.50 }, { 0.38, { 0.0, 1.0, 1.0 }, 0.25 },
    { 0.40, { 1.0, 0.0, 1.0 }, 0.40 }, { 0.60, { 1.0, 1.0, 1.0 }, 0.30 },
    { 0.62, { 1.0, 0.5, 0.0 }, 0.55 } };
  RenderSettings s;
  s.Width = s.Height = 48;
  s.View = TopView(true);
  s.Blend = BlendMode::IsoSurface;
  for (const IsoLayer& l : layers)
  {
    s.IsoValues.push_back(l.Value);
    for (const double x : { l.Value - 0.005, l.Value + 0.005 })
    {
      s.Transfer.Color.push_back({ x, l.Colour });
      s.Transfer.Opacity.push_back({ x, l.Opacity });
    }
  }
  s = WithCaster(s);
  const std::vector<IsoLayer> met(layers.rbegin(), layers.rend());
  const glm::dvec3 expected = CompositeLayers(met);
  // the same layers composited by a wrong rule: ascending values within a sample pair (the order
  // of the iso-values, not the ray's), and only the first two crossings of a pair
  const glm::dvec3 ascending = CompositeLayers(
    { layers[6], layers[7], layers[3], layers[4], layers[5], layers[0], layers[1], layers[2] });
  const glm::dvec3 firstTwo =
    CompositeLayers({ layers[7], layers[6], layers[5], layers[4], layers[2], layers[1] });
  // measured (llvmpipe): 0.18 levels on the GPU, 0.00 on both CPU integrators; the wrong
  // rules' composites are 45 and 25 levels off, their shaders 41 and 52
  const double bound = 1.0;
  Check(255.0 * glm::length(ascending - expected) > 4.0 * bound &&
      255.0 * glm::length(firstTwo - expected) > 4.0 * bound,
    "the wrong rules' composites differ from the right one by " +
      Fixed(255.0 * glm::length(ascending - expected)) + " and " +
      Fixed(255.0 * glm::length(firstTwo - expected)) + " levels");

  SinglePassRenderer gpu(h, s, SettingsCamera());
  const double onGpu = LargestDifference(RenderAsSet(gpu), expected);
  Check(onGpu <= bound,
    "GPU: every pixel within " + Fixed(onGpu) +
      " of the composite of the eight layers in ray "
      "order (bound " +
      Fixed(bound) + ")");
  if (Caster == RayCaster::Fragment)
  {
    const double reference = LargestDifference(RenderReference(h, s), expected);
    const double mirror = LargestDifference(MirrorImage(h, s), expected);
    Check(reference <= bound && mirror <= bound,
      "CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " from the same composite (bound " + Fixed(bound) + ")");
  }
  // the wrong rules, in the shader: the crossings of a falling pair in ascending value, and the
  // crossings beyond the second dropped
  const struct
  {
    const char* What;
    const char* From;
    const char* To;
  } wrongRules[] = {
    { "crossings of a pair met in ascending value",
      "amrspIsoValues[rising ? i : amrspIsoCount - 1 - i]", "amrspIsoValues[i]" },
    { "iso-values beyond the second of a pair dropped", "for (int i = 0; i < amrspIsoCount; ++i)",
      "for (int i = 0; i < min(amrspIsoCount, 2); ++i)" },
  };
  for (const auto& wrong : wrongRules)
  {
    const double off = LargestDifference(RenderWithWrongRule(gpu, wrong.From, wrong.To), expected);
    Check(off > 4.0 * bound,
      std::string("the shader with ") + wrong.What + ": " + Fixed(off) + " levels off (rejected)");
  }

  // seen from below (+z) the ray meets the same layers in ascending value
  RenderSettings up = s;
  up.View.Position = glm::dvec3(0.5, 0.5, -4.0);
  const glm::dvec3 rising = CompositeLayers(layers);
  SinglePassRenderer below(h, up, SettingsCamera());
  const double onGpuBelow = LargestDifference(RenderAsSet(below), rising);
  Check(onGpuBelow <= bound && 255.0 * glm::length(rising - expected) > 4.0 * bound,
    "GPU from below: every pixel within " + Fixed(onGpuBelow) +
      " of the composite in ascending value (bound " + Fixed(bound) + "; " +
      Fixed(255.0 * glm::length(rising - expected)) + " levels from the view from above)");
  if (Caster == RayCaster::Fragment)
  {
    const double reference = LargestDifference(RenderReference(h, up), rising);
    const double mirror = LargestDifference(MirrorImage(h, up), rising);
    Check(reference <= bound && mirror <= bound,
      "from below: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " from the same composite (bound " + Fixed(bound) + ")");
  }
  const double off = LargestDifference(
    RenderWithWrongRule(below, "amrspIsoValues[rising ? i : amrspIsoCount - 1 - i]",
      "amrspIsoValues[amrspIsoCount - 1 - i]"),
    rising);
  Check(off > 4.0 * bound,
    "the shader with the crossings of a rising pair in descending value: " + Fixed(off) +
      " levels off (rejected)");
}

} // namespace analytic
