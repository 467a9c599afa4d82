// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Resampling of an AMR hierarchy onto one uniform grid at the cell size of a chosen level: what
/// a user of a plain volume mapper has to do instead of rendering the hierarchy natively (the
/// "uniform-gpu" method of the benchmark).

#include "amrsp/Hierarchy.h"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace amrsp
{

struct UniformGrid
{
  glm::ivec3 Dims{ 0 };      ///< voxels (cells) per axis
  glm::dvec3 Origin{ 0.0 };  ///< world position of the first voxel's lower corner
  glm::dvec3 Spacing{ 1.0 }; ///< world size of a voxel
  std::vector<float> Values; ///< voxel values, x fastest; NaN outside every grid

  std::size_t Bytes() const { return Values.size() * sizeof(float); }
};

/// Raised when the uniform grid would exceed `maxVoxels` or `maxAxis`.
class ResampleError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Voxels of the root box at the cell size of `level` (what ResampleToLevel would allocate).
glm::i64vec3 UniformDims(const Hierarchy& h, int level);

/// Samples the hierarchy at every voxel centre of the root box at `level`'s cell size: the value
/// of the finest cell containing it (cell-centred) or the trilinear value of that cell's grid
/// (vertex-centred). Throws ResampleError, naming the size, when a dimension exceeds `maxAxis`
/// or the voxel count exceeds `maxVoxels`; nothing is allocated then.
UniformGrid ResampleToLevel(
  const Hierarchy& h, int level, int64_t maxVoxels, int maxAxis, int threads = 0);

} // namespace amrsp
