// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Structural checks of a kD-tree against the hierarchy it was built from, and of its encoding.
/// Used by the tests and reported by `amrsp inspect` (field "invariants").

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include <string>
#include <vector>

namespace amrsp
{

struct InvariantReport
{
  bool Ok = true;
  std::vector<std::string> Failures; ///< the first few failures, each naming the node
  std::size_t FailureCount = 0;

  void Fail(const std::string& what);
};

/// Checks that
/// - the root is the bounding box of the level-0 grids;
/// - every inner node's two children split its region exactly, on a face of its split level
///   strictly inside it (so the leaves tile the root box with no gap and no overlap);
/// - every leaf with data lies inside its grid, and no grid of a finer level overlaps it
///   (it shows the finest cells available there); every empty leaf overlaps no grid;
/// - every type (a) node lies inside its grid and only finer levels are shown below it;
/// - decoding the encoding gives back the same nodes (when `encoded` is given).
InvariantReport CheckKdTree(
  const Hierarchy& h, const KdTree& tree, const EncodedKdTree* encoded = nullptr);

} // namespace amrsp
