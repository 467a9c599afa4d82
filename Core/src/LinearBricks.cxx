// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/LinearBricks.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace amrsp
{

int64_t LinearBrickLayout::TotalTexels() const
{
  int64_t rows = 0;
  for (int r : this->PageRows)
  {
    rows += r;
  }
  return rows * this->Width();
}

LinearBrickLayout LayOutLinearBricks(
  const std::vector<glm::ivec3>& extents, int widthLog2, int maxRows)
{
  if (widthLog2 < 0 || widthLog2 > 20 || maxRows < 1)
  {
    throw std::invalid_argument("LayOutLinearBricks: bad page shape");
  }
  LinearBrickLayout out;
  out.WidthLog2 = widthLog2;
  out.Extents = extents;
  out.Base.resize(extents.size());
  out.PageOfGrid.resize(extents.size());
  const int64_t capacity =
    std::min(static_cast<int64_t>(maxRows) << widthLog2, int64_t(1) << LinearBaseBits);
  int64_t used = 0;
  int page = 0;
  for (std::size_t g = 0; g < extents.size(); ++g)
  {
    const glm::ivec3 e = extents[g];
    if (e.x < 0 || e.y < 0 || e.z < 0 || e.x > 0xffff || e.y > 0xffff)
    {
      throw std::runtime_error("grid " + std::to_string(g) +
        " is too large for the linear storage's brick table (16 bits per x and y size)");
    }
    const int64_t texels = static_cast<int64_t>(e.x) * e.y * e.z;
    if (texels > capacity)
    {
      throw std::runtime_error("grid " + std::to_string(g) + " (" + std::to_string(texels) +
        " texels) exceeds a linear page of " + std::to_string(capacity) + " texels");
    }
    if (used + texels > capacity)
    {
      out.PageTexels.push_back(used);
      used = 0;
      ++page;
    }
    out.Base[g] = used;
    out.PageOfGrid[g] = page;
    used += texels;
  }
  out.PageTexels.push_back(used);
  if (static_cast<int>(out.PageTexels.size()) > MaxLinearPages)
  {
    throw std::runtime_error("the grid data needs " + std::to_string(out.PageTexels.size()) +
      " linear pages of at most " + std::to_string(capacity) + " texels; the shader addresses " +
      std::to_string(MaxLinearPages));
  }
  for (int64_t t : out.PageTexels)
  {
    // at least one row, so that an empty hierarchy still has a texture to bind
    out.PageRows.push_back(
      static_cast<int>(std::max<int64_t>(1, (t + out.Width() - 1) >> widthLog2)));
  }
  return out;
}

UIntTexture3D LinearBrickTable(const LinearBrickLayout& layout)
{
  UIntTexture3D table;
  table.Dims = TextureDimsFor(layout.Base.size());
  table.Texels.assign(
    static_cast<std::size_t>(table.Dims.x) * table.Dims.y * table.Dims.z, glm::uvec2(0u));
  for (std::size_t g = 0; g < layout.Base.size(); ++g)
  {
    const glm::ivec3 e = layout.Extents[g];
    table.Texels[g] = glm::uvec2(static_cast<uint32_t>(layout.Base[g]) |
        (static_cast<uint32_t>(layout.PageOfGrid[g]) << LinearBaseBits),
      static_cast<uint32_t>(e.x) | (static_cast<uint32_t>(e.y) << 16));
  }
  return table;
}

LinearSlabFiller::LinearSlabFiller(const Hierarchy& h, const LinearBrickLayout& layout)
  : H(h)
  , Layout(layout)
{
  const std::size_t grids = layout.Base.size();
  if (h.Values.size() != grids || h.Grids.size() != grids)
  {
    throw std::invalid_argument("LinearSlabFiller: the layout has " + std::to_string(grids) +
      " bricks and the hierarchy " + std::to_string(h.Values.size()) + " value arrays");
  }
  for (std::size_t g = 0; g < grids; ++g)
  {
    const glm::ivec3 e = layout.Extents[g];
    if (h.Values[g].size() < static_cast<std::size_t>(e.x) * e.y * e.z)
    {
      throw std::invalid_argument(
        "LinearSlabFiller: grid " + std::to_string(g) + " has fewer values than its brick");
    }
  }
  // grids are laid out in order, so each page holds a contiguous run of them
  this->FirstGridOfPage.assign(layout.PageRows.size() + 1, grids);
  for (std::size_t g = grids; g-- > 0;)
  {
    this->FirstGridOfPage[static_cast<std::size_t>(layout.PageOfGrid[g])] = g;
  }
  for (std::size_t p = layout.PageRows.size(); p-- > 0;)
  {
    this->FirstGridOfPage[p] = std::min(this->FirstGridOfPage[p], this->FirstGridOfPage[p + 1]);
  }
}

void LinearSlabFiller::Fill(int page, int row0, int row1, float* out) const
{
  const LinearBrickLayout& L = this->Layout;
  if (page < 0 || page >= static_cast<int>(L.PageRows.size()) || row0 < 0 || row1 < row0 ||
    row1 > L.PageRows[static_cast<std::size_t>(page)])
  {
    throw std::invalid_argument("LinearSlabFiller::Fill: rows outside the page");
  }
  const int64_t lo = static_cast<int64_t>(row0) << L.WidthLog2;
  const int64_t hi = static_cast<int64_t>(row1) << L.WidthLog2;
  const std::size_t first = this->FirstGridOfPage[static_cast<std::size_t>(page)];
  const std::size_t last = this->FirstGridOfPage[static_cast<std::size_t>(page) + 1];
  // the first grid whose texels reach past lo: bases increase within a page
  std::size_t g =
    static_cast<std::size_t>(std::upper_bound(L.Base.begin() + static_cast<std::ptrdiff_t>(first),
                               L.Base.begin() + static_cast<std::ptrdiff_t>(last), lo) -
      L.Base.begin());
  g = g > first ? g - 1 : first;
  int64_t written = lo;
  for (; g < last && L.Base[g] < hi; ++g)
  {
    const glm::ivec3 e = L.Extents[g];
    const int64_t begin = std::max(lo, L.Base[g]);
    const int64_t end = std::min(hi, L.Base[g] + static_cast<int64_t>(e.x) * e.y * e.z);
    if (end <= begin)
    {
      continue;
    }
    std::memcpy(out + (begin - lo), this->H.Values[g].data() + (begin - L.Base[g]),
      static_cast<std::size_t>(end - begin) * sizeof(float));
    written = end;
  }
  // after the page's last brick (bricks are back to back, so nothing before it)
  std::fill(out + (written - lo), out + (hi - lo), 0.0f);
}

} // namespace amrsp
