// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Neighbour links ("ropes", Popov et al., Eurographics 2007) of the encoded kD-tree: for every
/// node and each of its six faces, the deepest node whose box holds the whole face seen from
/// outside. A ray that leaves a leaf through one face continues from that node instead of
/// descending again from the restart node or the far child (kd-restart), which saves most of the
/// descent (amrsp/WorkCounters.h counts it). Layout: Shaders/KdTreeLayout.glsl.
///
/// The traversal takes a rope target's box as float(box in finest cells) * FinestCellSize,
/// while a descent from the root sums split planes in float. The ropes are encoded only where the
/// two agree bit for bit for every node (refinement by powers of two and root boxes within 2^24
/// finest cells), so both paths cut segments at identical planes; elsewhere the texture is empty
/// and the traversal restarts as before.

#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include <cstdint>
#include <vector>

namespace amrsp
{

/// The rope of every node across each face, 0 for faces on the root box: ropes[6 n + 2 a + s]
/// for axis a and side s (0 lower, 1 upper). Built top-down: a child inherits its parent's ropes
/// and gets its sibling across the split; each rope then moves down through nodes whose split
/// plane leaves the whole face on one side.
std::vector<uint32_t> ComputeKdTreeRopes(const KdTree& tree);

/// The rope texture of `encoded` (its tree, root box, cell sizes and FinestCellSize), or an empty
/// one where a rope target's box would not equal the box a descent from the root computes.
UInt4Texture3D EncodeKdTreeRopes(const KdTree& tree, const EncodedKdTree& encoded);

} // namespace amrsp
