// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/WorkCounters.h"

#include "KdTreeRays.h"
#include "RayIntegration.h"

#include "amrsp/KdTraversal.h"
#include "amrsp/KdTreeLayout.h"
#include "amrsp/SampleStep.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace amrsp
{

using namespace integration;

namespace
{

/// Per-ray counts of the rays that entered the root box, and the tiles' lockstep steps.
struct WorkTally
{
  std::vector<long long> Segments, DescentSteps, Samples, TexelFetches, Steps;
  long long LockstepSteps = 0;
  long long FlatLoopSteps = 0;
  long long Fragments = 0;

  void AddRay(long long segments, long long descent, long long samples, long long fetches)
  {
    Segments.push_back(segments);
    DescentSteps.push_back(descent);
    Samples.push_back(samples);
    TexelFetches.push_back(fetches);
    Steps.push_back(segments + descent + samples);
  }

  void Merge(WorkTally& other)
  {
    auto append = [](std::vector<long long>& to, const std::vector<long long>& from)
    { to.insert(to.end(), from.begin(), from.end()); };
    append(Segments, other.Segments);
    append(DescentSteps, other.DescentSteps);
    append(Samples, other.Samples);
    append(TexelFetches, other.TexelFetches);
    append(Steps, other.Steps);
    LockstepSteps += other.LockstepSteps;
    FlatLoopSteps += other.FlatLoopSteps;
    Fragments += other.Fragments;
  }
};

/// Mean and 95th percentile (nearest rank) of `v`; reorders it.
WorkDistribution Distribution(std::vector<long long>& v)
{
  WorkDistribution d;
  if (v.empty())
  {
    return d;
  }
  long double sum = 0.0L;
  for (long long x : v)
  {
    sum += static_cast<long double>(x);
  }
  d.Mean = static_cast<double>(sum / static_cast<long double>(v.size()));
  const std::size_t rank =
    static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(v.size()))) - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(rank), v.end());
  d.P95 = static_cast<double>(v[rank]);
  return d;
}

long long TileCount(const RenderSettings& s)
{
  const long long across = (s.Width + WorkTileWidth - 1) / WorkTileWidth;
  const long long down = (s.Height + WorkTileHeight - 1) / WorkTileHeight;
  return across * down;
}

WorkSummary Summarize(WorkTally& t, const RenderSettings& s)
{
  WorkSummary w;
  w.Pixels = static_cast<long long>(s.Width) * s.Height;
  w.Tiles = TileCount(s);
  w.Rays = static_cast<long long>(t.Steps.size());
  long long steps = 0;
  for (long long x : t.Steps)
  {
    steps += x;
  }
  w.Segments = Distribution(t.Segments);
  w.DescentSteps = Distribution(t.DescentSteps);
  w.Samples = Distribution(t.Samples);
  w.TexelFetches = Distribution(t.TexelFetches);
  w.Steps = Distribution(t.Steps);
  const double lanes = static_cast<double>(WorkTileWidth * WorkTileHeight) * w.Tiles;
  static_assert(WorkTileWidth * WorkTileHeight == 32, "a SIMT group of 32 lanes");
  w.StepsPerPixel = w.Pixels > 0 ? static_cast<double>(steps) / static_cast<double>(w.Pixels) : 0.0;
  w.LockstepStepsPerPixel = lanes > 0.0 ? static_cast<double>(t.LockstepSteps) / lanes : 0.0;
  w.FlatLoopStepsPerPixel = lanes > 0.0 ? static_cast<double>(t.FlatLoopSteps) / lanes : 0.0;
  w.LockstepEfficiency =
    w.LockstepStepsPerPixel > 0.0 ? w.StepsPerPixel / (32.0 * w.LockstepStepsPerPixel) : 0.0;
  w.FragmentsPerPixel =
    w.Pixels > 0 ? static_cast<double>(t.Fragments) / static_cast<double>(w.Pixels) : 0.0;
  return w;
}

/// Runs tile(x0, y0, tally) for every 8 x 4 tile of the image, tile rows spread over threads,
/// and merges the threads' tallies.
template <class Tile>
WorkTally ForEachTile(const RenderSettings& s, const Tile& tile)
{
  const int bands = (s.Height + WorkTileHeight - 1) / WorkTileHeight;
  WorkTally total;
  std::mutex lock;
  ForEachRow(
    bands, s.Threads,
    [&](int band)
    {
      WorkTally mine;
      for (int x0 = 0; x0 < s.Width; x0 += WorkTileWidth)
      {
        tile(x0, band * WorkTileHeight, mine);
      }
      std::lock_guard<std::mutex> guard(lock);
      total.Merge(mine);
    },
    s.Progress);
  return total;
}

} // namespace

long long RayTexelFetches(const std::vector<SegmentWork>& segments, const FetchModel& m)
{
  const bool brickLookup = m.Storage != DataStorage::PackedAtlas;
  const long long dataReads =
    m.VertexCentred && m.Storage != DataStorage::PackedAtlas ? 8 : 1; // packing: hardware trilinear
  const long long perSample =
    dataReads + (m.TransferPerSample ? 1 : 0) + (brickLookup && !m.BrickLookupPerSegment ? 1 : 0);
  long long fetches = 1; // the root node
  for (const SegmentWork& w : segments)
  {
    fetches += (w.FromFar ? 1 : 0) + (w.FromRope ? 4 : 0) + w.Descent + w.LodChecks;
    if (!w.Data)
    {
      continue;
    }
    fetches += m.SkipFlags ? 1 : 0;
    if (w.Skipped)
    {
      continue;
    }
    fetches += 1 + (brickLookup && m.BrickLookupPerSegment ? 1 : 0); // data node, brick lookup
    fetches += perSample * w.Samples;
  }
  return fetches;
}

long long TileLockstepSteps(const std::vector<std::vector<SegmentWork>>& rays)
{
  std::size_t iterations = 0;
  for (const std::vector<SegmentWork>& r : rays)
  {
    iterations = std::max(iterations, r.size());
  }
  long long steps = 0;
  for (std::size_t k = 0; k < iterations; ++k)
  {
    long long descent = 0, samples = 0;
    for (const std::vector<SegmentWork>& r : rays)
    {
      if (k < r.size())
      {
        descent = std::max(descent, static_cast<long long>(r[k].Descent));
        samples = std::max(samples, static_cast<long long>(r[k].Samples));
      }
    }
    steps += 1 + descent + samples;
  }
  return steps;
}

long long TileFlatLoopSteps(const std::vector<std::vector<SegmentWork>>& rays)
{
  // each lane's operations in order: per segment 1 + Descent traversal operations, then Samples
  // samples; a lane's position is (segment, operation within it)
  struct Lane
  {
    const std::vector<SegmentWork>* Segments;
    std::size_t Segment = 0;
    uint32_t Op = 0;
  };
  std::vector<Lane> lanes;
  for (const std::vector<SegmentWork>& r : rays)
  {
    if (!r.empty())
    {
      lanes.push_back(Lane{ &r });
    }
  }
  long long steps = 0;
  for (;;)
  {
    bool traverse = false, sample = false;
    for (Lane& l : lanes)
    {
      if (l.Segment >= l.Segments->size())
      {
        continue;
      }
      const SegmentWork& w = (*l.Segments)[l.Segment];
      const bool isTraversal = l.Op < 1 + w.Descent;
      traverse = traverse || isTraversal;
      sample = sample || !isTraversal;
      if (++l.Op >= 1 + w.Descent + w.Samples)
      {
        ++l.Segment;
        l.Op = 0;
      }
    }
    if (!traverse && !sample)
    {
      return steps;
    }
    steps += (traverse ? 1 : 0) + (sample ? 1 : 0);
  }
}

WorkSummary MeasureSinglePassWork(const Hierarchy& h, const EncodedKdTree& tree,
  const RenderSettings& s, const FetchModel& fetches, const BrickAtlas* atlas)
{
  const KdTreeRays rays(h, tree, s, atlas);
  WorkTally tally = ForEachTile(s,
    [&](int x0, int y0, WorkTally& t)
    {
      std::vector<RaySegment> scratch;
      std::vector<std::vector<SegmentWork>> tile;
      RenderStats stats;
      for (int j = y0; j < std::min(y0 + WorkTileHeight, s.Height); ++j)
      {
        for (int i = x0; i < std::min(x0 + WorkTileWidth, s.Width); ++i)
        {
          const long long raysBefore = stats.Rays;
          tile.emplace_back();
          rays.Pixel(i, j, scratch, stats, &tile.back());
          if (stats.Rays == raysBefore)
          {
            tile.pop_back(); // the ray missed the root box: an idle lane
            continue;
          }
          long long descent = 0, samples = 0;
          for (const SegmentWork& w : tile.back())
          {
            descent += w.Descent;
            samples += w.Samples;
          }
          t.AddRay(static_cast<long long>(tile.back().size()), descent, samples,
            RayTexelFetches(tile.back(), fetches));
        }
      }
      t.LockstepSteps += TileLockstepSteps(tile);
      t.FlatLoopSteps += TileFlatLoopSteps(tile);
    });
  return Summarize(tally, s);
}

WorkSummary MeasureMultipassWork(
  const Hierarchy& h, const EncodedKdTree& tree, const RenderSettings& s)
{
  const std::vector<float> stepOfLevel = [&]
  {
    std::vector<float> steps;
    for (int l = 0; l < h.NumberOfLevels(); ++l)
    {
      steps.push_back(static_cast<float>(LevelSampleStep(h, l, s.SampleDistanceFactor)));
    }
    return steps;
  }();
  const glm::vec3 spacing(h.Spacing0), worldOrigin(h.Origin);
  std::vector<char> drawn(static_cast<std::size_t>(tree.NodeCount) + 1, 0);
  std::mutex drawnLock;
  WorkTally tally = ForEachTile(s,
    [&](int x0, int y0, WorkTally& t)
    {
      std::vector<RaySegment> segments;
      std::unordered_map<uint32_t, long long> mostSamples; // per draw (leaf) in this tile
      for (int j = y0; j < std::min(y0 + WorkTileHeight, s.Height); ++j)
      {
        for (int i = x0; i < std::min(x0 + WorkTileWidth, s.Width); ++i)
        {
          glm::dvec3 wo, wd;
          s.View.Ray(s.Width, s.Height, i + 0.5, j + 0.5, wo, wd);
          double clip0, clip1;
          segments.clear();
          if (ClipInterval(s, wo, wd, clip0, clip1))
          {
            TraverseKdTree(tree, (glm::vec3(wo) - worldOrigin) / spacing, glm::vec3(wd) / spacing,
              static_cast<float>(std::max(0.0, clip0)), static_cast<float>(clip1), LevelOfDetail(),
              segments);
          }
          if (segments.empty())
          {
            continue;
          }
          long long fragments = 0, samples = 0;
          for (const RaySegment& seg : segments)
          {
            if (seg.Data == 0)
            {
              continue;
            }
            const int n =
              std::max(1, static_cast<int>(std::ceil((seg.T1 - seg.T0) / stepOfLevel[seg.Level])));
            ++fragments;
            samples += n;
            long long& most = mostSamples[seg.Node];
            most = std::max(most, static_cast<long long>(n));
          }
          // a fragment reads its samples' atlas texels and the transfer table
          t.AddRay(fragments, 0, samples, 2 * samples);
          t.Fragments += fragments;
        }
      }
      std::lock_guard<std::mutex> guard(drawnLock);
      for (const auto& draw : mostSamples)
      {
        t.LockstepSteps += 1 + draw.second;
        drawn[draw.first] = 1;
      }
    });
  WorkSummary w = Summarize(tally, s);
  w.Draws = static_cast<long long>(std::count(drawn.begin(), drawn.end(), 1));
  return w;
}

} // namespace amrsp
