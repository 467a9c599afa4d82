// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Vertex-centred data (paper, section 5): values sit on grid vertices and are interpolated
/// trilinearly inside each brick. Adjacent bricks share the samples of their common faces; at a
/// coarse-fine interface the fine grid's "dangling" boundary vertices (those next to a cell that
/// no grid of the fine level covers) take the trilinear interpolation of the abutting coarser
/// data, so the field is continuous across grid and level boundaries.

#include "amrsp/Hierarchy.h"

namespace amrsp
{

/// Cell-centred values -> vertex-centred: each vertex takes the mean of the grid's cells that
/// touch it (1, 2, 4 or 8). NaN cells are left out of the mean (a vertex with only NaN cells stays
/// NaN). Sets VertexCentred, then calls MakeVertexDataContinuous.
void ConvertCellsToVertices(Hierarchy& h);

/// Replaces the value of every dangling vertex of every grid of level >= 1 by the trilinear
/// interpolation of the finest coarser grid containing it. Grids are processed coarse to fine, so
/// a fine grid interpolates already-corrected coarse data. Requires vertex-centred values.
void MakeVertexDataContinuous(Hierarchy& h);

/// Trilinear interpolation of grid `g`'s vertex values at `u`, in the grid's vertex coordinates
/// (vertex (i,j,k) at u = (i,j,k); u is clamped into the grid). Requires vertex-centred values.
float InterpolateVertices(const Hierarchy& h, int32_t g, glm::dvec3 u);

} // namespace amrsp
