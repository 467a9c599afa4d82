// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Packing of the AMR grid bricks into one 3D texture atlas (paper, section 5.1). Plain C++17 +
/// GLM; no VTK, no OpenGL. Only the layout is computed here; copying the texels is the caller's.
///
/// Conventions:
/// - A brick is an axis-aligned box of texels with extent >= 1 on every axis: the grid's cell
///   extent for cell-centred data, the cell extent + 1 per axis for vertex-centred data.
/// - Brick i occupies the half-open texel box [Origins[i], Origins[i] + extents[i]) of the atlas.
///   Bricks are never rotated (the shader adds the origin to a brick-local texel index).
/// - The atlas is the tight bounding box of the placed bricks, anchored at (0,0,0): on every axis
///   some brick touches 0 and some brick touches Dims. Dims <= maxDims component-wise and
///   Dims.x * Dims.y * Dims.z <= maxTexels (when a budget is given).
/// - Empty input gives Dims = (0,0,0), no origins, Efficiency 1 (nothing is wasted).
/// - The result depends on the input only (same extents and limits -> same layout), not on
///   timing or thread count.

#include "amrsp/Hierarchy.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace amrsp
{

/// Packing algorithms.
/// - NextFitDecreasingHeight ("nfdh"): the paper's NFDH. Bricks sorted by decreasing z, y, x
///   extent fill rows along x, rows fill a layer along y, layers stack along z; repeated over a
///   ladder of container base extents (x,y), keeping the smallest atlas.
/// - Best ("best"; AtlasLayout::PackerName "guillotine-bestfit"): box-driven best fit into
///   guillotine-cut free boxes. The lowest free box takes the tallest brick that fits it (largest
///   footprint first); the rest of the box is cut into the slab above the brick and two boxes
///   beside it, so layers and rows form on their own and the space above shorter bricks is
///   reused. Stacks along the axis with the largest limit, repeated over a set of footprints,
///   keeping the smallest atlas. About 95% efficient on the synthetic sets of the paper's sizes.
enum class Packer
{
  NextFitDecreasingHeight,
  Best
};

struct AtlasLayout
{
  /// Atlas size in texels (tight bounding box of the bricks; (0,0,0) for no bricks).
  glm::ivec3 Dims{ 0 };
  /// One per brick, in input order: brick i covers [Origins[i], Origins[i] + extents[i]).
  std::vector<glm::ivec3> Origins;
  /// Sum of the brick volumes, in texels.
  int64_t UsedTexels = 0;
  /// Dims.x * Dims.y * Dims.z, in texels.
  int64_t TotalTexels = 0;
  /// UsedTexels / TotalTexels (1 for an empty atlas).
  double Efficiency = 0.0;
  /// The algorithm that produced the layout: "nfdh" or "guillotine-bestfit".
  std::string PackerName;
  /// Wall-clock time of the packing (sorting, all trials, validation of the input), seconds.
  double Seconds = 0.0;
};

/// Raised when the bricks cannot be placed within the limits. The message says which limit,
/// by how much it is exceeded, and what to do instead.
class PackingError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Packs the bricks into one atlas.
/// @param extents brick sizes in texels, every component >= 1.
/// @param maxDims per-axis atlas limit in texels (e.g. GL_MAX_3D_TEXTURE_SIZE on every axis, or
///   AtlasLimits() to also respect the data-node offset encoding); every component in [1, 2^21).
/// @param maxTexels total texel budget of the atlas; 0 = no budget.
/// @throws PackingError when a brick is larger than maxDims, or no layout found fits maxDims and
///   maxTexels. The message names the limit, the shortfall, and suggests the bindless path, a
///   smaller array type, or level-of-detail. Bricks are never dropped or truncated.
/// @throws std::invalid_argument for an extent component < 1, a limit component outside
///   [1, 2^21), or maxTexels < 0.
AtlasLayout PackBricks(const std::vector<glm::ivec3>& extents, Packer packer,
  const glm::ivec3& maxDims, int64_t maxTexels = 0);

/// "nfdh" -> NextFitDecreasingHeight; "best" or "guillotine-bestfit" -> Best (case-insensitive).
/// @throws std::invalid_argument naming the accepted values.
Packer ParsePacker(const std::string& name);

/// Short name accepted by ParsePacker: "nfdh" or "best".
std::string PackerName(Packer packer);

/// The per-axis atlas limit for a context reporting `max3DTextureSize`
/// (GL_MAX_3D_TEXTURE_SIZE): that size on every axis, clamped to what the data-node offset
/// fields of the kD-tree encoding can address (2048 x 2048 x 1024, see Shaders/KdTreeLayout.glsl).
glm::ivec3 AtlasLimits(int max3DTextureSize);

/// Brick extents of a hierarchy's grids, in grid order: the cell extents, plus one per axis when
/// `vertexCentred` (pass h.VertexCentred for the hierarchy's own data).
std::vector<glm::ivec3> BrickExtents(const Hierarchy& h, bool vertexCentred);

} // namespace amrsp
