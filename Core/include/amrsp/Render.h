// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The two CPU integrators, with the conventions the mapper uses so that images can be compared
/// (camera: amrsp/Camera.h; transfer function: amrsp/TransferFunction.h; what a render is asked
/// to do: amrsp/RenderSettings.h):
///
/// - Emission-absorption, front to back, premultiplied: C += (1 - A) a c; A += (1 - A) a, where a
///   sample that represents a ray length dt has a = 1 - (1 - opacity(s))^(dt / UnitDistance)
///   (vtkVolumeProperty's ScalarOpacityUnitDistance). The pixel is C + (1 - A) * Background.
/// - Sampling rule of the kD-tree integrator (and of the GPU shader): a segment of data level d,
///   [t0, t1], is cut into n = max(1, ceil((t1 - t0) / D)) equal steps, D = SampleDistanceFactor
///   times the smallest world-space edge of a level-d cell (LevelSampleStep, amrsp/SampleStep.h);
///   sample k sits at t0 + (k + SampleOffset) dt, just before the step's midpoint (never exactly
///   on a cell face: amrsp/SampleStep.h). Cell-centred data is sampled nearest-cell.
/// - Reference integrator (amrsp/ReferenceRender.h): no kD-tree and none of the kD-tree
///   integrator's rule code. It marches the root box with steps of ReferenceSampleFactor times
///   the smallest edge of the finest cell at the current point, found directly from the hierarchy
///   (finest grid containing the point), and samples step midpoints.

#include "amrsp/BrickAtlas.h"
#include "amrsp/FinestCellLocator.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/Image.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/ReferenceRender.h"
#include "amrsp/RenderSettings.h"
#include "amrsp/Shading.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

/// The kD-tree integrator's point lookup (mirrors the shader's amrspSampleAtPoint): descends the
/// encoded tree from the root to the leaf containing p (level-0 index units; the lower child when
/// p[axis] < the node's float split plane) and samples that leaf's grid as the integrator does.
/// Returns NaN outside the root box or in a leaf without data; cellSize is the leaf's data-level
/// cell size (level-0 index units).
double SampleKdTreeAtPoint(
  const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p, glm::vec3& cellSize);

/// The kD-tree integrator's point lookup for the shading rules (PointLookup): point location in
/// the encoded tree (as the shader's amrspLocateDataNode; outside the root box or in a leaf without
/// data: NaN), then the leaf's brick, read from the grid or, with `atlas`, through the data node's
/// atlas offset; cellSize: the leaf's data-level cell size. `smooth` (cell-centred data only):
/// the smooth reconstruction of RenderSettings::SmoothCellData at the leaf's level, as the
/// sample loop computes it (the gradient's neighbours under SmoothCellData); otherwise the same
/// value as SampleKdTreeAtPoint. The lookup refers to h, tree and atlas, which must outlive it.
PointLookup KdTreePointLookup(
  const Hierarchy& h, const EncodedKdTree& tree, bool smooth, const BrickAtlas* atlas = nullptr);

/// Renders with the CPU kD-tree integrator over the encoded textures. Without `atlas`, samples
/// come from the grid named by each data node; with it, from the packed atlas through the data
/// nodes' atlas offsets, exactly as the packing shader addresses it (the tree must then have been
/// encoded with that atlas's origins). A NaN sample is transparent.
Image RenderKdTree(const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s,
  const BrickAtlas* atlas = nullptr);
/// The scalar the kD-tree integrator samples at p (level-0 index units; cell-centred data),
/// nearest-cell or smooth (RenderSettings::SmoothCellData), at the finest level there. NaN
/// outside every grid.
float SampleKdTreePoint(
  const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p, bool smooth);

/// The samples the kD-tree integrator takes along one world-space ray: position in level-0
/// index units (double, computed from the float segment bounds), the grid sampled and its cell.
struct TreeSample
{
  glm::dvec3 Position;
  int32_t Grid;
  glm::i64vec3 Cell;
};
void SampleRayKdTree(const Hierarchy& h, const EncodedKdTree& tree, const glm::dvec3& origin,
  const glm::dvec3& direction, double sampleDistanceFactor, std::vector<TreeSample>& samples);

} // namespace amrsp
