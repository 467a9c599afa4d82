// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The level-by-level kD-tree decomposition of an AMR hierarchy into non-overlapping blocks of
/// same-level cells (Kaehler & Abel 2013, section 4.1).

#include "amrsp/Hierarchy.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace amrsp
{

/// The paper's node types, plus empty leaves (regions of the root box no grid covers).
enum class NodeType : std::uint8_t
{
  Refined, ///< (a) inner node whose region lies in one grid and is refined everywhere (LOD stop)
  Leaf,    ///< (b) leaf covered by cells of exactly one grid, the finest available there
  Mixed,   ///< (c) inner node covering refined and unrefined cells (traversal only)
  Empty    ///< leaf outside every grid
};

struct KdNode
{
  /// Region in cells of the hierarchy's finest level (exact for any ratios).
  Box Region;
  /// Leaves: the data level. Inner nodes: the split level, whose cell faces the plane lies on.
  int Level = 0;
  /// Split axis 0..2 for inner nodes, -1 for leaves.
  int Axis = -1;
  /// Split position in cells of `Level`, relative to the region's lower corner (inner nodes).
  int64_t Split = 0;
  /// Index of the first child; the second is FirstChild + 1. -1 for leaves.
  int32_t FirstChild = -1;
  /// Grid whose cells this node shows (types (a) and (b)); -1 otherwise.
  int32_t Grid = -1;
  NodeType Type = NodeType::Empty;

  bool IsLeaf() const { return FirstChild < 0; }
  bool HasData() const { return Grid >= 0; }
};

struct KdTreeStatistics
{
  int64_t Nodes = 0;
  int64_t DataNodes = 0; ///< types (a) + (b)
  int64_t Refined = 0;   ///< type (a)
  int64_t Leaves = 0;    ///< type (b)
  int64_t Mixed = 0;     ///< type (c)
  int64_t Empty = 0;
  int Depth = 0;
};

/// A kD-tree over the hierarchy. Nodes[0] is the root, the bounding box of the level-0 grids.
/// Children are stored in pairs (FirstChild, FirstChild + 1) in breadth-first order.
struct KdTree
{
  std::vector<KdNode> Nodes;
  int FinestLevel = 0;

  const KdNode& Root() const { return Nodes.front(); }
  KdTreeStatistics Statistics() const;
};

/// Thrown for hierarchies the builder cannot decompose (no level-0 grid, inconsistent levels).
class HierarchyError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Builds the tree. Grids of level l are merged into the leaves of the tree built from levels
/// 0..l-1; each leaf is split by the axis-aligned plane on a level-l cell face with the fewest
/// grid-box intersections that leaves cells on both sides (ties: the most balanced count of grid
/// cells, then of node cells, then the lower axis, then the lower position), until every node is
/// covered by one grid or by none. Cells of grids outside the root box are ignored.
KdTree BuildKdTree(const Hierarchy& h);

/// Converts a finest-level box of `tree` to level-0 index units (lower, upper corner).
glm::dvec3 RegionLoIndex(const Hierarchy& h, const KdTree& tree, const Box& region);
glm::dvec3 RegionHiIndex(const Hierarchy& h, const KdTree& tree, const Box& region);

} // namespace amrsp
