// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Resample.h"

#include "amrsp/FinestCellLocator.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/VertexData.h"

#include <cstddef>
#include <limits>
#include <string>

namespace amrsp
{

glm::i64vec3 UniformDims(const Hierarchy& h, int level)
{
  return h.ToLevel(h.RootCells(), 0, level).Extent();
}

UniformGrid ResampleToLevel(
  const Hierarchy& h, int level, int64_t maxVoxels, int maxAxis, int threads)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("resampling needs values");
  }
  const glm::i64vec3 dims = UniformDims(h, level);
  const double voxels = static_cast<double>(dims.x) * dims.y * dims.z;
  if (dims.x > maxAxis || dims.y > maxAxis || dims.z > maxAxis ||
    voxels > static_cast<double>(maxVoxels))
  {
    throw ResampleError("the uniform grid at level " + std::to_string(level) + " would have " +
      std::to_string(dims.x) + " x " + std::to_string(dims.y) + " x " + std::to_string(dims.z) +
      " voxels (limits: " + std::to_string(maxAxis) + " per axis, " + std::to_string(maxVoxels) +
      " in all)");
  }
  const Box root = h.ToLevel(h.RootCells(), 0, level);
  const glm::dvec3 cell = h.CellSize(level); // level-0 index units
  UniformGrid u;
  u.Dims = glm::ivec3(dims);
  u.Spacing = h.Spacing0 * cell;
  u.Origin = h.Origin + glm::dvec3(root.Lo) * cell * h.Spacing0;
  u.Values.assign(static_cast<std::size_t>(voxels), std::numeric_limits<float>::quiet_NaN());
  const FinestCellLocator locator(h);
  // each slice k of voxels is written by one worker
  ParallelForInterleaved(
    u.Dims.z,
    [&](int64_t slice)
    {
      const int k = static_cast<int>(slice);
      for (int j = 0; j < u.Dims.y; ++j)
      {
        for (int i = 0; i < u.Dims.x; ++i)
        {
          const glm::dvec3 p = (glm::dvec3(root.Lo) + glm::dvec3(i, j, k) + 0.5) * cell;
          glm::i64vec3 c;
          const int32_t g = locator.Find(p, c);
          if (g < 0)
          {
            continue;
          }
          const glm::dvec3 r(h.CumulativeRatio(h.Grids[g].Level));
          u.Values[(static_cast<std::size_t>(k) * u.Dims.y + j) * u.Dims.x + i] = h.VertexCentred
            ? InterpolateVertices(h, g, p * r - glm::dvec3(h.Grids[g].Cells.Lo))
            : CellValue(h, g, c);
        }
      }
    },
    threads);
  return u;
}

} // namespace amrsp
