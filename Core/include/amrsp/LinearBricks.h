// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The linear storage of the grid data: every brick's texels one after another, in the order its
/// grid holds them (x fastest), in 2D R32F textures ("pages") whose rows are Width = 2^WidthLog2
/// texels long. Texel i of a page is (i & (Width - 1), i >> WidthLog2). A brick is contiguous in
/// memory, so a sample's neighbours along x are adjacent and along y and z one brick row or layer
/// away, where the packed atlas puts them an atlas row or layer away: a CPU driver that stores
/// textures linearly (Mesa's llvmpipe) reads fewer cache lines. There is no packing and no gap.
///
/// The shader finds a brick through its table entry (LinearBrickTable): the brick's first texel
/// in its page, the page, and its x and y sizes; a data node's offset inside its brick (the
/// bindless data-node encoding) gives the texel base + x + nx (y + ny z).

#include "amrsp/KdTreeEncoding.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace amrsp
{

/// Bits of a brick-table entry's first word that hold the brick's first texel in its page; the
/// page is in the two bits above them.
constexpr int LinearBaseBits = 30;
/// Most pages the shader can address (the page's two bits).
constexpr int MaxLinearPages = 4;

struct LinearBrickLayout
{
  int WidthLog2 = 0;
  std::vector<glm::ivec3> Extents; ///< per grid: its brick's texels per axis
  std::vector<int64_t> Base;       ///< per grid: index of its first texel in its page
  std::vector<int> PageOfGrid;     ///< per grid: its page
  std::vector<int> PageRows;       ///< per page: rows of Width texels
  std::vector<int64_t> PageTexels; ///< per page: texels its bricks use

  int64_t Width() const { return int64_t(1) << this->WidthLog2; }
  int64_t TotalTexels() const; ///< texels of all pages (rows times Width)
};

/// Lays the bricks of `extents` out in grid order: a brick goes to the current page unless it
/// would pass `maxRows` rows of 2^widthLog2 texels, then to a new page; at most MaxLinearPages
/// pages, and a page's texels below 2^LinearBaseBits.
/// @throws std::runtime_error naming the limit when the bricks do not fit.
LinearBrickLayout LayOutLinearBricks(
  const std::vector<glm::ivec3>& extents, int widthLog2, int maxRows);

/// The brick table (RG32UI, one texel per brick, laid out like the kD-tree textures): red = the
/// brick's first texel | page << LinearBaseBits, green = nx | ny << 16.
UIntTexture3D LinearBrickTable(const LinearBrickLayout& layout);

/// A rectangle of a page that one brick's values fill, in the order the brick holds them: rows
/// y <= row < y + Rows, texels x <= t < x + Width of each (so a rectangle of several rows spans
/// whole rows). Its first texel is value FirstValue of the brick.
struct LinearRun
{
  int X = 0;
  int Y = 0;
  int Width = 0;
  int Rows = 0;
  int64_t FirstValue = 0;
};

/// The at most three rectangles that hold grid `g`'s brick in its page, in order: the rest of
/// the row it starts in, the whole rows after it, and the start of the row it ends in (each only
/// when not empty). Every value of the brick is in exactly one of them, so a brick can be
/// uploaded straight from its values, without a staging copy.
/// @throws std::out_of_range for a grid outside the layout.
std::vector<LinearRun> LinearBrickRuns(const LinearBrickLayout& layout, std::size_t g);

} // namespace amrsp
