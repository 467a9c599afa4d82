// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The CPU side of the multi-pass baseline (paper, section 6; vtkMultiPassAMRVolumeMapper): the
/// kD-tree's data leaves as draws, each with what its node shader needs, and their order front to
/// back for a view. No OpenGL: the mapper draws what these list.

#include "amrsp/AtlasPages.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

/// Everything one draw needs about its data node (the per-node uniforms).
struct NodeDraw
{
  /// The node's box in level-0 index units, computed from the root down in float exactly as the
  /// single-pass shader computes it during its traversal (plane = lo + split * cell size).
  float Lo[3];
  float Hi[3];
  /// Size of a cell of the node's data level, level-0 index units (float, as the shaders').
  float CellSize[3];
  int Level = 0;
  /// First and last cell of the node in its level's index space (exact: floor and ceiling of the
  /// node's finest-cell box), and the atlas texel holding FirstCell.
  int FirstCell[3];
  int LastCell[3];
  int AtlasOffset[3];
  int Page = 0; ///< the atlas page (texture) holding the node's brick
};

/// The draws of a tree: one per leaf with data.
struct MultiPassNodes
{
  std::vector<NodeDraw> Draws;
  std::vector<int32_t> DrawOfNode; ///< kD node index -> index into Draws, -1 for none
  long long DataNodes = 0;         ///< nodes with data, types (a) and (b)
};

/// The draws of `tree` over `h`, whose bricks `atlas` places.
MultiPassNodes ListMultiPassNodes(const Hierarchy& h, const KdTree& tree, const AtlasPages& atlas);

/**
 * The draws of `nodes` front to back (indices into nodes.Draws) for rays from `eye` (model
 * coordinates), or, with `parallel`, along `direction` (model coordinates; only its signs
 * matter). Any ray from the eye that crosses a split plane goes from the eye's side to the
 * other, so visiting the eye's side first orders every ray's segments front to back.
 */
std::vector<int32_t> OrderFrontToBack(const Hierarchy& h, const KdTree& tree,
  const MultiPassNodes& nodes, const glm::dvec3& eye, const glm::dvec3& direction, bool parallel);

} // namespace amrsp
