// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The core's description of a structured AMR hierarchy: integer boxes per level, refinement
/// ratios, origin and level-0 spacing. Plain C++17 + GLM; no VTK, no OpenGL.
///
/// Index space conventions (used everywhere in the core and in the shaders):
/// - Each level l has its own integer cell index space. Cell (i,j,k) of level l covers, in
///   *level-0 index units*, the box [i,i+1) x [j,j+1) x [k,k+1) scaled by 1/CumulativeRatio(l).
/// - World position of level-0 index coordinate u is Origin + u * Spacing0 (component-wise).
/// - Boxes are half-open: [Lo, Hi) in cells of their level. Hi - Lo >= 1 on every axis.
/// - Level l's index space refines level l-1's by RefinementRatio[l] (per axis, >= 1), so a
///   level-(l-1) cell index i maps to level-l cells [i*r, (i+1)*r).

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

namespace amrsp
{

/// Half-open integer box [Lo, Hi) in the cells of one level.
struct Box
{
  glm::i64vec3 Lo{ 0 };
  glm::i64vec3 Hi{ 0 };

  glm::i64vec3 Extent() const { return Hi - Lo; }
  bool Empty() const { return Hi.x <= Lo.x || Hi.y <= Lo.y || Hi.z <= Lo.z; }
  int64_t Cells() const
  {
    if (Empty())
    {
      return 0;
    }
    const glm::i64vec3 e = Extent();
    return e.x * e.y * e.z;
  }
  bool Contains(const Box& o) const
  {
    return o.Lo.x >= Lo.x && o.Lo.y >= Lo.y && o.Lo.z >= Lo.z && o.Hi.x <= Hi.x && o.Hi.y <= Hi.y &&
      o.Hi.z <= Hi.z;
  }
  bool Overlaps(const Box& o) const
  {
    return o.Lo.x < Hi.x && o.Lo.y < Hi.y && o.Lo.z < Hi.z && Lo.x < o.Hi.x && Lo.y < o.Hi.y &&
      Lo.z < o.Hi.z;
  }
  Box Intersection(const Box& o) const { return Box{ glm::max(Lo, o.Lo), glm::min(Hi, o.Hi) }; }
  bool operator==(const Box& o) const { return Lo == o.Lo && Hi == o.Hi; }
  /// The same region in the cells of a level refined by `ratio` relative to this box's level.
  Box Refined(const glm::i64vec3& ratio) const { return Box{ Lo * ratio, Hi * ratio }; }
};

/// One AMR subgrid (patch). Its cells are the data of one brick.
struct Grid
{
  int Level = 0;
  Box Cells; ///< in cells of `Level`
  int64_t SourceId =
    -1; ///< caller's identifier (e.g. the flat VTK block index); not used by the core
};

/// Per-grid scalar values, x fastest, then y, then z: one float per cell of Grid::Cells for
/// cell-centred data, or one per vertex ((extent + 1) per axis) when Hierarchy::VertexCentred.
/// Empty means "no data loaded" (structure-only hierarchies, e.g. for tree statistics).
///
/// The values are either owned or borrowed from memory the caller keeps alive through a
/// type-erased owner (e.g. a VTK array), so that converting a hierarchy does not copy its cells.
/// Copies share the values. Reading never copies; every non-const accessor first makes the
/// values this object's own and unshared (copy on write), so writing never reaches borrowed
/// memory or another copy. Read through a const reference in loops over many values.
class GridValues
{
public:
  GridValues() = default;
  GridValues(std::vector<float> values);
  explicit GridValues(std::size_t count, float value = 0.0f);
  GridValues(std::initializer_list<float> values);

  /// `count` floats at `values`, valid as long as `owner` is held (never written through).
  static GridValues Borrow(
    const float* values, std::size_t count, std::shared_ptr<const void> owner);

  std::size_t size() const { return this->Owned ? this->Owned->size() : this->Count; }
  bool empty() const { return this->size() == 0; }
  const float* data() const { return this->Owned ? this->Owned->data() : this->Borrowed; }
  const float* begin() const { return this->data(); }
  const float* end() const { return this->data() + this->size(); }
  const float& operator[](std::size_t i) const { return this->data()[i]; }
  /// True when the values live in memory this object does not own.
  bool IsBorrowed() const { return !this->Owned && this->Count > 0; }

  /// Writable access (copy on write, see above).
  float* data() { return this->Writable().data(); }
  float* begin() { return this->data(); }
  float* end() { return this->data() + this->size(); }
  float& operator[](std::size_t i) { return this->Writable()[i]; }

  bool operator==(const GridValues& o) const;
  bool operator!=(const GridValues& o) const { return !(*this == o); }

private:
  std::vector<float>& Writable();

  std::shared_ptr<std::vector<float>> Owned;
  const float* Borrowed = nullptr;
  std::size_t Count = 0;
  std::shared_ptr<const void> Owner;
};

/// A structured AMR hierarchy. Grids are stored level by level (non-decreasing Level).
struct Hierarchy
{
  glm::dvec3 Origin{ 0.0 };   ///< world position of level-0 index coordinate (0,0,0)
  glm::dvec3 Spacing0{ 1.0 }; ///< world size of one level-0 cell
  /// RefinementRatio[l] refines level l-1 into level l; RefinementRatio[0] is (1,1,1).
  std::vector<glm::ivec3> RefinementRatio{ glm::ivec3(1) };
  std::vector<Grid> Grids;
  /// Values[g] belongs to Grids[g]; either empty (no data) or sized Grids.size().
  std::vector<GridValues> Values;
  /// True when the values are vertex-centred (texels on vertices); false for cell-centred data.
  bool VertexCentred = false;
  std::string ArrayName;

  int NumberOfLevels() const { return static_cast<int>(RefinementRatio.size()); }

  /// Product of the refinement ratios of levels 1..level (per axis); (1,1,1) for level 0.
  glm::i64vec3 CumulativeRatio(int level) const
  {
    glm::i64vec3 r(1);
    for (int l = 1; l <= level; ++l)
    {
      r *= glm::i64vec3(RefinementRatio[l]);
    }
    return r;
  }

  /// Size of one cell of `level`, in level-0 index units.
  glm::dvec3 CellSize(int level) const { return 1.0 / glm::dvec3(CumulativeRatio(level)); }

  /// A box of `level` expressed in the cells of a finer-or-equal level `target`.
  Box ToLevel(const Box& box, int level, int target) const
  {
    glm::i64vec3 r(1);
    for (int l = level + 1; l <= target; ++l)
    {
      r *= glm::i64vec3(RefinementRatio[l]);
    }
    return box.Refined(r);
  }

  /// World-space bounds of a box of `level`: lower and upper corner.
  glm::dvec3 WorldLo(const Box& box, int level) const
  {
    return Origin + glm::dvec3(box.Lo) * CellSize(level) * Spacing0;
  }
  glm::dvec3 WorldHi(const Box& box, int level) const
  {
    return Origin + glm::dvec3(box.Hi) * CellSize(level) * Spacing0;
  }

  /// Bounding box of the level-0 grids in level-0 cells (the kD-tree's root); empty if none.
  Box RootCells() const
  {
    Box root;
    bool first = true;
    for (const Grid& g : Grids)
    {
      if (g.Level == 0)
      {
        root =
          first ? g.Cells : Box{ glm::min(root.Lo, g.Cells.Lo), glm::max(root.Hi, g.Cells.Hi) };
        first = false;
      }
    }
    return root;
  }

  bool HasValues() const { return !Values.empty() && Values.size() == Grids.size(); }

  int64_t TotalCells() const
  {
    int64_t n = 0;
    for (const Grid& g : Grids)
    {
      n += g.Cells.Cells();
    }
    return n;
  }
};

/// Whether `a` and `b` have the same structure: origin, level-0 spacing, refinement ratios,
/// grids (level and cells, in the same order), centring and array name. Two time steps of a
/// simulation between regrids do; then everything built from the structure alone (the kD-tree,
/// its encoding, the atlas layout) is the same for both.
bool SameStructure(const Hierarchy& a, const Hierarchy& b);

} // namespace amrsp
