// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/LinearBricks.h"

#include <algorithm>
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

std::vector<LinearRun> LinearBrickRuns(const LinearBrickLayout& layout, std::size_t g)
{
  if (g >= layout.Base.size())
  {
    throw std::out_of_range("LinearBrickRuns: grid " + std::to_string(g) + " is not in the layout");
  }
  const glm::ivec3 e = layout.Extents[g];
  const int64_t count = static_cast<int64_t>(e.x) * e.y * e.z;
  const int64_t width = layout.Width();
  std::vector<LinearRun> runs;
  int64_t done = 0;
  while (done < count)
  {
    const int64_t texel = layout.Base[g] + done;
    LinearRun run;
    run.X = static_cast<int>(texel & (width - 1));
    run.Y = static_cast<int>(texel >> layout.WidthLog2);
    run.FirstValue = done;
    const int64_t left = count - done;
    if (run.X == 0 && left >= width)
    {
      run.Width = static_cast<int>(width);
      run.Rows = static_cast<int>(left >> layout.WidthLog2);
    }
    else
    {
      run.Width = static_cast<int>(std::min(left, width - run.X));
      run.Rows = 1;
    }
    done += static_cast<int64_t>(run.Width) * run.Rows;
    runs.push_back(run);
  }
  return runs;
}

} // namespace amrsp
