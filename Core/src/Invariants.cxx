// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Invariants.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace amrsp
{

void InvariantReport::Fail(const std::string& what)
{
  Ok = false;
  ++FailureCount;
  if (Failures.size() < 20)
  {
    Failures.push_back(what);
  }
}

namespace
{

/// Per-level uniform buckets over the grids' boxes, in finest-level cells.
class GridIndex
{
public:
  GridIndex(const Hierarchy& h, int finest)
    : H(h)
  {
    const int levels = h.NumberOfLevels();
    Levels.resize(levels);
    for (int l = 0; l < levels; ++l)
    {
      glm::i64vec3 r(1);
      for (int k = l + 1; k <= finest; ++k)
      {
        r *= glm::i64vec3(h.RefinementRatio[k]);
      }
      ToFinest.push_back(r);
    }
    for (std::size_t g = 0; g < h.Grids.size(); ++g)
    {
      Levels[h.Grids[g].Level].Members.push_back(static_cast<int32_t>(g));
    }
    Seen.assign(h.Grids.size(), 0);
    for (int l = 0; l < levels; ++l)
    {
      Level& L = Levels[l];
      if (L.Members.empty())
      {
        continue;
      }
      L.Lo = glm::i64vec3(std::numeric_limits<int64_t>::max());
      L.Hi = glm::i64vec3(std::numeric_limits<int64_t>::min());
      for (int32_t g : L.Members)
      {
        const Box b = Fine(g);
        L.Lo = glm::min(L.Lo, b.Lo);
        L.Hi = glm::max(L.Hi, b.Hi);
      }
      const int64_t n = std::max<int64_t>(1,
        std::min<int64_t>(
          32, static_cast<int64_t>(std::cbrt(static_cast<double>(L.Members.size())) * 2)));
      L.N = n;
      L.Size = glm::max(glm::i64vec3(1), (L.Hi - L.Lo + glm::i64vec3(n - 1)) / glm::i64vec3(n));
      L.Buckets.resize(static_cast<std::size_t>(n * n * n));
      for (int32_t g : L.Members)
      {
        const Box b = Fine(g);
        ForBuckets(L, b, [&](std::vector<int32_t>& bucket) { bucket.push_back(g); });
      }
    }
  }

  Box Fine(int32_t g) const
  {
    const Grid& grid = H.Grids[g];
    return grid.Cells.Refined(ToFinest[grid.Level]);
  }

  /// Calls f(g) once for each grid of `level` overlapping `region` (finest cells); stops when f
  /// returns false. O(bucket entries in `region`).
  template <typename F>
  void Overlapping(int level, const Box& region, F f) const
  {
    const Level& L = Levels[level];
    if (L.Members.empty() || !region.Overlaps(Box{ L.Lo, L.Hi }))
    {
      return;
    }
    // a grid in several buckets is visited once: Seen[g] == Query marks it for this query
    ++this->Query;
    bool go = true;
    ForBuckets(L, region,
      [&](const std::vector<int32_t>& bucket)
      {
        for (int32_t g : bucket)
        {
          if (!go || this->Seen[static_cast<std::size_t>(g)] == this->Query)
          {
            continue;
          }
          this->Seen[static_cast<std::size_t>(g)] = this->Query;
          if (Fine(g).Overlaps(region))
          {
            go = f(g);
          }
        }
      });
  }

private:
  // per grid, the last query that visited it (Overlapping is therefore not thread-safe)
  mutable std::vector<uint64_t> Seen;
  mutable uint64_t Query = 0;

  struct Level
  {
    std::vector<int32_t> Members;
    glm::i64vec3 Lo{ 0 }, Hi{ 0 }, Size{ 1 };
    int64_t N = 0;
    std::vector<std::vector<int32_t>> Buckets;
  };

  template <typename L, typename F>
  static void ForBuckets(L& level, const Box& b, F f)
  {
    const glm::i64vec3 last(level.N - 1);
    const glm::i64vec3 a = glm::clamp((b.Lo - level.Lo) / level.Size, glm::i64vec3(0), last);
    const glm::i64vec3 z =
      glm::clamp((b.Hi - glm::i64vec3(1) - level.Lo) / level.Size, glm::i64vec3(0), last);
    for (int64_t k = a.z; k <= z.z; ++k)
    {
      for (int64_t j = a.y; j <= z.y; ++j)
      {
        for (int64_t i = a.x; i <= z.x; ++i)
        {
          f(level.Buckets[static_cast<std::size_t>((k * level.N + j) * level.N + i)]);
        }
      }
    }
  }

  const Hierarchy& H;
  std::vector<Level> Levels;
  std::vector<glm::i64vec3> ToFinest;
};

std::string Name(std::size_t i)
{
  return "node " + std::to_string(i);
}

} // namespace

InvariantReport CheckKdTree(const Hierarchy& h, const KdTree& tree, const EncodedKdTree* encoded)
{
  InvariantReport r;
  if (tree.Nodes.empty())
  {
    r.Fail("the tree has no nodes");
    return r;
  }
  const int finest = tree.FinestLevel;
  const GridIndex index(h, finest);

  const Box root = h.ToLevel(h.RootCells(), 0, finest);
  if (!(tree.Root().Region == root))
  {
    r.Fail("the root is not the bounding box of the level-0 grids");
  }

  const glm::i64vec3 finestRatio = h.CumulativeRatio(finest);
  std::vector<int> minLeafLevel(tree.Nodes.size(), 0);
  for (std::size_t i = tree.Nodes.size(); i-- > 0;)
  {
    const KdNode& n = tree.Nodes[i];
    if (n.IsLeaf())
    {
      minLeafLevel[i] = n.HasData() ? h.Grids[n.Grid].Level : -1;
      if (n.Type != (n.HasData() ? NodeType::Leaf : NodeType::Empty))
      {
        r.Fail(Name(i) + ": leaf with the wrong type");
      }
      if (!n.HasData())
      {
        for (int l = 0; l <= finest; ++l)
        {
          index.Overlapping(l, n.Region,
            [&](int32_t g)
            {
              r.Fail(Name(i) + ": empty leaf overlaps grid " + std::to_string(g));
              return false;
            });
        }
        continue;
      }
      const int d = h.Grids[n.Grid].Level;
      if (n.Level != d)
      {
        r.Fail(Name(i) + ": leaf level differs from its grid's level");
      }
      if (!index.Fine(n.Grid).Contains(n.Region))
      {
        r.Fail(Name(i) + ": leaf is not inside its grid " + std::to_string(n.Grid));
      }
      for (int l = d + 1; l <= finest; ++l)
      {
        index.Overlapping(l, n.Region,
          [&](int32_t g)
          {
            r.Fail(Name(i) + " (level " + std::to_string(d) + ") is overlapped by finer grid " +
              std::to_string(g) + " of level " + std::to_string(l));
            return false;
          });
      }
      continue;
    }

    // inner node: exact partition on a face of the split level, strictly inside
    if (n.FirstChild <= static_cast<int32_t>(i) ||
      static_cast<std::size_t>(n.FirstChild) + 1 >= tree.Nodes.size())
    {
      r.Fail(Name(i) + ": child index out of order or range");
      continue;
    }
    const KdNode& lower = tree.Nodes[n.FirstChild];
    const KdNode& upper = tree.Nodes[n.FirstChild + 1];
    const int a = n.Axis;
    const int64_t unit = finestRatio[a] / h.CumulativeRatio(n.Level)[a];
    const int64_t plane = n.Region.Lo[a] + n.Split * unit;
    Box expectLower = n.Region, expectUpper = n.Region;
    expectLower.Hi[a] = plane;
    expectUpper.Lo[a] = plane;
    if (!(plane > n.Region.Lo[a] && plane < n.Region.Hi[a]))
    {
      r.Fail(Name(i) + ": split plane not strictly inside the node");
    }
    if (!(lower.Region == expectLower) || !(upper.Region == expectUpper))
    {
      r.Fail(Name(i) + ": children do not split the node exactly at its plane");
    }
    minLeafLevel[i] = std::min(minLeafLevel[n.FirstChild], minLeafLevel[n.FirstChild + 1]);
    if (n.Type == NodeType::Refined)
    {
      if (!n.HasData() || !index.Fine(n.Grid).Contains(n.Region))
      {
        r.Fail(Name(i) + ": type (a) node is not inside its grid");
      }
      else if (minLeafLevel[i] <= h.Grids[n.Grid].Level)
      {
        r.Fail(Name(i) + ": type (a) node has leaves no finer than its own data");
      }
    }
    else if (n.Type != NodeType::Mixed || n.HasData())
    {
      r.Fail(Name(i) + ": inner node with the wrong type");
    }
  }

  if (encoded)
  {
    const KdTree decoded = DecodeKdTree(h, *encoded);
    if (decoded.Nodes.size() != tree.Nodes.size())
    {
      r.Fail("decoded tree has a different number of nodes");
    }
    else
    {
      for (std::size_t i = 0; i < tree.Nodes.size(); ++i)
      {
        const KdNode& a = tree.Nodes[i];
        const KdNode& b = decoded.Nodes[i];
        if (!(a.Region == b.Region) || a.Level != b.Level || a.Axis != b.Axis ||
          a.Split != b.Split || a.FirstChild != b.FirstChild || a.Grid != b.Grid ||
          a.Type != b.Type)
        {
          r.Fail(Name(i) + ": encode/decode round trip differs");
        }
      }
    }
  }
  return r;
}

} // namespace amrsp
