// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The scenes and helpers of the analytic image tests (TestAnalyticImages.cxx, whose header says
// what each mode checks): hand-made grids, the views, the caster of the run, and the wrong-rule
// renders (a shader replacement) each check must reject.

#include "AmrspSinglePass.h"
#include "MapperTestHelpers.h"

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/Render.h"

#include "vtkOpenGLShaderProperty.h"
#include "vtkSinglePassAMRVolumeMapper.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace analytic
{
using namespace amrsp;
using namespace amrsp::harness;
using mappertest::Check;
using mappertest::Fixed;
using mappertest::ShaderProperty;

/// A grid of `level` over `cells` whose every cell holds value(its centre, world units).
inline void AddGrid(
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

inline Box Cube(int64_t lo, int64_t hi)
{
  return Box{ glm::i64vec3(lo), glm::i64vec3(hi) };
}

/// The view down -z onto the unit cube: parallel (the square fills the image) or perspective
/// from `distance` above the cube's top with the full vertical angle `angle`.
inline Camera TopView(bool parallel, double distance = 0.0, double angle = 30.0)
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
inline RayCaster Caster = RayCaster::Fragment;

/// `s` with this run's caster.
inline RenderSettings WithCaster(RenderSettings s)
{
  s.GpuRayCaster = Caster;
  return s;
}

/// Renders `h` with `s` (its camera as it is) and returns the frame; a frame cast by another
/// caster than this run's is a failed check.
inline Image RenderAsSet(SinglePassRenderer& gpu)
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

inline ViewAngles SettingsCamera()
{
  ViewAngles v;
  v.UseSettingsCamera = true;
  return v;
}

/// The largest channel difference (0-255) between `image` and the colour `expected` over every
/// pixel.
inline double LargestDifference(const Image& image, const glm::dvec3& expected)
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

/// The CPU mirror's (kD-tree integrator's) image of `h` with `s`.
inline Image MirrorImage(const Hierarchy& h, const RenderSettings& s)
{
  return RenderKdTree(h, EncodeKdTree(h, BuildKdTree(h)), s);
}

/// The frame of `gpu` with one replacement in its shader (a wrong rule), removed afterwards; a
/// volume without a shader property is a failed check (and an empty frame).
inline Image RenderWithWrongRule(
  SinglePassRenderer& gpu, const std::string& from, const std::string& to)
{
  vtkOpenGLShaderProperty* shader = ShaderProperty(gpu);
  if (!shader)
  {
    Check(false, "the volume has a vtkOpenGLShaderProperty");
    return Image();
  }
  shader->AddFragmentShaderReplacement(from, false, to, false);
  Image image = RenderAsSet(gpu);
  shader->ClearAllFragmentShaderReplacements();
  return image;
}

// the modes' checks (AnalyticLevelOfDetail.cxx, AnalyticIsoSurfaces.cxx, AnalyticMissingData.cxx)
void TestLevelOfDetail();
void TestIsoSurfaces();
void TestIsoLayers();
void TestNaN();
void TestMissingAndInfiniteSlabs();
void TestMissingDataInOtherModes();

} // namespace analytic
