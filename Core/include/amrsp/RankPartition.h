// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Splitting a hierarchy's domain into convex regions, one per parallel rank, for sort-last
/// rendering: each rank renders the part of every level inside its region, and the ranks' images
/// composite in visibility order because the regions are disjoint boxes (the cells of a kD-tree).

#include "amrsp/Hierarchy.h"

#include <vector>

namespace amrsp
{

/// Splits h.RootCells() into `parts` disjoint boxes of level-0 cells whose union is the root box.
/// Recursive bisection: a box for n parts is cut by one level-0 cell plane, perpendicular to its
/// longest world-space axis, into boxes for floor(n/2) and ceil(n/2) parts, at the plane whose
/// share of the box's cells (all levels, each grid clipped to the box; a fine cell counts as one)
/// is nearest to floor(n/2)/n. Because the planes are level-0 cell planes they are cell planes of
/// every level, so clipping a grid to a region never splits a cell.
/// A box that cannot be cut (one cell thick along every axis) keeps its cells in its first part;
/// the other parts are empty boxes. Precondition: parts >= 1 and the hierarchy has a level-0 grid.
/// Deterministic: every rank computing it from the same boxes gets the same regions.
std::vector<Box> PartitionRootBox(const Hierarchy& h, int parts);

/// `region` (level-0 cells) in the cells of `level`, intersected with `cells` (a box of that
/// level): the part of a grid a region's rank renders. Empty when they do not overlap.
Box ClipToRegion(const Hierarchy& h, const Box& cells, int level, const Box& region);

/// Ghost width of `level` around a region, in cells of that level per axis: two cells of the next
/// coarser level (two cells for level 0). Samples near a region face read data up to two cells
/// of their own level away (smooth corners and gradient neighbours), and under proper nesting
/// the coarsest samples next to level-l data are of level l - 1.
glm::i64vec3 RegionGhostWidth(const Hierarchy& h, int level);

/// The part of a grid (`cells`, a box of `level`) that the rank of `region` (level-0 cells) needs
/// when it clips its rays to the region: the region grown by RegionGhostWidth and intersected
/// with the grid. Empty when the grid is farther away.
Box GhostedPiece(const Hierarchy& h, const Box& cells, int level, const Box& region);

} // namespace amrsp
