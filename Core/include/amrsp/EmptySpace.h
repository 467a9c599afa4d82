// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Empty-space skipping: per data node, the range of the scalars a ray segment through that node
/// can sample, and the tests whether a transfer function gives that whole range zero opacity.
/// The ranges depend only on the data (computed once per build); the tests only on the transfer
/// function, so a transfer-function change never rebuilds the tree or the ranges.

#include "amrsp/Hierarchy.h"
#include "amrsp/KdTreeEncoding.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

struct TransferFunction;

/// Value range of every data node of `tree` (index = data-node index, entry 0 unused): the
/// minimum (x) and maximum (y) of the finite values the node's block holds, i.e. the cells
/// [first, last] of the node's data level covering its region (cell-centred, nearest sampling),
/// or the vertices [first, last + 1] of those cells (vertex-centred, trilinear sampling inside
/// the node; a trilinear sample lies between the minimum and maximum of its corners). NaN values
/// are left out (they are transparent); a node without a finite value gets the empty range
/// x = +FLT_MAX, y = -FLT_MAX, which every test below treats as transparent.
std::vector<glm::vec2> ComputeDataNodeRanges(const Hierarchy& h, const EncodedKdTree& tree);

/// What ComputeDataNodeRanges reads for one data node: its grid and the cells (or vertices)
/// [First, Last] of that grid, relative to the grid's first cell. Depends on the structure only.
struct DataNodeBlock
{
  uint32_t Data;
  std::size_t Grid;
  glm::i64vec3 First, Last, Extent;
};

/// The blocks of every data node of `tree` (decodes the tree once).
std::vector<DataNodeBlock> DataNodeBlocks(const Hierarchy& h, const EncodedKdTree& tree);

/// ComputeDataNodeRanges from blocks kept from an earlier build of the same structure: `h`'s
/// values, `dataNodeCount` data nodes. Lets a new time step with the same hierarchy refresh the
/// ranges without the tree.
std::vector<glm::vec2> ComputeDataNodeRanges(
  const Hierarchy& h, const std::vector<DataNodeBlock>& blocks, int64_t dataNodeCount);

/// Whether the piecewise-linear opacity of `tf` is zero everywhere on [lo, hi] (with the
/// transfer function's clamping beyond its end points). An empty range (lo > hi) is transparent.
bool TransparentRange(const TransferFunction& tf, double lo, double hi);

/**
 * The test on the tabulated transfer function the shader samples: `prefix[i]`
 * is the number of table entries 0..i with opacity > 0 (OpacityPrefixCounts). Table entry i
 * stands for the scalar first + i / (n - 1) * (last - first), with linear filtering between
 * entries and clamping beyond; `range` is the shader's (first, 1 / (last - first)).
 * A range is transparent when no entry from the one below lo's position to the one above hi's
 * position (one entry of margin on each side, against filtering round-off) has opacity.
 * vtkSinglePassAMRVolumeMapper evaluates it for every data node whenever the table changes and
 * gives the shader the verdicts (one flag per data node).
 */
std::vector<float> OpacityPrefixCounts(const std::vector<float>& opacity);
bool TableRangeTransparent(
  const std::vector<float>& prefix, const float range[2], float lo, float hi);

} // namespace amrsp
