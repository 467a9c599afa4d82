// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The multi-pass baseline's CPU build of the packing storage (paper, sections 4.1 and 5.1): a
/// converted hierarchy, its kD-tree, one brick per grid packed into one float atlas (or pages of
/// it), and what the shaders need about the levels. The single pass builds the same pieces inside
/// amrsp::PrepareRayCasting (amrsp/RayCastingData.h).

#include "amrsp/AtlasPages.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"

#include <cstdint>
#include <string>
#include <vector>

namespace amrsp
{

/// The hierarchy, its kD-tree and its packed atlas layout.
struct PackedHierarchy
{
  /// Grids, ratios, origin and spacing, and the values until the atlas holds them.
  Hierarchy Structure;
  KdTree Tree;
  /// Where each grid's brick lies in the atlas pages (usually one); Structure.Values are the
  /// bricks (borrowed from the input where possible), dropped by the caller after the upload.
  AtlasPages Atlas;
  bool VertexCentred = false; ///< vertex bricks (trilinear) instead of cell bricks (nearest)
  /// Smallest model-space edge of a cell of each level (the sampling rule's D for factor 1).
  std::vector<double> LevelMinEdge;
  /// Finite value range of the selected scalars ([0, 1] when there is none).
  double ScalarRange[2] = { 0.0, 1.0 };
  /// Model-space bounds of the root box [xmin, xmax, ymin, ymax, zmin, zmax].
  double Bounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
};

/**
 * Builds `out` from `converted`: the kD-tree and the bricks packed with the better packer within
 * `packLimit` texels per axis (0: the 2048 the data-node offsets address; a positive value lowers
 * it), over atlas pages of at most `maxPageTexels` texels (0: one atlas). With `mayRefresh` and
 * `converted` of `out`'s structure (amrsp::SameStructure), `out` keeps its tree and layout and
 * takes the new values and their range (`refreshed` true). Returns false with a one-line `error`
 * (tree or packing failure); `out` is then empty.
 */
bool PackHierarchy(Hierarchy converted, int packLimit, int64_t maxPageTexels, bool mayRefresh,
  PackedHierarchy& out, bool& refreshed, std::string& error);

} // namespace amrsp
