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

/// Where a sample lies in its step: sample k of a segment's n equal steps of length dt is at
/// t0 + (k + SampleOffset) dt. Not the midpoint: a segment that enters and leaves a node through
/// faces of one axis and spans an even number of cells along it would put its middle sample
/// exactly on a cell face, where the last bit of the position (which a compiler's contraction,
/// order of operations or approximate division decides) would pick the cell, and with it the
/// value and the gradient's stencil. This offset (about 0.5 - 0.0381966) is the float
/// 15495551 / 2^25: a sample lands on a face only where a node spans a multiple of 2^25 cells
/// along the axis, which no texture allows (Core.SampleStep.NoSampleSitsExactlyOnACellFace);
/// near a face it lands as often as any position would. The kD-tree
/// integrators and both shaders (Shaders/RaySteps.glsl, Shaders/MultiPassAMR.frag.glsl, written
/// there as the same literal) use it.
constexpr float SampleOffset = 0.4618034f;

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
