// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/RayCastingData.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/MinMaxFold.h"
#include "amrsp/ParallelFor.h"
#include "amrsp/SampleStep.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <future>
#include <limits>
#include <stdexcept>
#include <utility>

namespace amrsp
{

std::vector<int> PowerOfTwoExponents(const std::vector<int>& ratios)
{
  std::vector<int> exponents;
  for (int ratio : ratios)
  {
    int e = 0;
    while (e < 30 && (1 << e) < ratio)
    {
      ++e;
    }
    if ((1 << e) != ratio)
    {
      return {};
    }
    exponents.push_back(e);
  }
  return exponents;
}

int UniformRefinementExponent(const std::vector<int>& toFinestLog2)
{
  const int levels = static_cast<int>(toFinestLog2.size() / 3);
  if (levels == 0)
  {
    return 0;
  }
  const int k = levels > 1 ? toFinestLog2[0] / (levels - 1) : 1;
  if (k <= 0 || k * (levels - 1) >= 31)
  {
    return 0;
  }
  for (int l = 0; l < levels; ++l)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (toFinestLog2[static_cast<std::size_t>(3 * l + a)] != k * (levels - 1 - l))
      {
        return 0;
      }
    }
  }
  return k;
}

LevelTable ComputeLevelTable(const Hierarchy& h, const KdTree& tree)
{
  LevelTable t;
  const glm::i64vec3 finest = h.CumulativeRatio(tree.FinestLevel);
  const Box& root = tree.Root().Region;
  const int64_t limit = int64_t(1) << 30;
  t.RootFitsShaderIntegers = true;
  for (int a = 0; a < 3; ++a)
  {
    t.RootFitsShaderIntegers =
      t.RootFitsShaderIntegers && root.Lo[a] >= -limit && root.Hi[a] <= limit;
  }
  if (t.RootFitsShaderIntegers)
  {
    for (int a = 0; a < 3; ++a)
    {
      t.RootLoFinest[a] = static_cast<int>(root.Lo[a]);
      t.RootHiFinest[a] = static_cast<int>(root.Hi[a]);
    }
  }
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    const glm::i64vec3 r = finest / h.CumulativeRatio(l);
    for (int a = 0; a < 3; ++a)
    {
      t.LevelToFinest.push_back(static_cast<int>(r[a]));
    }
    t.LevelMinEdge.push_back(LevelMinEdge(h, l));
  }
  t.LevelToFinestLog2 = PowerOfTwoExponents(t.LevelToFinest);
  t.UniformRefinementLog2 = UniformRefinementExponent(t.LevelToFinestLog2);
  const glm::dvec3 lo = h.Origin + glm::dvec3(glm::vec3(RegionLoIndex(h, tree, root))) * h.Spacing0;
  const glm::dvec3 hi = h.Origin + glm::dvec3(glm::vec3(RegionHiIndex(h, tree, root))) * h.Spacing0;
  for (int a = 0; a < 3; ++a)
  {
    t.Bounds[2 * a] = lo[a];
    t.Bounds[2 * a + 1] = hi[a];
  }
  return t;
}

bool FiniteValueRange(const Hierarchy& h, double range[2])
{
  // per grid, then reduced: min and max are exact in float whatever the order
  std::vector<glm::vec2> perGrid(h.Values.size(), glm::vec2(FLT_MAX, -FLT_MAX));
  ParallelFor(
    static_cast<int64_t>(h.Values.size()),
    [&](int64_t g)
    {
      const GridValues& values = h.Values[static_cast<std::size_t>(g)];
      const int64_t count = static_cast<int64_t>(values.size());
      float lo = FLT_MAX, hi = -FLT_MAX;
      FoldMinMax(values.data(), count, lo, hi); // skips NaN, takes +-Inf
      if (lo < -FLT_MAX || hi > FLT_MAX)
      {
        // an infinite value: again, finite values only (rare: damaged data)
        lo = FLT_MAX;
        hi = -FLT_MAX;
        for (int64_t i = 0; i < count; ++i)
        {
          const float v = values.data()[i];
          const bool finite = v >= -FLT_MAX && v <= FLT_MAX; // false for NaN and +-Inf
          lo = finite && v < lo ? v : lo;
          hi = finite && v > hi ? v : hi;
        }
      }
      perGrid[static_cast<std::size_t>(g)] = glm::vec2(lo, hi);
    },
    0, 16);
  float vmin = FLT_MAX, vmax = -FLT_MAX;
  bool found = false;
  for (std::size_t g = 0; g < perGrid.size(); ++g)
  {
    if (perGrid[g].x <= perGrid[g].y)
    {
      found = true;
      vmin = std::min(vmin, perGrid[g].x);
      vmax = std::max(vmax, perGrid[g].y);
    }
  }
  range[0] = found ? vmin : 0.0;
  range[1] = found ? vmax : 1.0;
  return found;
}

void RayCastingData::FreeUploadData()
{
  this->Data.Values = std::vector<GridValues>();
  this->TreeTexels = UIntTexture3D();
  this->PackedDataNodeTexels = UIntTexture3D();
  this->BrickLocalDataNodeTexels = UIntTexture3D();
  this->RopeTexels = UInt4Texture3D();
}

void RayCastingData::WaitForNodeRanges()
{
  if (this->PendingNodeRanges.valid())
  {
    // a moved-from shared_future is no longer valid: nothing is pending after this
    const std::shared_future<std::vector<glm::vec2>> pending = std::move(this->PendingNodeRanges);
    this->NodeRanges = pending.get();
  }
  if (this->PendingNodeBlocks.valid())
  {
    const auto pending = std::move(this->PendingNodeBlocks);
    this->NodeBlocks = pending.get();
  }
}

RayCastingData PrepareRayCasting(Hierarchy h, int packLimit, int64_t maxPageTexels,
  const BuildProgress& progress, bool deferNodeRanges, bool packBricks)
{
  // the shares of the steps measured at the paper's dataset-3 size
  const auto report = [&progress](double fraction, const char* step)
  {
    if (progress)
    {
      progress(fraction, step);
    }
  };
  report(0.0, "kD-tree");
  RayCastingData out;
  // the packing needs the grid boxes only: it runs beside the tree, its encoding and the value
  // scans (its result does not depend on the timing)
  std::future<AtlasPages> packing =
    std::async(packBricks ? std::launch::async : std::launch::deferred,
      [&h, packLimit, maxPageTexels, packBricks]
      {
        if (!packBricks)
        {
          throw std::runtime_error("the bricks were not packed (the linear storage was asked for)");
        }
        return PackBricksInPages(BrickExtents(h, h.VertexCentred), Packer::Best,
          AtlasLimits(packLimit > 0 ? std::min(packLimit, 2048) : 2048), maxPageTexels);
      });
  const KdTree tree = BuildKdTree(h);
  out.VertexCentred = h.VertexCentred;
  // bindless: every data node stores the offset of its lower corner inside its own brick
  const std::vector<glm::ivec3> brickStarts(h.Grids.size(), glm::ivec3(0));
  report(0.3, "encoding the kD-tree");
  EncodedKdTree enc = EncodeKdTree(h, tree, &brickStarts);
  out.RopeTexels = std::move(enc.Ropes); // before the node ranges' copy of the encoding
  out.RopeCellSize = enc.FinestCellSize;
  report(0.35, "the data nodes' value ranges");
  if (deferNodeRanges)
  {
    // shallow copies: the values are shared (GridValues), the tree's texels are a few MB
    out.PendingNodeBlocks = std::async(std::launch::async,
      [hierarchy = h, tree = enc]() -> std::shared_ptr<const std::vector<DataNodeBlock>> {
        return std::make_shared<const std::vector<DataNodeBlock>>(DataNodeBlocks(hierarchy, tree));
      }).share();
    out.PendingNodeRanges = std::async(std::launch::async,
      [hierarchy = h, blocks = out.PendingNodeBlocks, count = enc.DataNodeCount] {
        return ComputeDataNodeRanges(hierarchy, *blocks.get(), count);
      }).share();
  }
  else
  {
    out.NodeBlocks = std::make_shared<const std::vector<DataNodeBlock>>(DataNodeBlocks(h, enc));
    out.NodeRanges = ComputeDataNodeRanges(h, *out.NodeBlocks, enc.DataNodeCount);
  }
  out.BrickLocalDataNodeTexels = std::move(enc.DataNodes);
  // packing: one brick per grid (cells, or vertices one texel larger), within the per-axis limit
  // the data-node offsets can address and packLimit when set
  try
  {
    report(0.75, "packing the bricks");
    out.Atlas = packing.get();
    out.PackedDataNodeTexels = EncodeKdTree(h, tree, &out.Atlas.Origins,
      out.Atlas.Pages.size() > 1 ? &out.Atlas.PageOfGrid : nullptr, false)
                                 .DataNodes;
  }
  catch (const std::exception& e)
  {
    out.PackingError = e.what();
    out.Atlas = AtlasPages();
    out.PackedDataNodeTexels = UIntTexture3D();
  }
  out.Levels = ComputeLevelTable(h, tree);
  if (!out.Levels.RootFitsShaderIntegers)
  {
    throw std::runtime_error("the root box spans more than 2^30 cells of the finest level; the "
                             "shader's integer node boxes cannot hold it");
  }
  out.LevelCellSize = enc.LevelCellSize;
  out.RootLo = enc.RootLo;
  out.RootHi = enc.RootHi;
  out.KdNodes = enc.NodeCount;
  out.DataNodes = enc.DataNodeCount;
  int64_t usedTexels = 0;
  for (const AtlasLayout& page : out.Atlas.Pages)
  {
    out.PageDims.push_back(page.Dims);
    usedTexels += page.UsedTexels;
  }
  out.AtlasDims = out.PageDims.empty() ? glm::ivec3(0) : out.PageDims[0];
  const int64_t totalTexels = out.Atlas.TotalTexels();
  out.AtlasWaste = totalTexels > 0
    ? (out.Atlas.Pages.size() == 1 ? 1.0 - out.Atlas.Pages[0].Efficiency
                                   : 1.0 - static_cast<double>(usedTexels) / totalTexels)
    : 0.0;
  report(0.9, "the scalar range");
  if (!FiniteValueRange(h, out.ScalarRange) && !h.Grids.empty())
  {
    throw std::runtime_error("the array '" + h.ArrayName +
      "' holds no finite value (NaN or +-Inf in every cell): nothing to render");
  }
  out.TreeBytes =
    static_cast<long long>(KdTreeTextureBytes(enc.Tree, out.BrickLocalDataNodeTexels)) +
    static_cast<long long>(out.RopeTexels.Bytes());
  const long long treeBytes = out.TreeBytes;
  out.BrickBytes = static_cast<long long>(SeparateBrickBytes(h));
  out.BindlessBytes =
    treeBytes + out.BrickBytes + static_cast<long long>(HandleTextureBytes(h.Grids.size()));
  out.PackedBytes = out.PackingError.empty()
    ? treeBytes + totalTexels * static_cast<long long>(AtlasTexelBytes)
    : 0;
  out.Grids = static_cast<long long>(h.Grids.size());
  out.TreeTexels = std::move(enc.Tree);
  report(1.0, "done");
  out.Data = std::move(h);
  return out;
}

void RefreshValues(RayCastingData& data, Hierarchy h, bool deferNodeRanges)
{
  data.WaitForNodeRanges(); // the previous step's blocks, if still pending
  if (!data.NodeBlocks || !SameStructure(data.Data, h))
  {
    throw std::logic_error("RefreshValues: the new step's hierarchy is not the built one");
  }
  double range[2];
  if (!FiniteValueRange(h, range) && !h.Grids.empty())
  {
    throw std::runtime_error("the array '" + h.ArrayName +
      "' holds no finite value (NaN or +-Inf in every cell): nothing to render");
  }
  std::copy(range, range + 2, data.ScalarRange);
  data.NodeRanges.clear();
  if (deferNodeRanges)
  {
    data.PendingNodeRanges = std::async(std::launch::async,
      [hierarchy = h, blocks = data.NodeBlocks, count = data.DataNodes] {
        return ComputeDataNodeRanges(hierarchy, *blocks, count);
      }).share();
  }
  else
  {
    data.NodeRanges = ComputeDataNodeRanges(h, *data.NodeBlocks, data.DataNodes);
  }
  data.Data = std::move(h);
}

} // namespace amrsp
