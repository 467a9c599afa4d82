// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The CPU build of the GPU ray casters (paper, sections 4 and 5), without OpenGL: from a
/// converted hierarchy to the kD-tree textures, the brick layout of the packed atlas, the level
/// table the shaders take as uniforms, and the figures the mappers report. The mappers upload the
/// result; everything here is tested without a GPU.
///
/// Units: "index units" are level-0 cell indices (world = Origin + index * Spacing0); "model"
/// coordinates are the volume's own; "finest cells" are cells of the hierarchy's finest level,
/// in which kD-tree regions are exact integers.

#include "amrsp/AtlasPages.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTree.h"
#include "amrsp/KdTreeEncoding.h"

#include <glm/glm.hpp>

#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

namespace amrsp
{

/// Base-2 logarithms of `ratios` (all > 0); empty unless every one is a power of two.
std::vector<int> PowerOfTwoExponents(const std::vector<int>& ratios);

/// k > 0 when `toFinestLog2` (3 per level) says every level refines the one above by 2^k on every
/// axis, i.e. level l has k (L - 1 - l) on every axis (one level: k = 1), with k (L - 1) < 31;
/// else 0.
int UniformRefinementExponent(const std::vector<int>& toFinestLog2);

/// What the shaders need about the levels and the root box, derived exactly from the tree.
struct LevelTable
{
  /// The root box in finest cells (exact), valid when RootFitsShaderIntegers: every bound within
  /// [-2^30, 2^30], what the single-pass shader's integer node boxes can hold.
  bool RootFitsShaderIntegers = false;
  glm::ivec3 RootLoFinest{ 0 };
  glm::ivec3 RootHiFinest{ 0 };
  /// Finest cells per cell of each level, 3 per level; their base-2 logarithms (empty unless all
  /// are powers of two); UniformRefinementExponent of those.
  std::vector<int> LevelToFinest;
  std::vector<int> LevelToFinestLog2;
  int UniformRefinementLog2 = 0;
  /// Smallest model-space edge of a cell of each level (amrsp::LevelMinEdge): the sampling
  /// distance D at factor 1; D = amrsp::LevelSampleStep(factor, LevelMinEdge[level]).
  std::vector<double> LevelMinEdge;
  /// Model-space bounds of the root box [xmin, xmax, ymin, ymax, zmin, zmax], through the float
  /// root box the shaders use (EncodedKdTree::RootLo/RootHi).
  double Bounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
};

/// The level table of `h` and its tree.
LevelTable ComputeLevelTable(const Hierarchy& h, const KdTree& tree);

/// The range of the finite values of `h` in `range`; false (and [0, 1]) when there is none.
bool FiniteValueRange(const Hierarchy& h, double range[2]);

/// The single-pass mapper's CPU build: both data-node encodings (packed atlas offsets, and
/// offsets inside each grid's own brick for the bindless storage), the atlas layout when the
/// bricks can be packed, the data nodes' value ranges (empty-space skipping) and the sizes.
struct RayCastingData
{
  /// The converted hierarchy; its Values are the bricks (FreeBricks drops them after upload).
  Hierarchy Data;
  UIntTexture3D TreeTexels;
  /// The data nodes with their block's texel in the packed atlas (and its page); empty when the
  /// bricks could not be packed.
  UIntTexture3D PackedDataNodeTexels;
  /// The data nodes with their block's texel inside its grid's own brick (the bindless and the
  /// linear storages).
  UIntTexture3D BrickLocalDataNodeTexels;
  /// The tree's neighbour links and node boxes (amrsp/KdTreeRopes.h); empty where not encoded.
  UInt4Texture3D RopeTexels;
  glm::vec3 RopeCellSize{ 0.0f }; ///< a finest-level cell, level-0 index units
  /// Cell size of each level in index units (float, as in GLSL), and the float root box.
  std::vector<glm::vec3> LevelCellSize;
  glm::vec3 RootLo{ 0.0f };
  glm::vec3 RootHi{ 0.0f };
  LevelTable Levels;
  /// min, max scalar per data node, indexed like the data-node texels (entry 0 unused). Empty
  /// while PendingNodeRanges is valid: call WaitForNodeRanges before reading them.
  std::vector<glm::vec2> NodeRanges;
  /// The node ranges while a worker thread computes them (PrepareRayCasting with
  /// deferNodeRanges); it reads its own shallow copies of the hierarchy and the tree, so the
  /// upload may free this object's copies meanwhile.
  std::shared_future<std::vector<glm::vec2>> PendingNodeRanges;
  /// What each data node's range is computed from (amrsp::DataNodeBlocks), kept for
  /// RefreshValues: set by PrepareRayCasting, or by WaitForNodeRanges when deferred.
  std::shared_ptr<const std::vector<DataNodeBlock>> NodeBlocks;
  std::shared_future<std::shared_ptr<const std::vector<DataNodeBlock>>> PendingNodeBlocks;
  /// The bricks' atlas pages (one texture each; usually one page); no page when the bricks could
  /// not be packed.
  AtlasPages Atlas;
  glm::ivec3 AtlasDims{ 0 };        ///< page 0's Dims, kept after FreeUploadData
  std::vector<glm::ivec3> PageDims; ///< every page's Dims, kept after FreeUploadData
  std::string PackingError;         ///< why no atlas could be packed (empty when packed)
  double AtlasWaste = 0.0;          ///< unused fraction of the atlas's texels
  double ScalarRange[2] = { 0.0, 1.0 };
  long long KdNodes = 0;
  long long DataNodes = 0;
  long long Grids = 0;
  /// GPU bytes of the tree textures any storage uploads: the tree, its data nodes and its ropes.
  long long TreeBytes = 0;
  /// GPU bytes of the packed and the bindless storages: TreeBytes + the atlas (0 without an
  /// atlas), or TreeBytes + the separate bricks + their handles.
  long long PackedBytes = 0;
  long long BindlessBytes = 0;
  /// Bytes of the grid data, one brick per grid (SeparateBrickBytes); kept after FreeUploadData.
  long long BrickBytes = 0;
  bool VertexCentred = false;

  /// Drops the CPU copies the upload consumed (bricks, texels); the structure (Data's grids,
  /// the atlas layout, NodeBlocks) and the figures (sizes, ranges, level table, AtlasDims) stay,
  /// for RefreshValues.
  void FreeUploadData();
  /// Waits for PendingNodeRanges, if valid, and moves them into NodeRanges; rethrows what their
  /// computation threw.
  void WaitForNodeRanges();
};

/// Builds the kD-tree of `h`, encodes it for both storages and packs the bricks within
/// `packLimit` texels per axis (0: the 2048 the data-node offsets address; a positive value
/// lowers it). A hierarchy that cannot be packed still succeeds (PackingError says why: the
/// bindless storage can render it). Throws std::runtime_error with a one-line message when it
/// cannot be rendered at all: an encoding limit, a root box over 2^30 finest cells, or no finite
/// value in any cell.
/// Progress of PrepareRayCasting: the fraction done (0 to 1, never decreasing) and the step that
/// starts there; called on the calling thread.
using BuildProgress = std::function<void(double fraction, const char* step)>;

/// `maxPageTexels` (> 0) spreads the bricks over several atlas pages of at most that many
/// texels each when one atlas would be larger (PackBricksInPages); 0 packs one atlas.
/// `deferNodeRanges` leaves the data nodes' value ranges to a worker thread (PendingNodeRanges)
/// for a caller that has other work before it needs them, such as the atlas upload: the ranges
/// read every value once, and the build's two cores are busy with the kD-tree and the packing.
/// `packBricks` false leaves the packing out (PackingError says so), for a caller that stores
/// the bricks otherwise (the linear storage).
RayCastingData PrepareRayCasting(Hierarchy h, int packLimit, int64_t maxPageTexels = 0,
  const BuildProgress& progress = nullptr, bool deferNodeRanges = false, bool packBricks = true);

/// A new time step of the same structure (SameStructure(data.Data, h), which it checks): `data`
/// keeps its tree, encoding and atlas layout and takes `h`'s values; the scalar range and the
/// data nodes' value ranges (from the kept NodeBlocks; deferred like PrepareRayCasting's) are
/// computed from them. The result equals PrepareRayCasting(h)'s in every field the upload and
/// the shaders read, so the image is the full rebuild's. Throws std::logic_error when the
/// structure differs or data has no NodeBlocks, std::runtime_error when `h` holds no finite
/// value.
void RefreshValues(RayCastingData& data, Hierarchy h, bool deferNodeRanges = false);

} // namespace amrsp
