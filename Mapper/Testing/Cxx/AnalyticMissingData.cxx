// SPDX-License-Identifier: BSD-3-Clause
// NaN and infinite cells: a column and slabs, composites from the segment lengths
// (TestAnalyticImages.cxx's header says what is checked).
#include "AnalyticScenes.h"

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

namespace analytic
{
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
    const double mirror = worst(MirrorImage(h, s), nanColumn, infColumn);
    Check(reference <= bound && mirror <= bound,
      "CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels from the same (bound " + Fixed(bound) + ")");
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
    const double off = worst(RenderWithWrongRule(gpu, wrong.From, wrong.To), nanColumn, infColumn);
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
    const double mirror = worst(MirrorImage(h, iso), redOnly, both);
    Check(reference <= bound && mirror <= bound,
      "iso-surfaces: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels (bound " + Fixed(bound) + ")");
  }
  // the wrong rule: a NaN sample leaves the pairing as it was
  const double unbroken =
    worst(RenderWithWrongRule(isoGpu, "    amrspHavePrevious = false;\n#endif\n    return true;",
            "#endif\n    return true;"),
      redOnly, both);
  Check(unbroken > 4.0 * bound,
    "the shader pairing samples across NaN: " + Fixed(unbroken) + " levels off (rejected)");

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
    const double mirror = worst(MirrorImage(h, mip), top, top);
    Check(reference <= bound && mirror <= bound,
      "maximum intensity: CPU reference " + Fixed(reference) + ", CPU mirror " + Fixed(mirror) +
        " levels (bound " + Fixed(bound) + ")");
  }
  const double ended = worst(
    RenderWithWrongRule(mipGpu, "return true; // missing data is transparent", "return false;"),
    top, top);
  Check(ended > 4.0 * bound,
    "the shader ending the ray at a NaN sample: " + Fixed(ended) + " levels off (rejected)");
}

} // namespace analytic
