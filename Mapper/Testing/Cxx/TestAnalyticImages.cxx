// SPDX-License-Identifier: BSD-3-Clause
//
// Features of vtkSinglePassAMRVolumeMapper checked against expectations that come from neither
// the shader's CPU mirror nor the CPU reference: hand-made hierarchies and views whose right image
// is known from the geometry and the rule's definition, pixel by pixel.
//
//   lod         the level-of-detail rule (docs/design.md): a type (a) node stops the descent when
//               one cell of its data level is smaller than LODThreshold pixels at the ray's entry.
//               Level 0 holds 1 (red), a level-1 patch over the middle holds 2 (green); maximum
//               intensity shows which level a ray sampled. Parallel view, level-0 cells of 8
//               pixels: thresholds 6 and off show the patch green, 10 and 16 red. Perspective view
//               close to the patch: green exactly where the ray enters the patch nearer than
//               c0 / (threshold x pixel size per distance), a disc computed per pixel here.
//   iso         iso-surfaces of f = distance from the centre at two iso-values: two spheres of
//               known radius seen along an axis; red (the inner value's colour) only inside the
//               inner ring, blue inside the outer, background beyond.
//               Then eight iso-values, up to three crossed between two samples: every pixel is
//               the textbook composite of the eight layers in the order the ray meets them.
//   nan         a column of NaN cells through the whole volume shows the background exactly, the
//               rest of the volume is drawn. Then slabs across the rays: NaN cells are skipped
//               (the ray goes on behind them), +Inf cells take the transfer function's last
//               point; each pixel is the composite computed here from the segment lengths.
//
// Each mode runs its checks twice, with the fragment and the compute caster (RayCaster), and
// shows in the test that the wrong rule fails its check: the shader with the LOD rule
// off by a factor 2 or dropped, one iso-value dropped, the crossings of a sample pair in
// ascending value or beyond the second dropped, NaN samples made opaque or ending the ray, +Inf
// treated as NaN (shader replacements, as TestLinearStorage breaks its layer stride). The layer
// and slab expectations are also required of the CPU reference and the CPU mirror.

#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkOpenGLShaderProperty.h"
#include "vtkRenderer.h"
#include "vtkSinglePassAMRVolumeMapper.h"
#include "vtkVolume.h"
#include "vtkVolumeCollection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::Check;
using mappertest::Failures;
using mappertest::Fixed;
using mappertest::ShaderProperty;

/// A grid of `level` over `cells` whose every cell holds value(its centre, world units).
void AddGrid(
  Hierarchy& h, int level, const Box& cells, const std::function<float(const glm::dvec3&)>& value)
{
  h.Grids.push_back(Grid{ level, cells });
  h.Grids.back().SourceId = static_cast<int64_t>(h.Grids.size() - 1);
  const glm::dvec3 size = h.CellSize(level) * h.Spacing0;
  const glm::i64vec3 e = cells.Extent();
  GridValues v(static_cast<std::size_t>(cells.Cells()));
  for (int64_t k = 0; k < e.z; ++k)
    for (int64_t j = 0; j < e.y; ++j)
      for (int64_t i = 0; i < e.x; ++i)
      {
        const glm::dvec3 centre =
          h.Origin + (glm::dvec3(cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * size;
        v[static_cast<std::size_t>((k * e.y + j) * e.x + i)] = value(centre);
      }
  h.Values.push_back(std::move(v));
}

Box Cube(int64_t lo, int64_t hi)
{
  return Box{ glm::i64vec3(lo), glm::i64vec3(hi) };
}

/// The view down -z onto the unit cube: parallel (the square fills the image) or perspective
/// from `distance` above the cube's top with the full vertical angle `angle`.
Camera TopView(bool parallel, double distance = 0.0, double angle = 30.0)
{
  Camera c;
  c.FocalPoint = glm::dvec3(0.5);
  c.Position = glm::dvec3(0.5, 0.5, parallel ? 5.0 : 1.0 + distance);
  c.ViewUp = glm::dvec3(0.0, 1.0, 0.0);
  c.Parallel = parallel;
  c.ParallelScale = 0.5;
  c.ViewAngle = angle;
  return c;
}

/// The caster every scene of this run is cast with (each mode runs once per caster).
RayCaster Caster = RayCaster::Fragment;

/// `s` with this run's caster.
RenderSettings WithCaster(RenderSettings s)
{
  s.GpuRayCaster = Caster;
  return s;
}

/// Renders `h` with `s` (its camera as it is) and returns the frame; a frame cast by another
/// caster than this run's is a failed check.
Image RenderAsSet(SinglePassRenderer& gpu)
{
  double ms = 0.0;
  Image image = gpu.Render(0.0, ms);
  const int ran = gpu.GetMapper()->GetLastRayCaster();
  if (ran != static_cast<int>(Caster))
  {
    Check(false,
      std::string("the frame was cast by the ") +
        vtkSinglePassAMRVolumeMapper::GetRayCasterName(ran) + " caster, not the " +
        RayCasterName(Caster));
  }
  return image;
}

ViewAngles SettingsCamera()
{
  ViewAngles v;
  v.UseSettingsCamera = true;
  return v;
}

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

/// The largest channel difference (0-255) between `image` and the colour `expected` over every
/// pixel.
double LargestDifference(const Image& image, const glm::dvec3& expected)
{
  double worst = 0.0;
  for (const glm::vec4& p : image.Pixels)
  {
    for (int c = 0; c < 3; ++c)
    {
      worst = std::max(worst, 255.0 * std::abs(static_cast<double>(p[c]) - expected[c]));
    }
  }
  return worst;
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
    const double mirror =
      LargestDifference(RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), s), expected);
    Check(reference <= bound && mirror <= bound,
      "CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " from the same composite (bound " + Fixed(bound) + ")");
  }
  // the wrong rules, in the shader: the crossings of a falling pair in ascending value, and the
  // crossings beyond the second dropped
  vtkOpenGLShaderProperty* shader = ShaderProperty(gpu);
  if (!shader)
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
    return;
  }
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
    shader->AddFragmentShaderReplacement(wrong.From, false, wrong.To, false);
    const double off = LargestDifference(RenderAsSet(gpu), expected);
    shader->ClearAllFragmentShaderReplacements();
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
    const double mirror =
      LargestDifference(RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), up), rising);
    Check(reference <= bound && mirror <= bound,
      "from below: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " from the same composite (bound " + Fixed(bound) + ")");
  }
  if (vtkOpenGLShaderProperty* belowShader = ShaderProperty(below))
  {
    belowShader->AddFragmentShaderReplacement("amrspIsoValues[rising ? i : amrspIsoCount - 1 - i]",
      false, "amrspIsoValues[amrspIsoCount - 1 - i]", false);
    const double off = LargestDifference(RenderAsSet(below), rising);
    belowShader->ClearAllFragmentShaderReplacements();
    Check(off > 4.0 * bound,
      "the shader with the crossings of a rising pair in descending value: " + Fixed(off) +
        " levels off (rejected)");
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }
}

// ---- NaN --------------------------------------------------------------------------------

void TestNaN()
{
  std::cout << "NaN samples\n";
  // 16^3 cells holding 1, a column x, y in [1/4, 1/2) through all z holding NaN; composite,
  // opaque colour; parallel view down z, 64 px: the column's 16 x 16 px show the background
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 16.0);
  h.ArrayName = "withnan";
  AddGrid(h, 0, Cube(0, 16),
    [](const glm::dvec3& p)
    {
      const bool column = p.x > 0.25 && p.x < 0.5 && p.y > 0.25 && p.y < 0.5;
      return column ? std::numeric_limits<float>::quiet_NaN() : 1.0f;
    });
  RenderSettings s;
  s.Width = s.Height = 64;
  s.View = TopView(true);
  s.Transfer.Color = { { 0.0, glm::dvec3(1.0, 1.0, 0.0) }, { 2.0, glm::dvec3(1.0, 1.0, 0.0) } };
  s.Transfer.Opacity = { { 0.0, 0.5 }, { 2.0, 0.5 } };
  s.Transfer.UnitDistance = 0.1;
  s.OpacityThreshold = 0.999;
  s = WithCaster(s);
  SinglePassRenderer gpu(h, s, SettingsCamera());
  const auto count = [&](const Image& img, std::size_t& columnLit, std::size_t& restDark)
  {
    columnLit = restDark = 0;
    for (int j = 0; j < s.Height; ++j)
    {
      for (int i = 0; i < s.Width; ++i)
      {
        const glm::vec4& p = img.Pixels[static_cast<std::size_t>(j) * s.Width + i];
        const bool lit = p.r + p.g + p.b > 0.0f;
        const bool column = i >= 16 && i < 32 && j >= 16 && j < 32;
        columnLit += column && lit ? 1 : 0;
        restDark += !column && !lit ? 1 : 0;
      }
    }
  };
  std::size_t columnLit = 0, restDark = 0;
  count(RenderAsSet(gpu), columnLit, restDark);
  Check(columnLit == 0 && restDark == 0,
    "the NaN column shows the background (" + std::to_string(columnLit) + " of 256 px lit), " +
      "the rest is drawn (" + std::to_string(restDark) + " of 3840 px dark)");
  if (vtkOpenGLShaderProperty* shader = ShaderProperty(gpu))
  {
    shader->AddFragmentShaderReplacement(
      "if (isnan(scalar))", false, "if (isnan(scalar)) { scalar = 1.0; } if (false)", false);
    count(RenderAsSet(gpu), columnLit, restDark);
    shader->ClearAllFragmentShaderReplacements();
    Check(columnLit == 256,
      "NaN samples made opaque light the column (" + std::to_string(columnLit) +
        " px): the check above rejects it");
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }
}

void TestMissingAndInfiniteSlabs()
{
  std::cout << "NaN and +Inf slabs across the rays\n";
  // 16^3 cells holding 1 (grey), a slab one cell thick at z in [1/2, 9/16) holding NaN where
  // x in [1/4, 1/2), +Inf where x in [5/8, 7/8), y < 1/2 for both; composite with opacity 0.5 per
  // unit distance 1, colour (1,1,0) at 0 and (0,0,1) at 2: value 1 is (0.5,0.5,0.5), +Inf takes
  // the last point's colour and opacity (the transfer function clamps; docs/command-line.md).
  // Along a ray down -z a length L of value v has alpha 1 - 0.5^L.
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 16.0);
  h.ArrayName = "slabs";
  const auto inSlab = [](const glm::dvec3& p) { return p.z > 0.5 && p.z < 0.5625 && p.y < 0.5; };
  AddGrid(h, 0, Cube(0, 16),
    [&](const glm::dvec3& p)
    {
      if (inSlab(p) && p.x > 0.25 && p.x < 0.5)
      {
        return std::numeric_limits<float>::quiet_NaN();
      }
      if (inSlab(p) && p.x > 0.625 && p.x < 0.875)
      {
        return std::numeric_limits<float>::infinity();
      }
      return 1.0f;
    });
  RenderSettings s;
  s.Width = s.Height = 64;
  s.View = TopView(true);
  s.Transfer.Color = { { 0.0, glm::dvec3(1.0, 1.0, 0.0) }, { 2.0, glm::dvec3(0.0, 0.0, 1.0) } };
  s.Transfer.Opacity = { { 0.0, 0.5 }, { 2.0, 0.5 } };
  s.Transfer.UnitDistance = 1.0;
  s = WithCaster(s);
  const glm::dvec3 grey(0.5), blue(0.0, 0.0, 1.0);
  const auto alpha = [](double length) { return 1.0 - std::pow(0.5, length); };
  // front to back: 7/16 of grey above the slab, the slab (1/16), 1/2 of grey below
  const auto column = [&](bool slabDrawn, const glm::dvec3& slabColour)
  {
    const double a1 = alpha(7.0 / 16.0), as = slabDrawn ? alpha(1.0 / 16.0) : 0.0;
    const double a2 = alpha(0.5);
    return a1 * grey + (1.0 - a1) * as * slabColour + (1.0 - a1) * (1.0 - as) * a2 * grey;
  };
  const glm::dvec3 plain = grey * alpha(1.0);
  const glm::dvec3 nanColumn = column(false, grey), infColumn = column(true, blue);
  // what wrong rules would show: a NaN sample ending the ray, +Inf transparent as NaN
  const glm::dvec3 nanEnds = grey * alpha(7.0 / 16.0);
  const auto expectedAt = [&](int i, int j, const glm::dvec3& nan, const glm::dvec3& inf)
  {
    const double x = (i + 0.5) / s.Width, y = (j + 0.5) / s.Height;
    if (y < 0.5 && x > 0.25 && x < 0.5)
    {
      return nan;
    }
    return y < 0.5 && x > 0.625 && x < 0.875 ? inf : plain;
  };
  const auto worst = [&](const Image& img, const glm::dvec3& nan, const glm::dvec3& inf)
  {
    double w = 0.0;
    for (int j = 0; j < s.Height; ++j)
    {
      for (int i = 0; i < s.Width; ++i)
      {
        const glm::vec4& p = img.Pixels[static_cast<std::size_t>(j) * s.Width + i];
        const glm::dvec3 e = expectedAt(i, j, nan, inf);
        for (int c = 0; c < 3; ++c)
        {
          w = std::max(w, 255.0 * std::abs(static_cast<double>(p[c]) - e[c]));
        }
      }
    }
    return w;
  };
  // measured (llvmpipe): 0.26 levels on the GPU, 0.00 on both CPU integrators; the NaN slab
  // alone moves its pixels by 4.9 levels, a ray ended there by 48, +Inf made transparent by 7.0
  const double bound = 1.0;
  Check(255.0 * glm::length(nanColumn - plain) > 2.0 * bound &&
      255.0 * glm::length(nanColumn - nanEnds) > 2.0 * bound &&
      255.0 * glm::length(infColumn - nanColumn) > 2.0 * bound,
    "the expectations are apart: NaN slab vs none " +
      Fixed(255.0 * glm::length(nanColumn - plain)) + ", vs a ray ended there " +
      Fixed(255.0 * glm::length(nanColumn - nanEnds)) + ", +Inf vs transparent " +
      Fixed(255.0 * glm::length(infColumn - nanColumn)) + " levels");
  SinglePassRenderer gpu(h, s, SettingsCamera());
  const double onGpu = worst(RenderAsSet(gpu), nanColumn, infColumn);
  Check(onGpu <= bound,
    "GPU: NaN slab transparent, +Inf slab the last colour: every pixel within " + Fixed(onGpu) +
      " levels of the composite (bound " + Fixed(bound) + ")");
  if (Caster == RayCaster::Fragment)
  {
    const double reference = worst(RenderReference(h, s), nanColumn, infColumn);
    const double mirror =
      worst(RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), s), nanColumn, infColumn);
    Check(reference <= bound && mirror <= bound,
      "CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels from the same (bound " + Fixed(bound) + ")");
  }
  vtkOpenGLShaderProperty* shader = ShaderProperty(gpu);
  if (!shader)
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
    return;
  }
  const struct
  {
    const char* What;
    const char* From;
    const char* To;
  } wrongRules[] = {
    { "a NaN sample ending the ray", "return true; // missing data is transparent",
      "return false;" },
    { "+Inf transparent as NaN", "if (isnan(scalar))", "if (isnan(scalar) || isinf(scalar))" },
  };
  for (const auto& wrong : wrongRules)
  {
    shader->AddFragmentShaderReplacement(wrong.From, false, wrong.To, false);
    const double off = worst(RenderAsSet(gpu), nanColumn, infColumn);
    shader->ClearAllFragmentShaderReplacements();
    Check(off > 2.0 * bound,
      std::string("the shader with ") + wrong.What + ": " + Fixed(off) + " levels off (rejected)");
  }
}

void TestMissingDataInOtherModes()
{
  std::cout << "NaN slab with iso-surfaces and maximum intensity\n";
  // f = z on 16^3 cells, a NaN slab one cell thick at z in [1/2, 9/16) where x in [1/4, 1/2),
  // y < 1/2 (the slab region); parallel view down -z, 64 px.
  Hierarchy h;
  h.Spacing0 = glm::dvec3(1.0 / 16.0);
  h.ArrayName = "height";
  const auto inRegion = [](double x, double y) { return x > 0.25 && x < 0.5 && y < 0.5; };
  AddGrid(h, 0, Cube(0, 16),
    [&](const glm::dvec3& p)
    {
      return p.z > 0.5 && p.z < 0.5625 && inRegion(p.x, p.y)
        ? std::numeric_limits<float>::quiet_NaN()
        : static_cast<float>(p.z);
    });
  const auto worst = [&](const Image& img, const glm::dvec3& slab, const glm::dvec3& elsewhere)
  {
    double w = 0.0;
    for (int j = 0; j < img.Height; ++j)
    {
      for (int i = 0; i < img.Width; ++i)
      {
        const glm::vec4& p = img.Pixels[static_cast<std::size_t>(j) * img.Width + i];
        const bool region = inRegion((i + 0.5) / img.Width, (j + 0.5) / img.Height);
        const glm::dvec3 e = region ? slab : elsewhere;
        for (int c = 0; c < 3; ++c)
        {
          w = std::max(w, 255.0 * std::abs(static_cast<double>(p[c]) - e[c]));
        }
      }
    }
    return w;
  };
  const double bound = 1.0;

  // iso-surfaces at 0.3 (red) and 0.53 (green), each half opaque: the pair of samples around the
  // slab (0.594 and 0.469, the NaN cell between them) is broken, so 0.53 is not drawn through the
  // slab region; 0.3 is drawn everywhere. Down -z the ray meets 0.53 first.
  RenderSettings iso;
  iso.Width = iso.Height = 64;
  iso.View = TopView(true);
  iso.Blend = BlendMode::IsoSurface;
  iso.IsoValues = { 0.3, 0.53 };
  iso.Transfer.Color = { { 0.295, { 1.0, 0.0, 0.0 } }, { 0.305, { 1.0, 0.0, 0.0 } },
    { 0.525, { 0.0, 1.0, 0.0 } }, { 0.535, { 0.0, 1.0, 0.0 } } };
  iso.Transfer.Opacity = { { 0.295, 0.5 }, { 0.535, 0.5 } };
  iso = WithCaster(iso);
  const glm::dvec3 red(1.0, 0.0, 0.0), green(0.0, 1.0, 0.0);
  const glm::dvec3 redOnly = 0.5 * red, both = 0.5 * green + 0.25 * red;
  SinglePassRenderer isoGpu(h, iso, SettingsCamera());
  const double isoOff = worst(RenderAsSet(isoGpu), redOnly, both);
  Check(isoOff <= bound,
    "iso-surfaces: the crossing across the NaN slab is not drawn, the others are: every pixel "
    "within " +
      Fixed(isoOff) + " levels (bound " + Fixed(bound) + ")");
  if (Caster == RayCaster::Fragment)
  {
    const double reference = worst(RenderReference(h, iso), redOnly, both);
    const double mirror =
      worst(RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), iso), redOnly, both);
    Check(reference <= bound && mirror <= bound,
      "iso-surfaces: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels (bound " + Fixed(bound) + ")");
  }
  if (vtkOpenGLShaderProperty* shader = ShaderProperty(isoGpu))
  {
    // the wrong rule: a NaN sample leaves the pairing as it was
    shader->AddFragmentShaderReplacement("    amrspHavePrevious = false;\n#endif\n    return true;",
      false, "#endif\n    return true;", false);
    const double off = worst(RenderAsSet(isoGpu), redOnly, both);
    shader->ClearAllFragmentShaderReplacements();
    Check(off > 4.0 * bound,
      "the shader pairing samples across NaN: " + Fixed(off) + " levels off (rejected)");
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }

  // maximum intensity seen from below, grey levels 0 to 1 at opacity 1: the maximum along every
  // ray is the top cell's 31/32, the NaN samples skipped on the way (the slab region the same)
  RenderSettings mip = iso;
  mip.View.Position = glm::dvec3(0.5, 0.5, -4.0);
  mip.Blend = BlendMode::Maximum;
  mip.IsoValues.clear();
  mip.Transfer.Color = { { 0.0, glm::dvec3(0.0) }, { 1.0, glm::dvec3(1.0) } };
  mip.Transfer.Opacity = { { 0.0, 1.0 }, { 1.0, 1.0 } };
  const glm::dvec3 top(31.0 / 32.0);
  SinglePassRenderer mipGpu(h, mip, SettingsCamera());
  const double mipOff = worst(RenderAsSet(mipGpu), top, top);
  Check(mipOff <= bound,
    "maximum intensity with NaN samples: every pixel within " + Fixed(mipOff) + " levels of " +
      "the top cell's value (bound " + Fixed(bound) + ")");
  if (Caster == RayCaster::Fragment)
  {
    const double reference = worst(RenderReference(h, mip), top, top);
    const double mirror = worst(RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), mip), top, top);
    Check(reference <= bound && mirror <= bound,
      "maximum intensity: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels (bound " + Fixed(bound) + ")");
  }
  if (vtkOpenGLShaderProperty* shader = ShaderProperty(mipGpu))
  {
    shader->AddFragmentShaderReplacement(
      "return true; // missing data is transparent", false, "return false;", false);
    const double off = worst(RenderAsSet(mipGpu), top, top);
    shader->ClearAllFragmentShaderReplacements();
    Check(off > 4.0 * bound,
      "the shader ending the ray at a NaN sample: " + Fixed(off) + " levels off (rejected)");
  }
  else
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
  }
}

} // namespace

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode != "lod" && mode != "iso" && mode != "nan")
  {
    std::cerr << "usage: TestAnalyticImages lod|iso|nan\n";
    return 2;
  }
  std::string why;
  if (!GpuRenderer::Available(why))
  {
    return mappertest::SkipOrFail(why);
  }
  try
  {
    // every check with each caster (vtkSinglePassAMRVolumeMapper::RayCaster)
    for (RayCaster caster : { RayCaster::Fragment, RayCaster::Compute })
    {
      Caster = caster;
      std::cout << "cast by the " << RayCasterName(caster) << " shader\n";
      if (mode == "lod")
      {
        TestLevelOfDetail();
      }
      else if (mode == "iso")
      {
        TestIsoSurfaces();
        TestIsoLayers();
      }
      else
      {
        TestNaN();
        TestMissingAndInfiniteSlabs();
        TestMissingDataInOtherModes();
      }
    }
  }
  catch (const std::exception& e)
  {
    std::cout << "  FAILED  " << e.what() << "\n";
    return 1;
  }
  return Failures() == 0 ? 0 : 1;
}
