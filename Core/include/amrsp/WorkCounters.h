// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// A cost model of the raycasters measured without a GPU: what the shaders' loops do per ray,
/// and what a GPU serialises when the rays of one SIMT group (32 lanes, a tile of 8 x 4 pixels)
/// diverge. The single pass is counted with the CPU mirror of its shader (RenderKdTree, the same
/// traversal, sampling and termination); the multi-pass baseline from the same traversal, one
/// draw per kD leaf with data.
///
/// Definitions (per ray: a pixel whose ray entered the root box):
/// - a *segment* is one iteration of the shader's segment loop (one kd-restart; empty space
///   included), up to the segment where the ray stopped early;
/// - a *descent step* is one iteration of the descent loop (one tree level down);
/// - a *sample* is one iteration of the sample loop (NaN samples included);
/// - a *step* is an iteration of any of the three loops: segments + descent steps + samples;
/// - *texel fetches* are the texture reads the shader issues for those loops (FetchModel):
///   the root node, the far child a restart starts from, a rope and its target's box and node,
///   every node a descent reaches, the data
///   node of a level-of-detail test, the empty-space flag, the data node of a sampled segment,
///   the brick table or bindless handle, the brick's texels and the transfer-function table.
///   Shading's, smooth reconstruction's and shadow rays' point lookups are not counted;
/// - *lockstep steps* of a tile: the steps its SIMT group executes when lanes wait for each
///   other: the sum over segment-loop iterations k of 1 + the largest descent-step count + the
///   largest sample count among the tile's rays in their iteration k (rays that have finished
///   take no part): the time of the tile's group in loop iterations. lockstep_steps_per_pixel is
///   the image's tiles' sum divided by 32 per tile (the group's time per lane); 32 times it
///   equals steps_per_pixel where every lane of every tile does the same work, and exceeds it by
///   what divergence and idle lanes cost.
/// - *flat-loop lockstep steps* of a tile: the same work in one loop that does one operation per
///   iteration (a segment's set-up or descent step, or a sample: Aila and Laine's "if-if"
///   structure, not the shader's nested loops): per iteration 1 when the tile's busy lanes all
///   traverse or all sample, 2 when some do each; a prediction for a loop the shader does not
///   have yet, normalised as lockstep_steps_per_pixel.
/// - multi-pass: every data segment of the traversal without level of detail is one fragment of
///   its leaf's draw (no early termination, no skipping); a fragment's steps are 1 + its samples;
///   a draw's lockstep steps in a tile are 1 + the largest sample count of its fragments there.

#include "amrsp/DataStorage.h"
#include "amrsp/BrickAtlas.h"
#include "amrsp/Hierarchy.h"
#include "amrsp/KdTreeEncoding.h"
#include "amrsp/RenderSettings.h"

#include <cstdint>
#include <vector>

namespace amrsp
{

/// One iteration of the single-pass shader's segment loop, as the CPU mirror ran it.
struct SegmentWork
{
  uint32_t Descent = 0;   ///< descent-loop iterations
  uint32_t LodChecks = 0; ///< data nodes read by level-of-detail tests during the descent
  uint32_t Samples = 0;   ///< sample-loop iterations (0 for empty or skipped segments)
  bool FromFar = false;   ///< the restart began at the far child (one node texel fetched)
  /// The descent began at a rope: the leaf's rope texel, the target's two box texels and its
  /// node texel fetched.
  bool FromRope = false;
  bool Data = false;    ///< the leaf has data
  bool Skipped = false; ///< ... which empty-space skipping did not sample
};

/// What the shader variant reads, to count texel fetches.
struct FetchModel
{
  /// Where the grid data lives, which decides the texel fetches of a sample: PackedAtlas one
  /// atlas texel (cells) or one hardware-filtered read (vertices) per sample; BindlessTextures
  /// the brick's handle, LinearBricks its table entry, then one texel (cells) or eight (vertices).
  DataStorage Storage = DataStorage::PackedAtlas;
  bool VertexCentred = false;
  /// The brick's handle or table entry is read once per sampled segment instead of per sample.
  bool BrickLookupPerSegment = true;
  /// The transfer-function table is read per sample (composite and iso-surface blending); the
  /// other blend modes read it once per ray (not counted).
  bool TransferPerSample = true;
  /// The empty-space flag of every data segment is read (empty-space skipping on).
  bool SkipFlags = false;
};

/// The texel fetches of one ray whose segment-loop iterations are `segments` (the root node's
/// fetch included).
long long RayTexelFetches(const std::vector<SegmentWork>& segments, const FetchModel& m);

/// Mean and 95th percentile of a per-ray count over the rays that entered the root box.
struct WorkDistribution
{
  double Mean = 0.0;
  double P95 = 0.0;
};

/// The cost model of one frame.
struct WorkSummary
{
  long long Pixels = 0; ///< image pixels
  long long Rays = 0;   ///< rays that entered the root box
  long long Tiles = 0;  ///< 8 x 4 tiles covering the image (partial ones at its edges included)
  WorkDistribution Segments;
  WorkDistribution DescentSteps;
  WorkDistribution Samples;
  WorkDistribution TexelFetches;
  WorkDistribution Steps;
  double StepsPerPixel = 0.0;         ///< the steps of all rays / pixels
  double LockstepStepsPerPixel = 0.0; ///< the tiles' lockstep steps / (32 per tile)
  double FlatLoopStepsPerPixel = 0.0; ///< the tiles' flat-loop lockstep steps / (32 per tile)
  /// steps_per_pixel / (32 lockstep_steps_per_pixel): the busy fraction of the groups' lanes, 1
  /// when the lanes of every group stay in step and none is idle.
  double LockstepEfficiency = 0.0;
  /// Multi-pass only: draws (kD leaves with data some ray crosses) and fragments per pixel.
  long long Draws = 0;
  double FragmentsPerPixel = 0.0;
};

/// Tile shape of a SIMT group: 8 x 4 pixels (32 lanes).
constexpr int WorkTileWidth = 8;
constexpr int WorkTileHeight = 4;

/// The single pass's work in the frame `s` describes, counted by the CPU mirror of its shader
/// (the same segments, descents, samples and early termination as RenderKdTree with the same
/// arguments).
WorkSummary MeasureSinglePassWork(const Hierarchy& h, const EncodedKdTree& tree,
  const RenderSettings& s, const FetchModel& fetches, const BrickAtlas* atlas = nullptr);

/// The multi-pass baseline's work in the frame `s` describes (composite blending; every
/// fragment reads one atlas texel and the transfer table per sample).
WorkSummary MeasureMultipassWork(
  const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s);

/// The lockstep steps of one tile whose rays' segment-loop iterations are `rays` (see the file
/// comment); exposed for tests.
long long TileLockstepSteps(const std::vector<std::vector<SegmentWork>>& rays);
/// The flat-loop lockstep steps of one tile (see the file comment); exposed for tests.
long long TileFlatLoopSteps(const std::vector<std::vector<SegmentWork>>& rays);

} // namespace amrsp
