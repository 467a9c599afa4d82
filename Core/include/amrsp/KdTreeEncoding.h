// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Encoding of a kD-tree into the integer 3D textures of Kaehler & Abel 2013, section 4.2, with
/// the bit layout of Shaders/KdTreeLayout.glsl, and the inverse decoding used by tests.

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace amrsp
{

/// An RG32UI 3D texture: Texels[i] is at amrspTexelOf(i); texels past the last used one are 0.
struct UIntTexture3D
{
  glm::ivec3 Dims{ 0 };
  std::vector<glm::uvec2> Texels;

  std::size_t Bytes() const { return Texels.size() * sizeof(glm::uvec2); }
};

/// An RGBA32UI 3D texture, laid out as UIntTexture3D.
struct UInt4Texture3D
{
  glm::ivec3 Dims{ 0 };
  std::vector<glm::uvec4> Texels;

  std::size_t Bytes() const { return Texels.size() * sizeof(glm::uvec4); }
};

/// Everything the single-pass shader (and the CPU traversal that mirrors it) needs about the tree.
struct EncodedKdTree
{
  UIntTexture3D Tree;
  UIntTexture3D DataNodes;
  /// Root box in level-0 index units.
  glm::vec3 RootLo{ 0.0f };
  glm::vec3 RootHi{ 0.0f };
  /// Cell size of each level in level-0 index units (1 / cumulative ratio), float as in GLSL.
  std::vector<glm::vec3> LevelCellSize;
  int64_t NodeCount = 0;
  int64_t DataNodeCount = 0; ///< not counting the unused texel 0
  /// Neighbour links (ropes) and the nodes' boxes (amrsp/KdTreeRopes.h); empty where they are
  /// not encoded.
  UInt4Texture3D Ropes;
  /// Cell size of the tree's finest level in level-0 index units: a rope target's box in
  /// level-0 index units is its box in finest cells times this (exact wherever Ropes is set).
  glm::vec3 FinestCellSize{ 0.0f };
};

/// Raised when a hierarchy exceeds what the layout can address. The message names the limit.
class EncodingError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Linear texel count -> 3D texture dimensions with rows of AMRSP_TEXTURE_ROW texels.
glm::ivec3 TextureDimsFor(std::size_t texels);

/// GPU bytes of the single-pass mapper's tree textures: the tree, the data nodes, and the data
/// nodes' empty-space flags (R8, one byte per data-node texel, same layout).
std::size_t KdTreeTextureBytes(const UIntTexture3D& tree, const UIntTexture3D& dataNodes);

/// Encodes the tree. `brickOrigins`, when given (one per grid), is the texel of each grid's first
/// cell inside the packed atlas; every data node then stores the atlas texel holding its own
/// lower corner. Without it the offsets are 0 (storage not decided yet). `brickPages`, when given
/// (one per grid, each below layout::MaxAtlasPages), is the atlas page (texture) holding each
/// grid's brick when the bricks fill several atlases; without it every page is 0.
/// Throws EncodingError when a field would overflow: more than 64 levels, more than 2^24 nodes,
/// more than 2^21 - 1 data nodes, a split position beyond 2047 cells, more than 2^24 grids, an
/// atlas offset beyond 2047 x 2047 x 1023, or a page beyond 3.
/// `ropes`: also encode the neighbour links (EncodedKdTree::Ropes; amrsp/KdTreeRopes.h).
EncodedKdTree EncodeKdTree(const Hierarchy& h, const KdTree& tree,
  const std::vector<glm::ivec3>* brickOrigins = nullptr,
  const std::vector<int>* brickPages = nullptr, bool ropes = true);

/// Rebuilds a KdTree from its encoding (node regions by exact integer arithmetic), for the
/// encode -> decode round-trip check. Node types are re-derived from the encoded fields.
KdTree DecodeKdTree(const Hierarchy& h, const EncodedKdTree& encoded);

} // namespace amrsp
