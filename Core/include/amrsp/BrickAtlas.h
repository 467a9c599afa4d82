// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The packed atlas (paper, section 5.1): one brick per AMR grid, copied into one 3D array of
/// float texels at the positions computed by PackBricks. Cell-centred data: texel (i,j,k) of a
/// brick is cell (i,j,k) of its grid (texel centres at cell centres, nearest sampling).
/// Vertex-centred data: texel (i,j,k) is vertex (i,j,k) (bricks one texel larger per axis,
/// trilinear sampling that never leaves the brick).

#include "amrsp/BrickPacking.h"
#include "amrsp/Hierarchy.h"

#include <cstddef>
#include <vector>

namespace amrsp
{

struct BrickAtlas
{
  AtlasLayout Layout;
  /// Layout.Dims texels, x fastest; texels outside every brick are 0. Values are copied
  /// unchanged: a NaN stays NaN (the integrators treat a NaN sample as transparent), +-Inf stays.
  std::vector<float> Texels;

  std::size_t Bytes() const { return Texels.size() * sizeof(float); }
  float At(const glm::ivec3& t) const
  {
    return Texels[(static_cast<std::size_t>(t.z) * Layout.Dims.y + t.y) * Layout.Dims.x + t.x];
  }
};

/// Bytes one float texel takes in the atlas.
constexpr std::size_t AtlasTexelBytes = sizeof(float);

/// Packs the grids of `h` and copies their values (cell- or vertex-centred). `maxBytes`
/// bounds the atlas memory (0 = no bound); it is checked before anything is allocated.
/// @throws PackingError (from PackBricks) when the atlas does not fit.
BrickAtlas BuildBrickAtlas(
  const Hierarchy& h, Packer packer, const glm::ivec3& maxDims, std::size_t maxBytes = 0);

/// Copies the values of `h` into an atlas laid out by `layout` (PackBricks of BrickExtents(h,
/// h.VertexCentred)), for callers that decide on the storage after packing.
/// @throws std::invalid_argument when `h` has no values or the layout has another brick count.
BrickAtlas FillBrickAtlas(const Hierarchy& h, AtlasLayout layout);

/// Fills the atlas slab by slab, for an upload without the whole atlas in memory. It keeps
/// references to `h` and `layout` (both must outlive it) and indexes the bricks by their first
/// layer once, so that a slab visits only the bricks that cross it: a slab costs its texels plus
/// O(log bricks), not a pass over every grid.
class AtlasSlabFiller
{
public:
  /// @throws std::invalid_argument as FillBrickAtlas.
  AtlasSlabFiller(const Hierarchy& h, const AtlasLayout& layout);

  /// The atlas texels of the slab z0 <= z < z1 (Layout.Dims.x * Layout.Dims.y * (z1 - z0)
  /// floats, x fastest) into `out`: what FillBrickAtlas would hold there, texels outside every
  /// brick 0. Safe to call from several threads for different slabs.
  /// @throws std::invalid_argument for a slab outside [0, Layout.Dims.z].
  void Fill(int z0, int z1, float* out) const;

private:
  const Hierarchy& H;
  const AtlasLayout& Layout;
  std::vector<glm::ivec3> Extents;
  std::vector<std::size_t> ByFirstLayer; ///< grid indices, by increasing Layout.Origins[g].z
  int TallestBrick = 0;
};

/// AtlasSlabFiller(h, layout).Fill(z0, z1, out), for a single slab.
void FillAtlasSlab(const Hierarchy& h, const AtlasLayout& layout, int z0, int z1, float* out);

/// Bytes of the grid data when every brick is its own texture (the bindless strategy): the sum
/// of the brick volumes (cells, or vertices when h.VertexCentred) times AtlasTexelBytes.
std::size_t SeparateBrickBytes(const Hierarchy& h);

/// Bytes of the bindless strategy's RG32UI "handles" texture: one 64-bit handle per brick, laid out
/// like the kD-tree textures (TextureDimsFor, rows of AMRSP_TEXTURE_ROW texels).
std::size_t HandleTextureBytes(std::size_t bricks);

} // namespace amrsp
