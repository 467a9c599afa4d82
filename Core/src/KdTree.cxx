// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/KdTree.h"

#include <algorithm>
#include <deque>
#include <string>
#include <utility>

namespace amrsp
{
namespace
{

/// A grid clipped to a node, in cells of the level being merged.
struct ClippedGrid
{
  int32_t Grid;
  Box Cells;
};

struct SplitChoice
{
  int Axis = -1;
  int64_t Position = 0; ///< absolute, in cells of the level being merged
  int64_t Crossings = 0;
  double GridBalance = 0.0;
  double NodeBalance = 0.0;
};

double Balance(double a, double b)
{
  const double hi = std::max(a, b);
  return hi > 0.0 ? std::min(a, b) / hi : 0.0;
}

bool Better(const SplitChoice& a, const SplitChoice& b)
{
  if (b.Axis < 0)
  {
    return true;
  }
  if (a.Crossings != b.Crossings)
  {
    return a.Crossings < b.Crossings;
  }
  if (a.GridBalance != b.GridBalance)
  {
    return a.GridBalance > b.GridBalance;
  }
  if (a.NodeBalance != b.NodeBalance)
  {
    return a.NodeBalance > b.NodeBalance;
  }
  return false; // candidates arrive by increasing axis, then position: keep the first
}

int64_t CrossSection(const Box& b, int axis)
{
  const glm::i64vec3 e = b.Extent();
  return e[(axis + 1) % 3] * e[(axis + 2) % 3];
}

/// The paper's split rule. Candidate planes are the faces of the clipped grids strictly inside
/// the node: a plane anywhere else separates nothing and only adds nodes.
SplitChoice ChooseSplit(const Box& node, const std::vector<ClippedGrid>& grids)
{
  SplitChoice best;
  double totalGridCells = 0.0;
  for (const ClippedGrid& g : grids)
  {
    totalGridCells += static_cast<double>(g.Cells.Cells());
  }
  std::vector<int64_t> candidates, lows, highs;
  std::vector<std::pair<int64_t, double>> events; // position, change of slope (cells per slab)
  for (int axis = 0; axis < 3; ++axis)
  {
    candidates.clear();
    lows.clear();
    highs.clear();
    events.clear();
    for (const ClippedGrid& g : grids)
    {
      const int64_t lo = g.Cells.Lo[axis], hi = g.Cells.Hi[axis];
      if (lo > node.Lo[axis])
      {
        candidates.push_back(lo);
      }
      if (hi < node.Hi[axis])
      {
        candidates.push_back(hi);
      }
      lows.push_back(lo);
      highs.push_back(hi);
      const double area = static_cast<double>(CrossSection(g.Cells, axis));
      events.emplace_back(lo, area);
      events.emplace_back(hi, -area);
    }
    if (candidates.empty())
    {
      continue;
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    std::sort(lows.begin(), lows.end());
    std::sort(highs.begin(), highs.end());
    std::sort(events.begin(), events.end());

    const double nodeArea = static_cast<double>(CrossSection(node, axis));
    size_t next = 0;
    int64_t cursor = node.Lo[axis];
    double slope = 0.0, left = 0.0;
    for (int64_t p : candidates)
    {
      while (next < events.size() && events[next].first <= p)
      {
        left += slope * static_cast<double>(events[next].first - cursor);
        cursor = events[next].first;
        slope += events[next].second;
        ++next;
      }
      left += slope * static_cast<double>(p - cursor);
      cursor = p;

      SplitChoice c;
      c.Axis = axis;
      c.Position = p;
      // grids with lo < p < hi: (lo < p) minus (hi <= p), as hi <= p implies lo < p
      c.Crossings = (std::lower_bound(lows.begin(), lows.end(), p) - lows.begin()) -
        (std::upper_bound(highs.begin(), highs.end(), p) - highs.begin());
      c.GridBalance = Balance(left, totalGridCells - left);
      c.NodeBalance = Balance(static_cast<double>(p - node.Lo[axis]) * nodeArea,
        static_cast<double>(node.Hi[axis] - p) * nodeArea);
      if (Better(c, best))
      {
        best = c;
      }
    }
  }
  return best;
}

Box Coarsened(const Box& fine, const glm::i64vec3& ratio)
{
  return Box{ fine.Lo / ratio, fine.Hi / ratio };
}

class Builder
{
public:
  explicit Builder(const Hierarchy& h)
    : H(h)
  {
  }

  KdTree Build()
  {
    Validate();
    Finest = H.NumberOfLevels() - 1;
    for (int l = 0; l <= Finest; ++l)
    {
      ToFinest.push_back(ToFinestRatio(l));
    }

    KdNode root;
    root.Region = H.RootCells().Refined(ToFinest[0]);
    Nodes.push_back(root);

    for (int level = 0; level <= Finest; ++level)
    {
      MergeLevel(level);
    }
    Classify();
    return BreadthFirst();
  }

private:
  void Validate() const
  {
    if (H.NumberOfLevels() < 1)
    {
      throw HierarchyError("the hierarchy has no levels");
    }
    for (int l = 0; l < H.NumberOfLevels(); ++l)
    {
      const glm::ivec3 r = H.RefinementRatio[l];
      if (r.x < 1 || r.y < 1 || r.z < 1)
      {
        throw HierarchyError("refinement ratio of level " + std::to_string(l) +
          " is not a positive integer on every axis");
      }
    }
    bool hasRoot = false;
    int previous = 0;
    for (const Grid& g : H.Grids)
    {
      if (g.Level < 0 || g.Level >= H.NumberOfLevels())
      {
        throw HierarchyError("grid of level " + std::to_string(g.Level) +
          " outside the hierarchy's " + std::to_string(H.NumberOfLevels()) + " levels");
      }
      if (g.Level < previous)
      {
        throw HierarchyError("grids are not sorted by level");
      }
      if (g.Cells.Empty())
      {
        throw HierarchyError("a grid of level " + std::to_string(g.Level) + " has no cells");
      }
      previous = g.Level;
      hasRoot = hasRoot || g.Level == 0;
    }
    if (!hasRoot)
    {
      throw HierarchyError("the hierarchy has no level-0 grid");
    }
  }

  glm::i64vec3 ToFinestRatio(int level) const
  {
    glm::i64vec3 r(1);
    for (int l = level + 1; l <= Finest; ++l)
    {
      r *= glm::i64vec3(H.RefinementRatio[l]);
    }
    return r;
  }

  /// Hands every grid of `level` to the leaves it overlaps, then refines those leaves.
  void MergeLevel(int level)
  {
    std::vector<std::vector<ClippedGrid>> pending(Nodes.size());
    std::vector<int32_t> touched;
    const Box rootCells = Coarsened(Nodes[0].Region, ToFinest[level]);
    std::vector<int32_t> stack;
    for (size_t gi = 0; gi < H.Grids.size(); ++gi)
    {
      const Grid& g = H.Grids[gi];
      if (g.Level != level || !g.Cells.Overlaps(rootCells))
      {
        continue;
      }
      stack.assign(1, 0);
      while (!stack.empty())
      {
        const int32_t n = stack.back();
        stack.pop_back();
        const Box region = Coarsened(Nodes[n].Region, ToFinest[level]);
        if (!region.Overlaps(g.Cells))
        {
          continue;
        }
        if (Nodes[n].IsLeaf())
        {
          if (pending[n].empty())
          {
            touched.push_back(n);
          }
          pending[n].push_back(
            ClippedGrid{ static_cast<int32_t>(gi), g.Cells.Intersection(region) });
        }
        else
        {
          stack.push_back(Nodes[n].FirstChild);
          stack.push_back(Nodes[n].FirstChild + 1);
        }
      }
    }
    for (int32_t n : touched)
    {
      Refine(n, std::move(pending[n]), level);
    }
  }

  /// A node still to refine with the grids of the level being merged that overlap it, and whether
  /// it needs a type (a) node of its own should one grid cover it whole (`OwnLodNode`: false when
  /// its sibling is covered whole too, so that their parent keeps the coarser data).
  struct RefineItem
  {
    int32_t Node;
    std::vector<ClippedGrid> Grids;
    bool OwnLodNode;
  };

  void Refine(int32_t start, std::vector<ClippedGrid>&& startGrids, int level)
  {
    std::vector<RefineItem> work;
    work.push_back(RefineItem{ start, std::move(startGrids), true });
    while (!work.empty())
    {
      const int32_t n = work.back().Node;
      std::vector<ClippedGrid> grids = std::move(work.back().Grids);
      const bool ownLodNode = work.back().OwnLodNode;
      work.pop_back();
      if (grids.empty())
      {
        continue; // keeps the data it inherited (a coarser grid, or none)
      }
      const Box region = Coarsened(Nodes[n].Region, ToFinest[level]);
      const auto cover = std::find_if(
        grids.begin(), grids.end(), [&](const ClippedGrid& g) { return g.Cells.Contains(region); });
      if (cover != grids.end())
      {
        CoverNode(n, region, cover->Grid, level, ownLodNode);
        continue;
      }
      const SplitChoice s = ChooseSplit(region, grids);
      if (s.Axis < 0)
      {
        throw HierarchyError("internal error: no split plane for a partially covered node");
      }
      const int32_t first = Split(n, region, s.Axis, s.Position, level);

      std::vector<ClippedGrid> lowerGrids, upperGrids;
      for (const ClippedGrid& g : grids)
      {
        if (g.Cells.Lo[s.Axis] < s.Position)
        {
          ClippedGrid c = g;
          c.Cells.Hi[s.Axis] = std::min(c.Cells.Hi[s.Axis], s.Position);
          lowerGrids.push_back(c);
        }
        if (g.Cells.Hi[s.Axis] > s.Position)
        {
          ClippedGrid c = g;
          c.Cells.Lo[s.Axis] = std::max(c.Cells.Lo[s.Axis], s.Position);
          upperGrids.push_back(c);
        }
      }
      const auto covered = [&](int32_t child, const std::vector<ClippedGrid>& childGrids)
      {
        const Box childRegion = Coarsened(Nodes[child].Region, ToFinest[level]);
        return std::any_of(childGrids.begin(), childGrids.end(),
          [&](const ClippedGrid& g) { return g.Cells.Contains(childRegion); });
      };
      const bool both = covered(first, lowerGrids) && covered(first + 1, upperGrids);
      work.push_back(RefineItem{ first, std::move(lowerGrids), !both });
      work.push_back(RefineItem{ first + 1, std::move(upperGrids), !both });
    }
  }

  /// Splits leaf `n` (its region in cells of `level`: `region`) on `axis` at `position` (cells of
  /// `level`, absolute); both children keep the node's grid (which contains both halves).
  /// Returns the lower child's index.
  int32_t Split(int32_t n, const Box& region, int axis, int64_t position, int level)
  {
    const int32_t first = static_cast<int32_t>(Nodes.size());
    KdNode& parent = Nodes[n];
    parent.Axis = axis;
    parent.Level = level;
    parent.Split = position - region.Lo[axis];
    parent.FirstChild = first;
    KdNode lower, upper;
    lower.Grid = upper.Grid = parent.Grid;
    lower.Level = upper.Level = parent.Grid >= 0 ? H.Grids[parent.Grid].Level : level;
    lower.Region = upper.Region = parent.Region;
    const int64_t planeFine = position * ToFinest[level][axis];
    lower.Region.Hi[axis] = planeFine;
    upper.Region.Lo[axis] = planeFine;
    Nodes.push_back(lower);
    Nodes.push_back(upper);
    return first;
  }

  /// Leaf `n` (region `region` in cells of `level`) lies wholly in `grid` of `level`. A leaf that
  /// showed a coarser grid keeps it for the level of detail where no ancestor will
  /// (`ownLodNode`: its sibling is not covered whole as well): it becomes a type (a) node over two
  /// halves showing `grid` (split in the middle of its longest axis in `level` cells; a node one
  /// cell wide on every axis cannot be, and shows `grid` alone). Without the split a single grid
  /// refining a region would leave no node where the level of detail could stop.
  void CoverNode(int32_t n, const Box& region, int32_t grid, int level, bool ownLodNode)
  {
    const glm::i64vec3 e = region.Extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    if (ownLodNode && Nodes[n].Grid >= 0 && e[axis] >= 2)
    {
      const int32_t first = Split(n, region, axis, region.Lo[axis] + e[axis] / 2, level);
      for (int32_t c = first; c < first + 2; ++c)
      {
        Nodes[c].Grid = grid;
        Nodes[c].Level = level;
      }
      return;
    }
    Nodes[n].Grid = grid;
    Nodes[n].Level = level;
  }

  /// Assigns node types bottom-up. An inner node keeps its covering grid (type (a)) only when
  /// every leaf below shows a finer level than that grid's; otherwise it is type (c).
  void Classify()
  {
    constexpr int uncovered = -1;
    std::vector<int> minLeafLevel(Nodes.size(), 0);
    for (size_t i = Nodes.size(); i-- > 0;)
    {
      KdNode& n = Nodes[i];
      if (n.IsLeaf())
      {
        n.Type = n.HasData() ? NodeType::Leaf : NodeType::Empty;
        minLeafLevel[i] = n.HasData() ? H.Grids[n.Grid].Level : uncovered;
        continue;
      }
      // children are always created after their parent, so they are already classified
      minLeafLevel[i] = std::min(minLeafLevel[n.FirstChild], minLeafLevel[n.FirstChild + 1]);
      if (n.HasData() && minLeafLevel[i] > H.Grids[n.Grid].Level)
      {
        n.Type = NodeType::Refined;
      }
      else
      {
        n.Type = NodeType::Mixed;
        n.Grid = -1;
      }
    }
  }

  KdTree BreadthFirst() const
  {
    KdTree tree;
    tree.FinestLevel = Finest;
    tree.Nodes.reserve(Nodes.size());
    std::deque<int32_t> queue{ 0 };
    tree.Nodes.push_back(Nodes[0]);
    std::vector<int32_t> newIndex{ 0 };
    // newIndex[k] is the new index of queue entry k, processed in order
    size_t k = 0;
    while (!queue.empty())
    {
      const int32_t old = queue.front();
      queue.pop_front();
      const int32_t self = newIndex[k++];
      if (Nodes[old].IsLeaf())
      {
        continue;
      }
      const int32_t first = static_cast<int32_t>(tree.Nodes.size());
      tree.Nodes[self].FirstChild = first;
      for (int c = 0; c < 2; ++c)
      {
        tree.Nodes.push_back(Nodes[Nodes[old].FirstChild + c]);
        queue.push_back(Nodes[old].FirstChild + c);
        newIndex.push_back(first + c);
      }
    }
    return tree;
  }

  const Hierarchy& H;
  int Finest = 0;
  std::vector<glm::i64vec3> ToFinest;
  std::vector<KdNode> Nodes;
};

} // namespace

KdTreeStatistics KdTree::Statistics() const
{
  KdTreeStatistics s;
  s.Nodes = static_cast<int64_t>(Nodes.size());
  std::vector<int> depth(Nodes.size(), 0);
  for (size_t i = 0; i < Nodes.size(); ++i)
  {
    const KdNode& n = Nodes[i];
    switch (n.Type)
    {
      case NodeType::Refined:
        ++s.Refined;
        break;
      case NodeType::Leaf:
        ++s.Leaves;
        break;
      case NodeType::Mixed:
        ++s.Mixed;
        break;
      case NodeType::Empty:
        ++s.Empty;
        break;
    }
    if (!n.IsLeaf())
    {
      depth[n.FirstChild] = depth[n.FirstChild + 1] = depth[i] + 1;
    }
    s.Depth = std::max(s.Depth, depth[i]);
  }
  s.DataNodes = s.Refined + s.Leaves;
  return s;
}

KdTree BuildKdTree(const Hierarchy& h)
{
  return Builder(h).Build();
}

glm::dvec3 RegionLoIndex(const Hierarchy& h, const KdTree& tree, const Box& region)
{
  return glm::dvec3(region.Lo) / glm::dvec3(h.CumulativeRatio(tree.FinestLevel));
}

glm::dvec3 RegionHiIndex(const Hierarchy& h, const KdTree& tree, const Box& region)
{
  return glm::dvec3(region.Hi) / glm::dvec3(h.CumulativeRatio(tree.FinestLevel));
}

} // namespace amrsp
