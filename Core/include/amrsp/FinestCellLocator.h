// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The reference's tree-free lookup of the finest cell containing a point, and cell values.

#include "amrsp/Hierarchy.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

/// Finds the finest grid cell containing a point straight from the hierarchy's boxes (per-level
/// uniform buckets), with no kD-tree: the reference's independent lookup.
class FinestCellLocator
{
public:
  explicit FinestCellLocator(const Hierarchy& h);
  /// Point in level-0 index units. Returns the grid index (or -1 outside every grid) and the
  /// cell of that grid containing the point.
  int32_t Find(const glm::dvec3& p, glm::i64vec3& cell) const;

private:
  struct LevelBuckets
  {
    glm::dvec3 Lo{ 0.0 };
    glm::dvec3 BucketSize{ 1.0 };
    glm::ivec3 Count{ 0 };
    std::vector<std::vector<int32_t>> Grids;
  };
  const Hierarchy& H;
  std::vector<LevelBuckets> Levels;
  std::vector<glm::dvec3> CumRatio;
};

/// Value of grid `g` at cell `cell` (clamped into the grid). Requires cell-centred values.
float CellValue(const Hierarchy& h, int32_t g, glm::i64vec3 cell);

} // namespace amrsp
