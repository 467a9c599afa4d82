// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/PackedHierarchy.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/BrickPacking.h"
#include "amrsp/RayCastingData.h"

#include <algorithm>
#include <exception>
#include <utility>

namespace amrsp
{

bool PackHierarchy(Hierarchy converted, int packLimit, int64_t maxPageTexels, bool mayRefresh,
  PackedHierarchy& out, bool& refreshed, std::string& error)
{
  refreshed = false;
  try
  {
    if (mayRefresh && !out.Tree.Nodes.empty() && SameStructure(out.Structure, converted))
    {
      FiniteValueRange(converted, out.ScalarRange); // as the full build below
      out.Structure.Values = std::move(converted.Values);
      refreshed = true;
      return true;
    }
    out = PackedHierarchy();
    out.Structure = std::move(converted);
    const Hierarchy& h = out.Structure;
    out.Tree = BuildKdTree(h);
    // one brick per grid (cells, or vertices one texel larger), packed within the per-axis limit
    // the data-node offsets can address and MaximumAtlasSize when set
    out.Atlas = PackBricksInPages(BrickExtents(h, h.VertexCentred), Packer::Best,
      AtlasLimits(packLimit > 0 ? std::min(packLimit, 2048) : 2048), maxPageTexels);
    out.VertexCentred = h.VertexCentred;

    // the level table and the finite range as the single-pass build computes them
    const LevelTable levels = ComputeLevelTable(h, out.Tree);
    out.LevelMinEdge = levels.LevelMinEdge;
    std::copy(levels.Bounds, levels.Bounds + 6, out.Bounds);
    FiniteValueRange(h, out.ScalarRange);
  }
  catch (const std::exception& e)
  {
    error = e.what();
    out = PackedHierarchy();
    return false;
  }
  return true;
}

} // namespace amrsp
