// SPDX-License-Identifier: BSD-3-Clause
// The CPU kD-tree integrator: the shader's traversal, sampling and compositing on the CPU.
#include "amrsp/Render.h"

#include "KdTreeRays.h"
#include "RayIntegration.h"

#include "amrsp/BrickAtlas.h"
#include "amrsp/EmptySpace.h"
#include "amrsp/FinestCellLocator.h"
#include "amrsp/KdTraversal.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/SampleStep.h"
#include "amrsp/Shading.h"
#include "amrsp/VertexData.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

namespace amrsp
{

using namespace integration;

namespace
{

/// Trilinear lookup in the atlas at texel coordinate `u` (texel i at u = i), with the eight
/// texels clamped into [lo, hi]: the vertex texels of one kD node.
float AtlasTrilinear(
  const BrickAtlas& atlas, const glm::vec3& u, const glm::ivec3& lo, const glm::ivec3& hi)
{
  const glm::vec3 c = glm::clamp(u, glm::vec3(lo), glm::vec3(hi));
  const glm::ivec3 base = glm::min(glm::ivec3(glm::floor(c)), glm::max(hi - 1, lo));
  const glm::vec3 w = c - glm::vec3(base);
  float sum = 0.0f;
  for (int corner = 0; corner < 8; ++corner)
  {
    const glm::ivec3 o(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const float weight =
      (o.x ? w.x : 1.0f - w.x) * (o.y ? w.y : 1.0f - w.y) * (o.z ? w.z : 1.0f - w.z);
    if (weight != 0.0f)
    {
      sum += weight * atlas.At(glm::min(base + o, hi));
    }
  }
  return sum;
}

/// Point location in the encoded tree, as the shader's amrspLocateDataNode: from the root to the
/// leaf containing p (level-0 index units); a point on a split plane goes to the upper side (the
/// cell it starts). Returns the data index (0: empty leaf or outside the root box) and the
/// node's box, computed as the traversal computes node boxes.
uint32_t LocateDataNode(const EncodedKdTree& tree, const glm::vec3& p, glm::vec3& lo, glm::vec3& hi)
{
  using namespace layout;
  lo = tree.RootLo;
  hi = tree.RootHi;
  for (int a = 0; a < 3; ++a)
  {
    if (!(p[a] >= lo[a] && p[a] < hi[a]))
    {
      return 0;
    }
  }
  uvec2 texel = tree.Tree.Texels[0];
  for (;;)
  {
    const uint child = amrspNodeFirstChild(texel);
    if (child == 0)
    {
      break;
    }
    const int axis = static_cast<int>(amrspNodeAxis(texel));
    const uint level = amrspNodeLevel(texel);
    const float plane =
      lo[axis] + static_cast<float>(amrspNodeSplit(texel)) * tree.LevelCellSize[level][axis];
    if (p[axis] < plane)
    {
      hi[axis] = plane;
      texel = tree.Tree.Texels[child];
    }
    else
    {
      lo[axis] = plane;
      texel = tree.Tree.Texels[child + 1];
    }
  }
  return amrspNodeData(texel);
}

/// The nearest cell value of the data node `data` (box lo, hi) at p: from the grid, or from the
/// atlas through the node's offset as the packing shader reads it.
float NodeCellValue(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  uint32_t data, const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& p)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  const glm::vec3 cellSize = tree.LevelCellSize[amrspDataLevel(dn)];
  if (atlas)
  {
    const glm::ivec3 first = glm::ivec3(glm::floor(lo / cellSize));
    const glm::ivec3 last = glm::ivec3(glm::ceil(hi / cellSize)) - 1;
    const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(p / cellSize)), first, last);
    return atlas->At(amrspDataOffset(dn) + cell - first);
  }
  return CellValue(
    h, static_cast<int32_t>(amrspDataBrick(dn)), glm::i64vec3(glm::floor(p / cellSize)));
}

/// Cell `cell` (any cell of the data node's grid, cells of its level) read through the data node
/// (box lo, hi): from the grid, or from the atlas at the node's offset + (cell - first cell), as
/// the shader's amrspFetchGridCell reads it.
float NodeGridCell(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  uint32_t data, const glm::vec3& lo, const glm::ivec3& cell)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  if (atlas)
  {
    const glm::ivec3 first = glm::ivec3(glm::floor(lo / tree.LevelCellSize[amrspDataLevel(dn)]));
    return atlas->At(amrspDataOffset(dn) + cell - first);
  }
  return CellValue(h, static_cast<int32_t>(amrspDataBrick(dn)), glm::i64vec3(cell));
}

/// A corner of the smooth reconstruction's dual cell that is no cell of the sample's grid: x, a
/// cell centre of level `level`. The leaf containing x, of level m: for m >= level its nearest
/// cell at x; for a coarser leaf (x lies outside the sample's level) the trilinear value of
/// level m at x, its corners the cells of the leaf's grid (covered or not) or, where that grid
/// has no such cell, the nearest cell of the leaf there. `fallback` outside every leaf.
float SmoothCornerKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& x, int level, float fallback)
{
  using namespace layout;
  glm::vec3 lo, hi;
  const uint32_t data = LocateDataNode(tree, x, lo, hi);
  if (data == 0)
  {
    return fallback;
  }
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int m = static_cast<int>(amrspDataLevel(dn));
  const float vx = NodeCellValue(h, tree, atlas, data, lo, hi, x);
  if (m >= level)
  {
    return vx;
  }
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  const glm::vec3 cellSize = tree.LevelCellSize[m];
  return DualCellInterpolate(x, cellSize,
    [&](const glm::vec3& c)
    {
      const glm::ivec3 cell = glm::ivec3(c);
      if (GridHasCell(h, g, glm::i64vec3(cell)))
      {
        return NodeGridCell(h, tree, atlas, data, lo, cell);
      }
      const glm::vec3 y = (c + 0.5f) * cellSize;
      glm::vec3 ylo, yhi;
      const uint32_t ydata = LocateDataNode(tree, y, ylo, yhi);
      return ydata != 0 ? NodeCellValue(h, tree, atlas, ydata, ylo, yhi, y) : vx;
    });
}

/// Smooth reconstruction (RenderSettings::SmoothCellData) at p for a sample of the data node
/// `data` (box lo, hi): trilinear in the dual cell of the node's level around p; a corner that is
/// a cell of the node's grid (covered by finer grids or not) takes that cell's value, any other
/// corner SmoothCornerKdTree's. Linear-exact across level boundaries where every grid's cells,
/// covered ones included, hold the field at their centres (docs/design.md, "Smooth cell-centred
/// data").
float SmoothKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& p, uint32_t data, const glm::vec3& lo, float fallback)
{
  using namespace layout;
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int level = static_cast<int>(amrspDataLevel(dn));
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  const glm::vec3 cellSize = tree.LevelCellSize[level];
  return DualCellInterpolate(p, cellSize,
    [&](const glm::vec3& c)
    {
      const glm::ivec3 cell = glm::ivec3(c);
      return GridHasCell(h, g, glm::i64vec3(cell))
        ? NodeGridCell(h, tree, atlas, data, lo, cell)
        : SmoothCornerKdTree(h, tree, atlas, (c + 0.5f) * cellSize, level, fallback);
    });
}

/// The cell-centred value the kD-tree integrator samples at p: point location, then the leaf's
/// nearest cell or, with `smooth`, the smooth reconstruction at the leaf's data level (the rule of
/// the sample loop). NaN outside every leaf with data; cellSize: the leaf's data-level cell size.
float SampleCellsKdTree(const Hierarchy& h, const EncodedKdTree& tree, const BrickAtlas* atlas,
  const glm::vec3& p, bool smooth, glm::vec3& cellSize)
{
  using namespace layout;
  glm::vec3 lo, hi;
  const uint32_t data = LocateDataNode(tree, p, lo, hi);
  if (data == 0)
  {
    return std::numeric_limits<float>::quiet_NaN();
  }
  const int level = static_cast<int>(amrspDataLevel(tree.DataNodes.Texels[data]));
  cellSize = tree.LevelCellSize[level];
  const float v = NodeCellValue(h, tree, atlas, data, lo, hi, p);
  return smooth ? SmoothKdTree(h, tree, atlas, p, data, lo, v) : v;
}

/// The sample step of each level (level-0 index units), as float like the shader's.
std::vector<float> LevelSampleSteps(const Hierarchy& h, double sampleDistanceFactor)
{
  std::vector<float> steps;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    steps.push_back(static_cast<float>(LevelSampleStep(h, l, sampleDistanceFactor)));
  }
  return steps;
}

/// A ray's traversal in the work counters: a ray that met the tree, its segments and the levels
/// its descents went down.
void CountTraversal(const std::vector<RaySegment>& segments, RenderStats& stats)
{
  stats.Rays += segments.empty() ? 0 : 1;
  stats.Segments += static_cast<long long>(segments.size());
  for (const RaySegment& seg : segments)
  {
    stats.DescentLevels += seg.Descent;
  }
}

/// The level-of-detail parameters of the view: pixel size per distance (perspective) or the
/// pixel size (parallel), with the threshold in pixels.
LevelOfDetail ViewLevelOfDetail(const Hierarchy& h, const RenderSettings& s)
{
  LevelOfDetail lod;
  lod.ThresholdPixels = s.LodThresholdPixels;
  lod.Spacing0 = glm::vec3(h.Spacing0);
  if (s.View.Parallel)
  {
    lod.ParallelPixelSize = static_cast<float>(2.0 * s.View.ParallelScale / s.Height);
  }
  else
  {
    lod.PixelSizePerDistance =
      static_cast<float>(2.0 * std::tan(glm::radians(s.View.ViewAngle) * 0.5) / s.Height);
  }
  return lod;
}

/// Per data node (index 0 unused), 1 where its value range is transparent under the transfer
/// function: the ranges of s.DataNodeRanges, or computed from the data.
/// @throws std::invalid_argument when s.DataNodeRanges belongs to another tree.
std::vector<char> TransparentDataNodes(
  const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s)
{
  std::vector<glm::vec2> computed;
  if (!s.DataNodeRanges)
  {
    computed = ComputeDataNodeRanges(h, tree);
  }
  const std::vector<glm::vec2>& ranges = s.DataNodeRanges ? *s.DataNodeRanges : computed;
  if (ranges.size() != static_cast<std::size_t>(tree.DataNodeCount + 1))
  {
    throw std::invalid_argument("the data-node ranges do not belong to this tree");
  }
  std::vector<char> transparent(ranges.size());
  for (std::size_t k = 0; k < ranges.size(); ++k)
  {
    transparent[k] = TransparentRange(s.Transfer, ranges[k].x, ranges[k].y) ? 1 : 0;
  }
  return transparent;
}

/// The value at `p` (level-0 index units) in a data segment of grid
/// `g` with cells of `cellSize`: from the packed atlas (the node's cells [first, last] start at
/// the data node's `offset`) when there is one, else from the grid; trilinear between vertices
/// for vertex-centred data, the nearest cell otherwise.
float SegmentSample(const Hierarchy& h, const BrickAtlas* atlas, int32_t g, const glm::vec3& p,
  const glm::vec3& cellSize, const glm::ivec3& first, const glm::ivec3& last,
  const glm::ivec3& offset)
{
  if (atlas && h.VertexCentred)
  {
    return AtlasTrilinear(*atlas, glm::vec3(offset) + p / cellSize - glm::vec3(first), offset,
      offset + last + 1 - first);
  }
  if (atlas)
  {
    const glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(p / cellSize)), first, last);
    return atlas->At(offset + cell - first);
  }
  if (h.VertexCentred)
  {
    return InterpolateVertices(h, g, glm::dvec3(p / cellSize) - glm::dvec3(h.Grids[g].Cells.Lo));
  }
  return CellValue(h, g, glm::i64vec3(glm::floor(p / cellSize)));
}

} // namespace

double SampleKdTreeAtPoint(
  const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p, glm::vec3& cellSize)
{
  using namespace layout;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (OutsideBox(glm::dvec3(p), glm::dvec3(tree.RootLo), glm::dvec3(tree.RootHi)))
  {
    return nan;
  }
  glm::vec3 lo = tree.RootLo;
  uvec2 texel = tree.Tree.Texels[0];
  for (;;)
  {
    const uint child = amrspNodeFirstChild(texel);
    if (child == 0u)
    {
      break;
    }
    const int axis = static_cast<int>(amrspNodeAxis(texel));
    const uint level = amrspNodeLevel(texel);
    const float plane =
      lo[axis] + static_cast<float>(amrspNodeSplit(texel)) * tree.LevelCellSize[level][axis];
    uint node = child;
    if (!(p[axis] < plane))
    {
      lo[axis] = plane;
      node = child + 1u;
    }
    texel = tree.Tree.Texels[node];
  }
  const uint data = amrspNodeData(texel);
  if (data == 0u)
  {
    return nan;
  }
  const uvec2 dn = tree.DataNodes.Texels[data];
  const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
  cellSize = tree.LevelCellSize[amrspDataLevel(dn)];
  if (h.VertexCentred)
  {
    return InterpolateVertices(h, g, glm::dvec3(p / cellSize) - glm::dvec3(h.Grids[g].Cells.Lo));
  }
  return CellValue(h, g, glm::i64vec3(glm::floor(p / cellSize)));
}

void SampleRayKdTree(const Hierarchy& h, const EncodedKdTree& tree, const glm::dvec3& origin,
  const glm::dvec3& direction, double sampleDistanceFactor, std::vector<TreeSample>& samples)
{
  using namespace layout;
  const glm::dvec3 o = (origin - h.Origin) / h.Spacing0;
  const glm::dvec3 d = direction / h.Spacing0;
  std::vector<RaySegment> segments;
  TraverseKdTree(tree, glm::vec3(o), glm::vec3(d), 0.0f, std::numeric_limits<float>::infinity(),
    LevelOfDetail(), segments);
  for (const RaySegment& s : segments)
  {
    if (s.Data == 0)
    {
      continue;
    }
    const int32_t g = static_cast<int32_t>(amrspDataBrick(tree.DataNodes.Texels[s.Data]));
    const glm::dvec3 ratio(h.CumulativeRatio(s.Level));
    const double step = LevelSampleStep(h, s.Level, sampleDistanceFactor);
    const double length = static_cast<double>(s.T1) - static_cast<double>(s.T0);
    const int n = std::max(1, static_cast<int>(std::ceil(length / step)));
    const double dt = length / n;
    for (int k = 0; k < n; ++k)
    {
      const double t = static_cast<double>(s.T0) + (k + static_cast<double>(SampleOffset)) * dt;
      const glm::dvec3 p = o + t * d;
      samples.push_back(TreeSample{ p, g, glm::i64vec3(glm::floor(p * ratio)) });
    }
  }
}

KdTreeRays::KdTreeRays(
  const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s, const BrickAtlas* atlas)
  : H(h)
  , Tree(tree)
  , S(s)
  , Atlas(atlas)
  , Lod(ViewLevelOfDetail(h, s))
  , StepOfLevel(LevelSampleSteps(h, s.SampleDistanceFactor))
  , Spacing(h.Spacing0)
  , WorldOrigin(h.Origin)
  , Skip(s.SkipEmptySpace && s.Blend == BlendMode::Composite)
  , IsoValues(SortedIsoValues(s))
  , Shaded(s.Light.Shade || s.Light.Shadows)
  , SmoothCells(s.SmoothCellData && !h.VertexCentred)
{
  RequireValues(h);
  // empty-space skipping: per data node, whether its value range is transparent under this
  // transfer function (the ranges depend on the data only)
  if (Skip)
  {
    Transparent = TransparentDataNodes(h, tree, s);
  }
  Shading = MakeShadingContext(s.Light, s.Transfer, h.Origin, h.Spacing0, glm::dvec3(tree.RootLo),
    glm::dvec3(tree.RootHi), s.View.Position, s.View.FocalPoint);
  // iso-surface bisection and shadow rays read what the samples read (nearest or smooth); the
  // gradient's neighbours likewise
  Lookup =
    SmoothCells ? KdTreePointLookup(h, tree, true, atlas) : KdTreePointLookup(h, tree, false);
  if (SmoothCells)
  {
    Shading.Neighbours = Lookup;
  }
  Shading.CellStencil = !SmoothCells && !h.VertexCentred;
}

glm::vec4 KdTreeRays::Pixel(int i, int j, std::vector<RaySegment>& segments, RenderStats& stats,
  std::vector<SegmentWork>* work) const
{
  using namespace layout;
  const Hierarchy& h = H;
  const RenderSettings& s = S;
  glm::dvec3 wo, wd;
  s.View.Ray(s.Width, s.Height, i + 0.5, j + 0.5, wo, wd);
  const glm::vec3 o = (glm::vec3(wo) - WorldOrigin) / Spacing;
  const glm::vec3 d = glm::vec3(wd) / Spacing;
  segments.clear();
  if (work)
  {
    work->clear();
  }
  float tMax = std::numeric_limits<float>::infinity();
  glm::dvec3 background = s.Background, hitColour;
  double hit = 0.0;
  if (s.Opaque && s.Opaque(wo, wd, hit, hitColour))
  {
    tMax = static_cast<float>(hit);
    background = hitColour;
  }
  double clip0, clip1;
  if (ClipInterval(s, wo, wd, clip0, clip1))
  {
    TraverseKdTree(Tree, o, d, static_cast<float>(std::max(0.0, clip0)),
      static_cast<float>(std::min(static_cast<double>(tMax), clip1)), Lod, segments, false,
      s.Ropes);
  }
  CountTraversal(segments, stats);
  Accumulator<float> acc(s.Blend);
  IsoSurfaceTracker iso(Shading, Lookup, IsoValues, -wd);
  glm::dvec3 isoColour(0.0);
  double isoAlpha = 0.0;
  for (const RaySegment& seg : segments)
  {
    // the shader leaves its segment loop once the ray is opaque enough
    if (acc.Done(s.OpacityThreshold))
    {
      break;
    }
    SegmentWork* step = nullptr;
    if (work)
    {
      work->emplace_back();
      step = &work->back();
      step->Descent = seg.Descent;
      step->LodChecks = seg.LodChecks;
      step->FromFar = seg.FromFar;
      step->FromRope = seg.FromRope;
      step->Data = seg.Data != 0;
    }
    if (seg.Data == 0)
    {
      iso.Break();
      continue;
    }
    const uvec2 dn = Tree.DataNodes.Texels[seg.Data];
    const int32_t g = static_cast<int32_t>(amrspDataBrick(dn));
    const glm::vec3 cellSize = Tree.LevelCellSize[seg.Level];
    const float length = seg.T1 - seg.T0;
    const int n = std::max(1, static_cast<int>(std::ceil(length / StepOfLevel[seg.Level])));
    const float dt = length / static_cast<float>(n);
    ++stats.DataSegments;
    if (Skip && Transparent[seg.Data])
    {
      ++stats.SkippedSegments;
      stats.SkippedSamples += n;
      if (step)
      {
        step->Skipped = true;
      }
      continue;
    }
    // packing path: the node's first cell sits at the data node's atlas offset; cells of
    // the node are [first, last] (clamped so float error never reaches a neighbour brick)
    const glm::ivec3 first = glm::ivec3(glm::floor(seg.NodeLo / cellSize));
    const glm::ivec3 last = glm::ivec3(glm::ceil(seg.NodeHi / cellSize)) - 1;
    const glm::ivec3 offset = amrspDataOffset(dn);
    for (int k = 0; k < n; ++k)
    {
      const float t = seg.T0 + (static_cast<float>(k) + SampleOffset) * dt;
      const glm::vec3 p = o + t * d;
      float v = SegmentSample(h, Atlas, g, p, cellSize, first, last, offset);
      if (SmoothCells)
      {
        v = SmoothKdTree(h, Tree, Atlas, p, seg.Data, seg.NodeLo, v);
      }
      ++stats.Samples;
      if (step)
      {
        ++step->Samples;
      }
      if (s.Blend == BlendMode::IsoSurface)
      {
        if (std::isnan(v))
        {
          iso.Break();
        }
        else
        {
          iso.Sample(glm::dvec3(p), v, isoColour, isoAlpha);
        }
        continue;
      }
      const std::function<glm::dvec3(const glm::dvec3&)> shade = [&](const glm::dvec3& rgb)
      { return ShadeSample(Shading, Lookup, rgb, glm::dvec3(p), v, glm::dvec3(cellSize), -wd); };
      acc.Add(s.Transfer, v, dt, Shaded ? &shade : nullptr);
      if (acc.Done(s.OpacityThreshold))
      {
        break;
      }
    }
  }
  stats.TerminatedRays += acc.Done(s.OpacityThreshold) ? 1 : 0;
  if (s.Blend == BlendMode::IsoSurface)
  {
    acc.Color = glm::vec3(isoColour);
    acc.Alpha = static_cast<float>(isoAlpha);
  }
  return acc.Pixel(s.Transfer, background);
}

Image RenderKdTree(
  const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s, const BrickAtlas* atlas)
{
  const KdTreeRays rays(h, tree, s, atlas);
  Image img;
  img.Width = s.Width;
  img.Height = s.Height;
  img.Pixels.resize(static_cast<std::size_t>(s.Width) * s.Height);
  StatsSink sink;
  sink.Target = s.Stats;
  if (s.Stats)
  {
    *s.Stats = RenderStats();
  }
  ForEachRow(
    s.Height, s.Threads,
    [&](int j)
    {
      std::vector<RaySegment> segments;
      RenderStats rowStats;
      for (int i = 0; i < s.Width; ++i)
      {
        img.Pixels[static_cast<std::size_t>(j) * s.Width + i] =
          rays.Pixel(i, j, segments, rowStats, nullptr);
      }
      sink.Add(rowStats);
    },
    s.Progress);
  return img;
}

float SampleKdTreePoint(
  const Hierarchy& h, const EncodedKdTree& tree, const glm::vec3& p, bool smooth)
{
  glm::vec3 ignored;
  return SampleCellsKdTree(h, tree, nullptr, p, smooth, ignored);
}

PointLookup KdTreePointLookup(
  const Hierarchy& h, const EncodedKdTree& tree, bool smooth, const BrickAtlas* atlas)
{
  if (!smooth || h.VertexCentred)
  {
    return [&h, &tree](const glm::dvec3& q, glm::dvec3& cellSize)
    {
      glm::vec3 size(1.0f);
      const double v = SampleKdTreeAtPoint(h, tree, glm::vec3(q), size);
      cellSize = glm::dvec3(size);
      return v;
    };
  }
  return [&h, &tree, atlas](const glm::dvec3& q, glm::dvec3& cellSize)
  {
    glm::vec3 size(1.0f);
    const double v = SampleCellsKdTree(h, tree, atlas, glm::vec3(q), true, size);
    cellSize = glm::dvec3(size);
    return v;
  };
}
} // namespace amrsp
