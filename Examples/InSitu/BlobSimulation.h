// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlobSimulation.h
 * @brief A small AMR simulation for the in-situ example: Gaussian blobs carried around the
 * z axis of the unit cube, refined where the field is steep, regridded every few steps, its
 * blocks shared out among MPI ranks. Plain C++: no VTK, no MPI calls.
 *
 * The field at time t is the sum of the blobs, each an amplitude times exp(-r^2 / (2 w^2)) around
 * a centre that turns about the cube's vertical axis at its own angular speed (radians per unit
 * time): the exact solution of advecting the initial blobs with that rotation. Each step every
 * rank computes the cell-centre values of the blocks it owns.
 *
 * Index space: level l has (BaseCells * 2^l)^3 cells of edge 1 / (BaseCells * 2^l); a block is
 * a box of cells [Lo, Lo + Cells) of its level. Level 0 is cut into cubes of BaseBlockCells;
 * the levels above are unions of cubes of TileCells cells kept where the level below is steep
 * (see Regrid). Every rank computes the same hierarchy from the same time and configuration:
 * ranks exchange no metadata.
 */
#ifndef BlobSimulation_h
#define BlobSimulation_h

#include <array>
#include <cstdint>
#include <vector>

namespace insitu
{

struct SimulationConfig
{
  int BaseCells = 32;      ///< level-0 cells per axis
  int BaseBlockCells = 16; ///< level-0 block edge, in cells (divides BaseCells)
  int TileCells = 8;       ///< edge of the blocks above level 0, in their level's cells (even)
  int Levels = 3;          ///< levels, refinement ratio 2 between neighbours
  int RegridInterval = 3;  ///< steps between regrids
  double TimeStep = 0.05;  ///< time per step
  /// A cell is refined where its value changes by more than this between neighbours, i.e.
  /// |grad f| * cell edge > RefineThreshold.
  double RefineThreshold = 0.04;
};

/// One block: its level, first cell and cells per axis in that level's index space, the rank
/// that owns it, and (on that rank only) its values, x fastest.
struct Block
{
  int Level = 0;
  std::array<int, 3> Lo{};
  std::array<int, 3> Cells{};
  int Owner = 0;
  std::vector<float> Values; ///< cell-centre values on the owner, empty elsewhere
};

class BlobSimulation
{
public:
  BlobSimulation(const SimulationConfig& config, int rank, int ranks);

  /// Advances one step: moves the blobs, regrids every RegridInterval steps, recomputes the
  /// owned blocks' values.
  void Step();

  int StepIndex() const { return this->StepCount; }
  double Time() const { return this->StepCount * this->Config.TimeStep; }
  bool RegriddedLastStep() const { return this->Regridded; }
  /// Every block of every level, level by level; Values filled where Owner is this rank.
  const std::vector<Block>& Blocks() const { return this->Hierarchy; }
  /// The same, writable: an adaptor hands the values to VTK arrays, which take non-const
  /// pointers and only read them.
  std::vector<Block>& Blocks() { return this->Hierarchy; }
  /// Cell edge of `level`.
  double CellSize(int level) const;
  /// The field at point (x, y, z) at the current time.
  double Field(double x, double y, double z) const;

private:
  /// Rebuilds the hierarchy from the current field and shares the blocks out among the ranks.
  void Regrid();
  /// Recomputes the values of the blocks this rank owns.
  void Compute();

  SimulationConfig Config;
  int Rank;
  int Ranks;
  int StepCount = 0;
  bool Regridded = false;
  std::vector<Block> Hierarchy;
};

} // namespace insitu

#endif
