// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The independent CPU reference (Core/src/reference/): no kD-tree, the finest cell found from
/// the grids' boxes, and its own implementation of every rule (compositing, opacity correction,
/// blend modes, transfer functions, sampling, gradient, shading, shadows, iso-surfaces), written
/// apart from the kD-tree integrator that mirrors the shader. It marches the root box with steps
/// of ReferenceSampleFactor times the smallest edge of the finest cell at the current point and
/// samples the step midpoints (amrsp/Render.h states the conventions both follow).

#include "amrsp/FinestCellLocator.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/Image.h"
#include "amrsp/PointLookup.h"
#include "amrsp/RenderSettings.h"

namespace amrsp
{

/// Renders the independent reference. Any number of iso-values (the limit of 8 is the GPU's).
Image RenderReference(const Hierarchy& h, const RenderSettings& s);

/// The reference's point lookup: the finest grid containing the point, found by `locator` (no
/// kD-tree); NaN outside the root box and every grid; cellSize: that grid's cell size. `smooth`
/// (cell-centred data only): the reference's smooth reconstruction at the finest level there.
/// Refers to h and locator, which must outlive it.
PointLookup ReferencePointLookup(const Hierarchy& h, const FinestCellLocator& locator, bool smooth);

} // namespace amrsp
