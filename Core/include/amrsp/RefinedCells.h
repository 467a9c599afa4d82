// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Which cells of each grid a finer level refines: the input of VTK-style blanking (a
/// vtkGhostType REFINEDCELL mask), computed from the boxes alone in O(n log n) per level pair
/// and O(1) memory per box, independent of how far apart the grids lie in index space.

#include "amrsp/Hierarchy.h"

#include <vector>

namespace amrsp
{

/// For every grid g (same order as h.Grids), the boxes of g's cells, in cells of g's level and
/// clipped to g, that a grid of level g.Level + 1 overlaps. A partly overlapped coarse cell
/// counts as refined (the finer box is coarsened outward). Boxes of one grid may overlap each
/// other only where the finer grids' coarsened boxes do.
std::vector<std::vector<Box>> RefinedRegions(const Hierarchy& h);

/// The refined-cell mask of grid `grid` (x fastest, then y, then z; one byte per cell of the
/// grid, 1 = refined by the next level) from RefinedRegions' boxes for it.
std::vector<unsigned char> RefinedCellMask(const Box& grid, const std::vector<Box>& refined);

} // namespace amrsp
