// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The sampling distance of each level: a ray segment through data of level d is sampled every
/// D = factor x (smallest world-space edge of a level-d cell) or less (the segment is cut into
/// max(1, ceil(length / D)) equal steps). The kD-tree integrator (SampleDistanceFactor), the
/// reference (ReferenceSampleFactor) and the GPU mappers (RayCastingData::LevelMinEdge times
/// their SampleDistanceFactor) all derive their steps here; world units throughout.

#include "amrsp/Hierarchy.h"

#include <glm/glm.hpp>

#include <algorithm>

namespace amrsp
{

/// The smallest world-space edge of a cell of `level`: min over the axes of
/// Spacing0 * CellSize(level).
inline double LevelMinEdge(const Hierarchy& h, int level)
{
  const glm::dvec3 edge = h.Spacing0 * h.CellSize(level);
  return std::min(edge.x, std::min(edge.y, edge.z));
}

/// The sampling distance D of a level whose smallest cell edge is `levelMinEdge`.
inline double LevelSampleStep(double factor, double levelMinEdge)
{
  return factor * levelMinEdge;
}

/// The sampling distance D of `level` of `h`.
inline double LevelSampleStep(const Hierarchy& h, int level, double factor)
{
  return LevelSampleStep(factor, LevelMinEdge(h, level));
}

} // namespace amrsp
