// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A synthetic, cosmology-like AMR hierarchy: clustered, deeply nested refinement of a procedural
/// density field. Used for tests and for the performance benchmarks at the sizes of the paper's
/// Table 1. Plain C++17 + GLM; no VTK, no OpenGL.
///
/// The hierarchy produced by GenerateCosmo():
/// - Level 0 is the cube [0,N0)^3 of level-0 cells, split into root grids by recursive
///   bisection (2x2x2 by default). World space is the unit cube: Origin = (0,0,0),
///   Spacing0 = 1/N0. N0 is chosen from the cell budget so that level 1 covers about a tenth of
///   the domain.
/// - Refinement: on each level the parents are cut into tiles of a searched edge T; the densest
///   tiles (field at the tile centre) worth the level's share of the cell budget are selected,
///   merged into boxes within each parent (runs along x, then rows, then slabs), and the box
///   count is brought to the level's grid count by halving the biggest boxes (or, on levels
///   with a handful of grids, by joining neighbours).
/// - Every level l >= 1 refines level l-1 by 2 on every axis. Each level-l grid lies inside ONE
///   level-(l-1) grid (so the hierarchy is properly nested), grids of one level never overlap,
///   and every level has at least one grid.
/// - Hierarchy::Grids is sorted by level; Grids[g].SourceId == g.
/// - Values (when requested) hold one float per cell, x fastest: the density field (CosmoField)
///   at the cell centre. ArrayName is "Density", VertexCentred is false.
///
/// Everything is a function of the parameters only: the same parameters give bit-identical
/// boxes and values on every run and thread count. The generator uses its own PRNG (splitmix64)
/// and its own uniform-double conversion, and the field uses only +, -, *, /, sqrt and floor, so
/// results do not depend on the standard library. (Compilers that contract a*b+c into fused
/// multiply-adds, e.g. GCC on aarch64 by default, may change last bits; compile this file with
/// -ffp-contract=off where bit-identical results across architectures matter.)

#include "amrsp/Progress.h"
#include "amrsp/Hierarchy.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace amrsp
{

struct CosmoParameters
{
  /// Requested total number of grids (all levels, root grids included). Reproduced exactly
  /// (levels 1.. get geometrically fewer grids, ratio 0.75 per level), unless a level's boxes
  /// have all been split down to single cells.
  int64_t Grids = 2666;
  /// Number of levels (>= 1). Reproduced exactly.
  int Levels = 4;
  /// Requested total number of cells over all grids (covered cells included). With two or more
  /// levels the refined levels absorb the rounding of the cubic root domain (typically within
  /// 1%); with one level the cells are the nearest cube N0^3.
  int64_t Cells = 19000000;
  uint64_t Seed = 1;
  /// False: boxes only (Hierarchy::Values left empty), for fast tree statistics.
  bool GenerateValues = true;
  /// Number of root grids; 0 = automatic: 8 (2x2x2) when Levels >= 2, Grids when Levels == 1.
  int64_t RootGrids = 0;
  /// A time series of Steps steps (>= 1): at step s every halo has drifted s times its own
  /// velocity (CosmoField's time s). The boxes are those of the last regrid step: every
  /// RegridEvery steps (0: never, the boxes of step 0 throughout), as AMR codes regrid every
  /// few steps; the values always follow the field of the step. Step 0 is GenerateCosmo's.
  int Steps = 1;
  int RegridEvery = 0;
  /// The step GenerateCosmo builds (0 <= Step < Steps).
  int Step = 0;
};

/// Parses "grids=N,levels=L,cells=C,seed=S" (any subset, any order; keys are case-insensitive;
/// spaces around items are ignored; an empty string gives the defaults). Also accepted:
/// "roots=R" (CosmoParameters::RootGrids), "values=0|1" (CosmoParameters::GenerateValues),
/// "steps=T", "regrid=K" and "step=S" (CosmoParameters::Steps, RegridEvery, Step).
/// N, C and R accept the suffixes k (10^3), M (10^6) and G (10^9), also after a decimal number as
/// long as the result is an integer (cells=19M, cells=1.5M, grids=2.5k, cells=1G).
/// @throws std::invalid_argument naming the offending item, key or value.
CosmoParameters ParseCosmoParameters(const std::string& spec);

/// The inverse of ParseCosmoParameters (all keys, plain integers).
std::string FormatCosmoParameters(const CosmoParameters& p);

/// The procedural density field that the hierarchy refines, in world coordinates of the unit
/// cube [0,1]^3 (defined, but not interesting, outside). Depends only on the seed.
///
/// density(x) = background(x) + sum over halos h with |x - c_h| < R_h of
///              A_h * (1 - |x - c_h|^2 / R_h^2)^2 / (|x - c_h|^2 + eps_h^2)
/// i.e. softened isothermal (1/r^2) halos with a smooth cut-off at R_h, placed as massive
/// clusters with satellites, filaments of small halos between neighbouring clusters, and a few
/// isolated field halos; halo radii follow a power law (dN/dR ~ R^-3, i.e. dN/dM ~ M^-5/3 for
/// M ~ R^3) and amplitudes grow as R^2 (isothermal: M(<R) ~ A R). The background is a smooth,
/// periodic, strictly positive modulation between about 0.35 and 2. The softening eps_h is
/// 1.5e-6 to 4.5e-6 (about the cell size of level 10 of a 256^3 root): deeper levels nest
/// around the smooth maxima of the halo cores. Always > 0.
/// Only +, -, *, /, sqrt and floor are used, so the values do not depend on the C library.
///
/// Copies share the (immutable) halo catalogue; evaluation is thread-safe.
class CosmoField
{
public:
  /// The field of `seed` at `time`: every halo moved by `time` times its velocity (a random
  /// direction, at most HaloSpeed box lengths per unit time, from a stream of its own, so time 0
  /// is bit for bit the field without motion); the background does not move.
  explicit CosmoField(uint64_t seed, double time = 0.0);

  /// The largest halo speed, in box lengths per unit time (one step of a series).
  static constexpr double HaloSpeed = 0.01;

  /// Density at a world position (unit cube).
  double operator()(const glm::dvec3& world) const;

  /// Number of halos in the catalogue (for reports).
  std::size_t NumberOfHalos() const;

  /// Writes the density at the cells centres of `box` (cells of a level whose cell size is
  /// `cellSize` in world units, with index (0,0,0) at world (0,0,0)): values[i + nx*(j + ny*k)]
  /// = float(density(((box.Lo + (i,j,k)) + 0.5) * cellSize)), bit-identical to evaluating
  /// operator() point by point at those positions. `values` is resized. Fast: halos are
  /// gathered once per block of cells.
  void Sample(const Box& box, double cellSize, std::vector<float>& values) const;

  struct Impl;

private:
  std::shared_ptr<const Impl> Internals;
};

/// Builds the hierarchy (of step p.Step of a series: GenerateCosmoStep).
/// @throws std::invalid_argument for impossible requests: Levels < 1 or > 30, Grids < 1,
/// Grids smaller than the number of root grids plus one grid per refined level, Cells smaller
/// than 64 cells per grid on average, RootGrids incompatible with Levels/Grids.
/// `progress`, when set, receives the fraction of the cells whose values are generated.
Hierarchy GenerateCosmo(const CosmoParameters& p, const ProgressCallback& progress = nullptr);

/// Step `step` (0 <= step < p.Steps) of the time series p describes: the boxes GenerateCosmo
/// builds on the field at the last regrid step (step - step % RegridEvery, or 0 without
/// regrids), the values of the field at `step`. Step 0 equals GenerateCosmo(p).
/// @throws std::invalid_argument for a step outside the series, and as GenerateCosmo.
Hierarchy GenerateCosmoStep(
  const CosmoParameters& p, int step, const ProgressCallback& progress = nullptr);

/// The step whose boxes step `step` uses (its last regrid).
int CosmoRegridStep(const CosmoParameters& p, int step);

/// The density field of GenerateCosmo(p) at a point given in level-0 index units of `h` (the
/// hierarchy made by GenerateCosmo with a parameter set of seed `seed`): CosmoField(seed) at
/// h.Origin + indexPos * h.Spacing0. Builds the halo catalogue on every call (about 10 ms);
/// use CosmoField directly for many points.
double CosmoDensity(uint64_t seed, const Hierarchy& h, const glm::dvec3& indexPos);

/// Per-level statistics of a hierarchy (any hierarchy, not only synthetic ones).
struct CosmoStatistics
{
  std::vector<int64_t> GridsPerLevel;
  std::vector<int64_t> CellsPerLevel;
  int64_t Grids = 0;
  int64_t Cells = 0;
  int64_t MinGridCells = 0;
  int64_t MaxGridCells = 0;
};
CosmoStatistics ComputeCosmoStatistics(const Hierarchy& h);

} // namespace amrsp
