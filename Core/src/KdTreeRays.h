// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// One frame of the CPU kD-tree integrator, ray by ray: what RenderKdTree prepares once per frame
/// and the integration of one pixel's ray, so that the work counters (WorkCounters.cxx) run the
/// same rays tile by tile. Internal to the core library.

#include "amrsp/BrickAtlas.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/RenderSettings.h"
#include "amrsp/Shading.h"
#include "amrsp/WorkCounters.h"

#include <glm/glm.hpp>

#include <vector>

namespace amrsp
{
namespace integration
{

class KdTreeRays
{
public:
  /// The frame `s` over `tree` (samples from the grids, or from `atlas` through the data nodes'
  /// offsets). h, tree, s and atlas must outlive this object.
  KdTreeRays(const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s,
    const BrickAtlas* atlas);
  KdTreeRays(const KdTreeRays&) = delete;
  KdTreeRays& operator=(const KdTreeRays&) = delete;

  /// The colour of pixel (i, j) (column, row from the bottom). Adds the ray's work to `stats`
  /// and, when `work` is set, replaces its content with the ray's segment-loop iterations up to
  /// the one where it stopped. `segments` is scratch space.
  glm::vec4 Pixel(int i, int j, std::vector<RaySegment>& segments, RenderStats& stats,
    std::vector<SegmentWork>* work) const;

private:
  const Hierarchy& H;
  const EncodedKdTree& Tree;
  const RenderSettings& S;
  const BrickAtlas* Atlas;
  LevelOfDetail Lod;
  std::vector<float> StepOfLevel; ///< sampling distance per level, model units (float)
  glm::vec3 Spacing;
  glm::vec3 WorldOrigin;
  bool Skip;                     ///< empty-space skipping (composite only)
  std::vector<char> Transparent; ///< per data node, under Skip
  std::vector<double> IsoValues;
  bool Shaded;
  bool SmoothCells;
  PointLookup Lookup;
  ShadingContext Shading;
};

} // namespace integration
} // namespace amrsp
