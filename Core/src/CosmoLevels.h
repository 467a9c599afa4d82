// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Private to the synthetic cosmology generator (CosmoHierarchy.cxx): its portable arithmetic,
/// its thread counts, the root-grid split, the grid counts per level and the builder of one
/// refined level. Everything that decides the structure goes through the portable arithmetic,
/// so the hierarchy does not depend on the C library or the number of threads.

#include "amrsp/Hierarchy.h"
#include "amrsp/SyntheticCosmo.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace amrsp
{
namespace cosmo
{

/// Fraction of level-0 cells that the cell budget model gives to level 1, in units of the domain
/// volume: level 1 refines about this fraction of the domain.
constexpr double Level1VolumeFraction = 0.1;
/// Ratio of grid counts of consecutive refined levels (geometric distribution over levels).
constexpr double GridCountRatio = 0.75;
/// A level never covers more than this fraction of its parent level's volume.
constexpr double MaxVolumeFraction = 0.3;

/// Cube root of x > 0 by a fixed number of Newton steps from a power-of-two start (frexp and
/// ldexp are exact), so the result does not depend on the C library's cbrt.
double CubeRoot(double x);

/// The integer n >= 1 whose cube is nearest to x (x >= 1), by integer bisection.
int64_t NearestIntegerCubeRoot(int64_t x);

/// Worker threads of the generator: one per core, at most 64.
int CosmoWorkers();

/// Workers for `n` items of which each should get at least `minPerWorker` (1 for small n).
int SliceWorkers(int64_t n, int64_t minPerWorker);

/// Splits `box` into `count` boxes by recursive bisection of the longest axis, cutting in
/// proportion to the counts on either side. Appends in a deterministic order.
void SplitDomain(const Box& box, int64_t count, std::vector<Box>& out);

/// Grid counts of levels 1..levels-1: at least one each, the rest geometric, rounded so that they
/// sum to `total` exactly.
std::vector<int64_t> GridsPerRefinedLevel(int64_t total, int levels);

/// Builds the refined levels one after the other, each nested in the one before; its scratch
/// arrays and the tile-size guess carry from level to level.
class RefinedLevelBuilder
{
public:
  explicit RefinedLevelBuilder(const CosmoField& field);
  ~RefinedLevelBuilder();

  /// One refined level with exactly `grids` boxes (when the parents have room) holding about
  /// `targetCells` cells, every box inside one of `parents` (refined to this level) and disjoint
  /// from the others; `cellSize` is the world size of a cell of this level. Empty when the
  /// parents have no room.
  std::vector<Box> Build(
    const std::vector<Box>& parents, double cellSize, int64_t grids, int64_t targetCells);

private:
  struct Internals;
  std::unique_ptr<Internals> I;
};

} // namespace cosmo
} // namespace amrsp
