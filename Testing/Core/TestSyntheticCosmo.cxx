// SPDX-License-Identifier: BSD-3-Clause
// Tests of the synthetic cosmology-like AMR hierarchy generator (amrsp/SyntheticCosmo.h).

#include "amrsp/SyntheticCosmo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace
{

using amrsp::Box;
using amrsp::CosmoParameters;
using amrsp::Grid;
using amrsp::Hierarchy;

CosmoParameters Params(const std::string& spec, bool values)
{
  CosmoParameters p = amrsp::ParseCosmoParameters(spec);
  p.GenerateValues = values;
  return p;
}

/// Boxes bucketed on a uniform lattice of `bucket` cells, for neighbour queries.
class BoxIndex
{
public:
  BoxIndex(const std::vector<Box>& boxes, int64_t bucket)
    : Bucket(std::max<int64_t>(1, bucket))
  {
    for (std::size_t i = 0; i < boxes.size(); ++i)
    {
      this->ForBuckets(boxes[i], [&](uint64_t key) { this->Map[key].push_back(i); });
    }
  }

  /// Indices of the boxes that share a bucket with `b`, each once, ascending.
  std::vector<std::size_t> Near(const Box& b) const
  {
    std::vector<std::size_t> out;
    this->ForBuckets(b,
      [&](uint64_t key)
      {
        const auto it = this->Map.find(key);
        if (it != this->Map.end())
        {
          out.insert(out.end(), it->second.begin(), it->second.end());
        }
      });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

private:
  int64_t Bucket;
  std::unordered_map<uint64_t, std::vector<std::size_t>> Map;

  template <class F>
  void ForBuckets(const Box& b, F&& f) const
  {
    const glm::i64vec3 lo = b.Lo / this->Bucket;
    const glm::i64vec3 hi = (b.Hi - int64_t(1)) / this->Bucket;
    for (int64_t k = lo.z; k <= hi.z; ++k)
    {
      for (int64_t j = lo.y; j <= hi.y; ++j)
      {
        for (int64_t i = lo.x; i <= hi.x; ++i)
        {
          f(static_cast<uint64_t>(i) | (static_cast<uint64_t>(j) << 21) |
            (static_cast<uint64_t>(k) << 42));
        }
      }
    }
  }
};

std::vector<Box> LevelBoxes(const Hierarchy& h, int level)
{
  std::vector<Box> boxes;
  for (const Grid& g : h.Grids)
  {
    if (g.Level == level)
    {
      boxes.push_back(g.Cells);
    }
  }
  return boxes;
}

int64_t MedianExtent(const std::vector<Box>& boxes)
{
  std::vector<int64_t> e;
  for (const Box& b : boxes)
  {
    const glm::i64vec3 x = b.Extent();
    e.push_back(std::max(x.x, std::max(x.y, x.z)));
  }
  if (e.empty())
  {
    return 1;
  }
  std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
  return e[e.size() / 2];
}

/// Checks the structural invariants: levels sorted, SourceId, every level non-empty, boxes
/// non-empty and inside the domain, no overlap within a level, root grids tile the domain and
/// every level-l grid lies inside the union of level l-1 grids.
void ExpectWellFormed(const Hierarchy& h)
{
  const int levels = h.NumberOfLevels();
  ASSERT_GE(levels, 1);
  EXPECT_EQ(h.RefinementRatio[0], glm::ivec3(1));
  for (int l = 1; l < levels; ++l)
  {
    EXPECT_EQ(h.RefinementRatio[static_cast<std::size_t>(l)], glm::ivec3(2));
  }
  EXPECT_EQ(h.ArrayName, "Density");
  EXPECT_FALSE(h.VertexCentred);
  EXPECT_EQ(h.Origin, glm::dvec3(0.0));
  const double n0d = 1.0 / h.Spacing0.x;
  const int64_t n0 = static_cast<int64_t>(std::llround(n0d));
  EXPECT_EQ(h.Spacing0, glm::dvec3(1.0 / static_cast<double>(n0)));

  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    ASSERT_EQ(h.Grids[g].SourceId, static_cast<int64_t>(g));
    ASSERT_FALSE(h.Grids[g].Cells.Empty());
    ASSERT_GE(h.Grids[g].Level, 0);
    ASSERT_LT(h.Grids[g].Level, levels);
    if (g > 0)
    {
      ASSERT_LE(h.Grids[g - 1].Level, h.Grids[g].Level) << "grids not sorted by level";
    }
    const Box domain = h.ToLevel(Box{ glm::i64vec3(0), glm::i64vec3(n0) }, 0, h.Grids[g].Level);
    ASSERT_TRUE(domain.Contains(h.Grids[g].Cells)) << "grid " << g << " outside the domain";
  }

  std::vector<Box> previous;
  for (int l = 0; l < levels; ++l)
  {
    const std::vector<Box> boxes = LevelBoxes(h, l);
    ASSERT_FALSE(boxes.empty()) << "level " << l << " has no grids";

    // No overlap within the level.
    const BoxIndex same(boxes, MedianExtent(boxes));
    for (std::size_t i = 0; i < boxes.size(); ++i)
    {
      for (std::size_t j : same.Near(boxes[i]))
      {
        ASSERT_FALSE(j != i && boxes[i].Overlaps(boxes[j]))
          << "level " << l << " grids " << i << " and " << j << " overlap";
      }
    }

    if (l == 0)
    {
      int64_t cells = 0;
      for (const Box& b : boxes)
      {
        cells += b.Cells();
      }
      EXPECT_EQ(cells, n0 * n0 * n0) << "root grids do not tile the domain";
    }
    else
    {
      // Parents are disjoint, so a child is covered by their union exactly when the volumes of
      // its intersections with them add up to its own volume.
      std::vector<Box> refined;
      for (const Box& b : previous)
      {
        refined.push_back(b.Refined(glm::i64vec3(2)));
      }
      const BoxIndex parents(refined, MedianExtent(refined));
      for (std::size_t i = 0; i < boxes.size(); ++i)
      {
        int64_t covered = 0;
        for (std::size_t j : parents.Near(boxes[i]))
        {
          covered += boxes[i].Intersection(refined[j]).Cells();
        }
        ASSERT_EQ(covered, boxes[i].Cells())
          << "level " << l << " grid " << i << " is not properly nested";
      }
    }
    previous = boxes;
  }
}

void ExpectStatistics(const Hierarchy& h, const CosmoParameters& p)
{
  const amrsp::CosmoStatistics s = amrsp::ComputeCosmoStatistics(h);
  EXPECT_EQ(h.NumberOfLevels(), p.Levels);
  EXPECT_EQ(static_cast<int>(s.GridsPerLevel.size()), p.Levels);
  EXPECT_NEAR(static_cast<double>(s.Grids), static_cast<double>(p.Grids), 0.03 * p.Grids)
    << amrsp::FormatCosmoParameters(p);
  EXPECT_NEAR(static_cast<double>(s.Cells), static_cast<double>(p.Cells), 0.10 * p.Cells)
    << amrsp::FormatCosmoParameters(p);
  EXPECT_EQ(s.Cells, h.TotalCells());
}

bool SameBoxes(const Hierarchy& a, const Hierarchy& b)
{
  if (a.Grids.size() != b.Grids.size() || a.Spacing0 != b.Spacing0)
  {
    return false;
  }
  for (std::size_t i = 0; i < a.Grids.size(); ++i)
  {
    if (a.Grids[i].Level != b.Grids[i].Level || !(a.Grids[i].Cells == b.Grids[i].Cells))
    {
      return false;
    }
  }
  return true;
}

/// 0, stride, 2 stride, ... below n, and n - 1.
std::vector<int64_t> SampleIndices(int64_t n, int64_t stride)
{
  std::vector<int64_t> out;
  for (int64_t i = 0; i < n; i += stride)
  {
    out.push_back(i);
  }
  if (out.back() != n - 1)
  {
    out.push_back(n - 1);
  }
  return out;
}

template <class F>
void ExpectInvalid(F&& f, const std::string& mention)
{
  try
  {
    f();
    ADD_FAILURE() << "expected std::invalid_argument mentioning '" << mention << "'";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos)
      << "message '" << e.what() << "' does not mention '" << mention << "'";
  }
}

} // namespace

TEST(SyntheticCosmo, ParserDefaults)
{
  const CosmoParameters d;
  for (const char* spec : { "", "   " })
  {
    const CosmoParameters p = amrsp::ParseCosmoParameters(spec);
    EXPECT_EQ(p.Grids, d.Grids);
    EXPECT_EQ(p.Levels, d.Levels);
    EXPECT_EQ(p.Cells, d.Cells);
    EXPECT_EQ(p.Seed, d.Seed);
    EXPECT_EQ(p.GenerateValues, d.GenerateValues);
  }
  EXPECT_EQ(d.Grids, 2666);
  EXPECT_EQ(d.Levels, 4);
  EXPECT_EQ(d.Cells, 19000000);
}

TEST(SyntheticCosmo, ParserAccepts)
{
  CosmoParameters p = amrsp::ParseCosmoParameters("grids=50,levels=3,cells=200k,seed=7");
  EXPECT_EQ(p.Grids, 50);
  EXPECT_EQ(p.Levels, 3);
  EXPECT_EQ(p.Cells, 200000);
  EXPECT_EQ(p.Seed, 7u);

  // Any order, any subset, spaces, key case, suffixes (also after decimals).
  p = amrsp::ParseCosmoParameters(" cells = 19M , GRIDS=2.5k ");
  EXPECT_EQ(p.Cells, 19000000);
  EXPECT_EQ(p.Grids, 2500);
  EXPECT_EQ(p.Levels, 4);
  p = amrsp::ParseCosmoParameters("cells=1.5M,grids=18K,seed=18446744073709551615");
  EXPECT_EQ(p.Cells, 1500000);
  EXPECT_EQ(p.Grids, 18000);
  EXPECT_EQ(p.Seed, 18446744073709551615ULL);
  p = amrsp::ParseCosmoParameters("cells=1G,grids=0.28M");
  EXPECT_EQ(p.Cells, 1000000000);
  EXPECT_EQ(p.Grids, 280000);
  EXPECT_EQ(amrsp::ParseCosmoParameters("cells=1.5G").Cells, 1500000000);
  p = amrsp::ParseCosmoParameters("levels=13,roots=27,values=0");
  EXPECT_EQ(p.Levels, 13);
  EXPECT_EQ(p.RootGrids, 27);
  EXPECT_FALSE(p.GenerateValues);

  // Round trip.
  const CosmoParameters q = amrsp::ParseCosmoParameters(amrsp::FormatCosmoParameters(p));
  EXPECT_EQ(q.Grids, p.Grids);
  EXPECT_EQ(q.Levels, p.Levels);
  EXPECT_EQ(q.Cells, p.Cells);
  EXPECT_EQ(q.Seed, p.Seed);
  EXPECT_EQ(q.RootGrids, p.RootGrids);
  EXPECT_EQ(q.GenerateValues, p.GenerateValues);
}

TEST(SyntheticCosmo, ParserRejects)
{
  auto parse = [](const char* s) { return [s]() { amrsp::ParseCosmoParameters(s); }; };
  ExpectInvalid(parse("grid=50"), "'grid'");                    // unknown key
  ExpectInvalid(parse("grids=abc"), "'abc'");                   // not a number
  ExpectInvalid(parse("grids=12x"), "'12x'");                   // bad suffix
  ExpectInvalid(parse("cells=19T"), "'19T'");                   // unsupported suffix
  ExpectInvalid(parse("cells=-5"), "'-5'");                     // negative
  ExpectInvalid(parse("levels=2k"), "'2k'");                    // no suffix for levels
  ExpectInvalid(parse("levels=0"), "levels");                   // out of range
  ExpectInvalid(parse("levels=31"), "levels");                  // out of range
  ExpectInvalid(parse("grids=0"), "grids");                     // out of range
  ExpectInvalid(parse("grids=1.2345k"), "'1.2345k'");           // not an integer
  ExpectInvalid(parse("grids=1.5"), "'1.5'");                   // decimals need a suffix
  ExpectInvalid(parse("seed=1k"), "'1k'");                      // no suffix for the seed
  ExpectInvalid(parse("seed=18446744073709551616"), "seed");    // overflow
  ExpectInvalid(parse("cells=99999999999999999999M"), "cells"); // overflow
  ExpectInvalid(parse("grids="), "grids");                      // empty value
  ExpectInvalid(parse("grids"), "'grids'");                     // not key=value
  ExpectInvalid(parse("grids=5,grids=6"), "'grids'");           // duplicate
  ExpectInvalid(parse("grids=50,,levels=3"), "empty item");     // empty item
  ExpectInvalid(parse("values=maybe"), "'maybe'");
}

TEST(SyntheticCosmo, ImpossibleRequestsThrow)
{
  auto gen = [](CosmoParameters p) { return [p]() { amrsp::GenerateCosmo(p); }; };
  CosmoParameters p = Params("grids=50,levels=3,cells=200k", false);
  p.Levels = 0;
  ExpectInvalid(gen(p), "levels");
  p.Levels = 31;
  ExpectInvalid(gen(p), "levels");
  // 8 root grids + 2 refined levels need at least 10 grids.
  ExpectInvalid(gen(Params("grids=9,levels=3,cells=200k", false)), "root grids");
  ExpectInvalid(gen(Params("grids=7,levels=2,cells=200k", false)), "root grids");
  // Fewer than 64 cells per grid on average.
  ExpectInvalid(gen(Params("grids=100,levels=3,cells=6000", false)), "cells too small");
  // With one level every grid is a root grid.
  ExpectInvalid(gen(Params("grids=5,levels=1,roots=3,cells=100k", false)), "roots");
  p = Params("grids=50,levels=3,cells=200k", false);
  p.Grids = 0;
  ExpectInvalid(gen(p), "grids");
}

TEST(SyntheticCosmo, SmallCaseStructureAndStatistics)
{
  const CosmoParameters p = Params("grids=50,levels=3,cells=200k", false);
  const Hierarchy h = amrsp::GenerateCosmo(p);
  ExpectWellFormed(h);
  ExpectStatistics(h, p);
  EXPECT_FALSE(h.HasValues());
  EXPECT_EQ(amrsp::ComputeCosmoStatistics(h).GridsPerLevel[0], 8); // 2x2x2 root grids
}

TEST(SyntheticCosmo, VariousSmallCases)
{
  for (const char* spec : { "grids=10,levels=3,cells=50k", "grids=200,levels=6,cells=1M,seed=3",
         "grids=120,levels=2,cells=400k,roots=27", "grids=1,levels=1,cells=1000",
         "grids=7,levels=1,cells=300k", "grids=64,levels=1,cells=262144" })
  {
    SCOPED_TRACE(spec);
    const CosmoParameters p = Params(spec, false);
    const Hierarchy h = amrsp::GenerateCosmo(p);
    ExpectWellFormed(h);
    ExpectStatistics(h, p);
  }
  // One level: exactly `grids` root grids tiling an N0^3 cube with N0^3 closest to `cells`.
  const Hierarchy h = amrsp::GenerateCosmo(Params("grids=64,levels=1,cells=262144", false));
  EXPECT_EQ(h.Grids.size(), 64u);
  EXPECT_EQ(h.TotalCells(), 262144);
  for (const Grid& g : h.Grids)
  {
    EXPECT_EQ(g.Cells.Extent(), glm::i64vec3(16)); // 4x4x4 root grids of 16^3
  }
}

TEST(SyntheticCosmo, DeterministicForASeed)
{
  const CosmoParameters p = Params("grids=60,levels=4,cells=300k,seed=11", true);
  const Hierarchy a = amrsp::GenerateCosmo(p);
  const Hierarchy b = amrsp::GenerateCosmo(p);
  ASSERT_TRUE(SameBoxes(a, b));
  ASSERT_TRUE(a.HasValues());
  ASSERT_TRUE(b.HasValues());
  for (std::size_t g = 0; g < a.Values.size(); ++g)
  {
    ASSERT_EQ(a.Values[g], b.Values[g]) << "grid " << g;
  }
  // Structure-only generation gives the same boxes.
  CosmoParameters noValues = p;
  noValues.GenerateValues = false;
  EXPECT_TRUE(SameBoxes(a, amrsp::GenerateCosmo(noValues)));

  // Another seed gives another hierarchy and another field.
  CosmoParameters other = p;
  other.Seed = 12;
  const Hierarchy c = amrsp::GenerateCosmo(other);
  EXPECT_FALSE(SameBoxes(a, c));
  const glm::dvec3 x(0.3, 0.6, 0.45);
  EXPECT_NE(amrsp::CosmoField(11)(x), amrsp::CosmoField(12)(x));
}

TEST(SyntheticCosmo, SameResultEverywhere)
{
  // Fingerprints of one seed's field and hierarchy, fixed when the generator was written. They
  // catch anything that makes the output depend on the compiler, the standard library or the
  // platform (std:: distributions, unspecified evaluation order of two random draws in one
  // expression, libm functions). A change of the generator's design must update them.
  const amrsp::CosmoField field(1);
  EXPECT_EQ(field.NumberOfHalos(), 2202u);
  EXPECT_NEAR(field(glm::dvec3(0.5)), 0.44365918951961614, 1e-13);
  EXPECT_NEAR(field(glm::dvec3(0.1, 0.2, 0.3)), 0.55800164509007522, 1e-13);
  EXPECT_NEAR(field(glm::dvec3(0.9, 0.05, 0.7)), 0.59815511092194762, 1e-13);

  const Hierarchy h = amrsp::GenerateCosmo(Params("grids=50,levels=3,cells=200k,seed=1", false));
  // FNV-1a over (level, lo, hi) of every grid, by value (independent of byte order).
  uint64_t hash = 14695981039346656037ULL;
  for (const Grid& g : h.Grids)
  {
    const int64_t v[7] = { g.Level, g.Cells.Lo.x, g.Cells.Lo.y, g.Cells.Lo.z, g.Cells.Hi.x,
      g.Cells.Hi.y, g.Cells.Hi.z };
    for (int64_t x : v)
    {
      for (int byte = 0; byte < 8; ++byte)
      {
        hash ^= (static_cast<uint64_t>(x) >> (8 * byte)) & 0xFFu;
        hash *= 1099511628211ULL;
      }
    }
  }
  EXPECT_EQ(hash, 0x2a11848fbf5da470ULL);
}

TEST(SyntheticCosmo, ValuesAreTheFieldAtCellCentres)
{
  const CosmoParameters p = Params("grids=50,levels=3,cells=200k,seed=5", true);
  const Hierarchy h = amrsp::GenerateCosmo(p);
  ASSERT_TRUE(h.HasValues());
  const amrsp::CosmoField field(p.Seed);
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const Grid& grid = h.Grids[g];
    const amrsp::GridValues& v = h.Values[g];
    ASSERT_EQ(static_cast<int64_t>(v.size()), grid.Cells.Cells());
    const glm::i64vec3 e = grid.Cells.Extent();
    const glm::dvec3 cell = h.CellSize(grid.Level);
    // Every cell of small grids, a stride of cells elsewhere (corners included).
    const int64_t stride = grid.Cells.Cells() > 4096 ? 7 : 1;
    for (int64_t k : SampleIndices(e.z, stride))
    {
      for (int64_t j : SampleIndices(e.y, stride))
      {
        for (int64_t i : SampleIndices(e.x, stride))
        {
          const glm::dvec3 index = (glm::dvec3(grid.Cells.Lo + glm::i64vec3(i, j, k)) + 0.5) * cell;
          const float expected = static_cast<float>(field(h.Origin + index * h.Spacing0));
          const float got = v[static_cast<std::size_t>(i + e.x * (j + e.y * k))];
          ASSERT_GT(got, 0.0f);
          // Same arithmetic in the same order: equal up to the last bit in practice; allow one
          // float ulp for compilers that contract differently in the two code paths.
          ASSERT_NEAR(got, expected, 1.2e-7f * std::fabs(expected))
            << "grid " << g << " cell " << i << "," << j << "," << k;
        }
      }
    }
  }
  // The convenience function agrees with the field.
  const Grid& last = h.Grids.back();
  const glm::dvec3 index = (glm::dvec3(last.Cells.Lo) + 0.5) * h.CellSize(last.Level);
  EXPECT_FLOAT_EQ(static_cast<float>(amrsp::CosmoDensity(p.Seed, h, index)), h.Values.back()[0]);
}

TEST(SyntheticCosmo, RefinementFollowsDensityPeaks)
{
  const CosmoParameters p = Params("grids=300,levels=6,cells=2M,seed=2", false);
  const Hierarchy h = amrsp::GenerateCosmo(p);
  const amrsp::CosmoField field(p.Seed);
  // Median density at grid centres rises with the level, far above the domain's median.
  std::vector<double> medians;
  for (int l = 0; l < h.NumberOfLevels(); ++l)
  {
    std::vector<double> d;
    for (const Grid& g : h.Grids)
    {
      if (g.Level == l)
      {
        d.push_back(field(0.5 * (h.WorldLo(g.Cells, l) + h.WorldHi(g.Cells, l))));
      }
    }
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    medians.push_back(d[d.size() / 2]);
  }
  for (int l = 2; l < h.NumberOfLevels(); ++l)
  {
    EXPECT_GT(medians[static_cast<std::size_t>(l)], medians[static_cast<std::size_t>(l - 1)])
      << "level " << l;
  }
  EXPECT_GT(medians.back(), 100.0 * medians[0]);

  // The finest level is concentrated: its bounding box is a small part of the domain.
  const int finest = h.NumberOfLevels() - 1;
  glm::dvec3 lo(1.0), hi(0.0);
  double volume = 0.0;
  for (const Grid& g : h.Grids)
  {
    if (g.Level == finest)
    {
      const glm::dvec3 a = h.WorldLo(g.Cells, finest), b = h.WorldHi(g.Cells, finest);
      lo = glm::min(lo, a);
      hi = glm::max(hi, b);
      volume += (b.x - a.x) * (b.y - a.y) * (b.z - a.z);
    }
  }
  EXPECT_LT(volume, 1e-3);
}

TEST(SyntheticCosmo, GridSizesVary)
{
  const Hierarchy h = amrsp::GenerateCosmo(Params("grids=2666,levels=4,cells=19M", false));
  for (int l = 1; l < h.NumberOfLevels(); ++l)
  {
    std::vector<int64_t> cells;
    std::vector<glm::i64vec3> extents;
    for (const Grid& g : h.Grids)
    {
      if (g.Level == l)
      {
        cells.push_back(g.Cells.Cells());
        extents.push_back(g.Cells.Extent());
      }
    }
    std::sort(cells.begin(), cells.end());
    const int64_t p10 = cells[cells.size() / 10];
    const int64_t p90 = cells[cells.size() * 9 / 10];
    EXPECT_GT(p90, 3 * p10) << "level " << l;
    std::sort(extents.begin(), extents.end(),
      [](const glm::i64vec3& a, const glm::i64vec3& b)
      { return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z); });
    const auto distinct = std::unique(extents.begin(), extents.end()) - extents.begin();
    EXPECT_GT(distinct, 20) << "level " << l;
  }
}

TEST(SyntheticCosmo, PaperTable1Sizes)
{
  // Structure only: the sizes of Kaehler & Abel 2013, Table 1.
  for (const char* spec : { "grids=2666,levels=4,cells=19M", "grids=18528,levels=4,cells=33M",
         "grids=39061,levels=13,cells=140M" })
  {
    SCOPED_TRACE(spec);
    const CosmoParameters p = Params(spec, false);
    const Hierarchy h = amrsp::GenerateCosmo(p);
    ExpectStatistics(h, p);
    ExpectWellFormed(h);
    EXPECT_FALSE(h.HasValues());
  }
}

// The time series: halos drift with the steps, the boxes change only at the regrid steps.
TEST(SyntheticCosmo, SeriesDriftsAndRegridsEveryKSteps)
{
  CosmoParameters p =
    amrsp::ParseCosmoParameters("grids=60,levels=4,cells=300k,seed=3,steps=5,regrid=2");
  EXPECT_EQ(p.Steps, 5);
  EXPECT_EQ(p.RegridEvery, 2);
  const CosmoParameters q = amrsp::ParseCosmoParameters(amrsp::FormatCosmoParameters(p));
  EXPECT_EQ(q.Steps, 5);
  EXPECT_EQ(q.RegridEvery, 2);
  EXPECT_THROW(amrsp::ParseCosmoParameters("steps=0"), std::invalid_argument);
  EXPECT_THROW(amrsp::ParseCosmoParameters("regrid=-1"), std::invalid_argument);

  std::vector<Hierarchy> steps;
  for (int s = 0; s < p.Steps; ++s)
  {
    steps.push_back(amrsp::GenerateCosmoStep(p, s));
    EXPECT_EQ(amrsp::CosmoRegridStep(p, s), s - s % 2);
  }
  EXPECT_THROW(amrsp::GenerateCosmoStep(p, 5), std::invalid_argument);
  // step 0 is the plain generator's, bit for bit
  const Hierarchy plain = amrsp::GenerateCosmo(p);
  ASSERT_TRUE(amrsp::SameStructure(plain, steps[0]));
  for (std::size_t g = 0; g < plain.Values.size(); ++g)
  {
    ASSERT_EQ(plain.Values[g], steps[0].Values[g]) << "grid " << g;
  }
  // between regrids the structure stays and the values move; at a regrid the boxes follow
  EXPECT_TRUE(amrsp::SameStructure(steps[0], steps[1]));
  EXPECT_TRUE(amrsp::SameStructure(steps[2], steps[3]));
  EXPECT_FALSE(amrsp::SameStructure(steps[1], steps[2]));
  EXPECT_FALSE(amrsp::SameStructure(steps[3], steps[4]));
  std::size_t changed = 0;
  for (std::size_t g = 0; g < steps[0].Values.size(); ++g)
  {
    changed += steps[0].Values[g] == steps[1].Values[g] ? 0 : 1;
  }
  EXPECT_GT(changed, steps[0].Values.size() / 2);
  // the field of a step is the drifted field: the boxes of step 3 are those built on time 2
  const amrsp::CosmoField at0(3), at1(3, 1.0), atZero(3, 0.0);
  int moved = 0;
  for (int i = 0; i < 1000; ++i)
  {
    const glm::dvec3 x(0.001 * i, std::fmod(0.618 * i, 1.0), std::fmod(0.414 * i, 1.0));
    moved += at1(x) != at0(x) ? 1 : 0;
    ASSERT_EQ(atZero(x), at0(x));
  }
  EXPECT_GT(moved, 10); // where halos reach; the background does not move
  // without regrids every step keeps step 0's boxes
  p.RegridEvery = 0;
  EXPECT_TRUE(amrsp::SameStructure(steps[0], amrsp::GenerateCosmoStep(p, 4)));
}
