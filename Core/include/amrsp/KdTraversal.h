// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// CPU kd-restart traversal of the ENCODED tree (Kaehler & Abel 2013, section 4.3). It reads only
/// the tree and data-nodes texels and mirrors the GLSL raycaster step for step (float arithmetic,
/// same plane and tie rules), so tests of it test the encoding and the shader's logic.

#include "amrsp/KdTreeEncoding.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

/// One ray segment inside one kD node, front to back.
struct RaySegment
{
  float T0 = 0.0f;
  float T1 = 0.0f;
  uint32_t Node = 0;        ///< linear tree-texel index
  uint32_t Data = 0;        ///< data-nodes index; 0 for empty space
  int Level = 0;            ///< data level (of the grid sampled); -1 for empty space
  glm::vec3 NodeLo{ 0.0f }; ///< the node's box in level-0 index units, as the shader computes it
  glm::vec3 NodeHi{ 0.0f };
  uint32_t Descent = 0; ///< tree levels descended by the restart that found this segment
  /// The restart started at the far child of the previous descent (the shader fetches that
  /// node's texel; a restart from the restart node reuses the texel it keeps).
  bool FromFar = false;
  /// Level-of-detail tests of that descent that read a data node (inner nodes with data while
  /// LevelOfDetail::ThresholdPixels > 0).
  uint32_t LodChecks = 0;
  /// The descent began at the rope of the previous segment's leaf (amrsp/KdTreeRopes.h): the
  /// shader fetched that rope and the target's box and tree texels.
  bool FromRope = false;
};

/// Level-of-detail selection at type (a) nodes: the traversal stops descending when one cell of
/// the node's data level projects to fewer than ThresholdPixels pixels at the segment's entry.
struct LevelOfDetail
{
  float ThresholdPixels = 0.0f;      ///< 0 disables LOD (always the finest level)
  float PixelSizePerDistance = 0.0f; ///< perspective: world size of a pixel at distance 1
  float ParallelPixelSize = 0.0f;    ///< parallel projection: world size of a pixel (used if > 0)
  glm::vec3 Spacing0{ 1.0f };        ///< world size of a level-0 cell
};

/// Ray: origin + t * direction in level-0 index units. When direction is a unit world direction
/// divided by the level-0 spacing, t is the world distance. Appends the segments of [tMin, tMax]
/// that lie inside the root box; empty-space segments are included (Data == 0).
/// Where the tree has ropes (EncodedKdTree::Ropes), `ropes` is set and level of detail is off, a
/// ray that leaves a leaf through exactly one face descends from that face's rope; otherwise each
/// restart descends from the far child of the deepest split plane the previous descent crossed,
/// or else from the deepest node whose box holds the rest of the ray (push-down), as the shader.
/// restartFromRoot = true descends from the root every time (the paper's plain kd-restart).
/// All give the same segments.
void TraverseKdTree(const EncodedKdTree& tree, const glm::vec3& origin, const glm::vec3& direction,
  float tMin, float tMax, const LevelOfDetail& lod, std::vector<RaySegment>& segments,
  bool restartFromRoot = false, bool ropes = true);

/// Slab test of a ray against a box; returns false when they miss. Mirrors the shader.
bool IntersectBox(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& origin,
  const glm::vec3& direction, float& tEnter, float& tExit);

} // namespace amrsp
