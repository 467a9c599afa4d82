// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Bricks spread over several atlas textures ("pages") when one texture would exceed what a
/// driver allocates (Mesa's llvmpipe: 2 GiB per texture, its 32-bit signed texel offsets). With
/// one page everything is as with a single atlas; the data nodes carry the page of their brick
/// (Shaders/KdTreeLayout.glsl) and the shaders read the brick from that page's texture.

#include "amrsp/BrickPacking.h"
#include "amrsp/Hierarchy.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace amrsp
{

struct AtlasPages
{
  /// One layout per page; Pages[p].Origins lists the bricks of page p in grid order.
  std::vector<AtlasLayout> Pages;
  /// Per grid: its page, and its brick's origin inside that page.
  std::vector<int> PageOfGrid;
  std::vector<glm::ivec3> Origins;
  /// Per page: its grids, in grid order.
  std::vector<std::vector<std::size_t>> GridsOfPage;

  int64_t TotalTexels() const;
};

/// Packs the bricks of `extents` (one per grid) into as few pages as hold them, each within
/// `maxDims` per axis and `maxPageTexels` texels (0: no budget): first into one atlas exactly as
/// PackBricks does; when that atlas exceeds the budget, into k = 2 .. layout::MaxAtlasPages
/// pages of consecutive grids with about equal used texels each, every page packed by
/// PackBricks. Throws PackingError when even the most pages allowed do not fit.
AtlasPages PackBricksInPages(const std::vector<glm::ivec3>& extents, Packer packer,
  const glm::ivec3& maxDims, int64_t maxPageTexels);

/// The grids of page `page` of `h` as a hierarchy sharing `h`'s values (no copy), in grid order:
/// what FillAtlasSlab fills that page's texture from with pages.Pages[page].
Hierarchy PageHierarchy(const Hierarchy& h, const AtlasPages& pages, int page);

} // namespace amrsp
