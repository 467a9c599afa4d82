// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/AtlasPages.h"

#include "amrsp/KdTreeLayout.h"

#include <algorithm>
#include <string>

namespace amrsp
{

int64_t AtlasPages::TotalTexels() const
{
  int64_t n = 0;
  for (const AtlasLayout& p : this->Pages)
  {
    n += p.TotalTexels;
  }
  return n;
}

namespace
{
/// The bricks split into `k` runs of consecutive grids with about equal used texels.
std::vector<std::vector<std::size_t>> ConsecutiveRuns(const std::vector<glm::ivec3>& extents, int k)
{
  int64_t total = 0;
  for (const glm::ivec3& e : extents)
  {
    total += static_cast<int64_t>(e.x) * e.y * e.z;
  }
  std::vector<std::vector<std::size_t>> runs(static_cast<std::size_t>(k));
  int64_t before = 0;
  for (std::size_t g = 0; g < extents.size(); ++g)
  {
    const glm::ivec3 e = extents[g];
    const int64_t texels = static_cast<int64_t>(e.x) * e.y * e.z;
    // the run holding the brick's middle texel
    const int64_t middle = before + texels / 2;
    const int run =
      static_cast<int>(std::min<int64_t>(k - 1, middle * k / std::max<int64_t>(1, total)));
    runs[static_cast<std::size_t>(run)].push_back(g);
    before += texels;
  }
  return runs;
}
} // namespace

AtlasPages PackBricksInPages(const std::vector<glm::ivec3>& extents, Packer packer,
  const glm::ivec3& maxDims, int64_t maxPageTexels)
{
  AtlasPages out;
  AtlasLayout one = PackBricks(extents, packer, maxDims);
  if (maxPageTexels <= 0 || one.TotalTexels <= maxPageTexels)
  {
    out.PageOfGrid.assign(extents.size(), 0);
    out.Origins = one.Origins;
    out.GridsOfPage.resize(1);
    for (std::size_t g = 0; g < extents.size(); ++g)
    {
      out.GridsOfPage[0].push_back(g);
    }
    out.Pages.push_back(std::move(one));
    return out;
  }
  for (int k = 2; k <= static_cast<int>(layout::MaxAtlasPages); ++k)
  {
    const std::vector<std::vector<std::size_t>> runs = ConsecutiveRuns(extents, k);
    AtlasPages trial;
    trial.PageOfGrid.assign(extents.size(), 0);
    trial.Origins.assign(extents.size(), glm::ivec3(0));
    bool fits = true;
    for (int p = 0; p < k && fits; ++p)
    {
      if (runs[static_cast<std::size_t>(p)].empty())
      {
        fits = false; // a brick larger than a page's share: try more pages
        break;
      }
      std::vector<glm::ivec3> pageExtents;
      for (std::size_t g : runs[static_cast<std::size_t>(p)])
      {
        pageExtents.push_back(extents[g]);
      }
      try
      {
        AtlasLayout page = PackBricks(pageExtents, packer, maxDims);
        fits = page.TotalTexels <= maxPageTexels;
        for (std::size_t i = 0; i < runs[static_cast<std::size_t>(p)].size(); ++i)
        {
          const std::size_t g = runs[static_cast<std::size_t>(p)][i];
          trial.PageOfGrid[g] = p;
          trial.Origins[g] = page.Origins[i];
        }
        trial.Pages.push_back(std::move(page));
      }
      catch (const PackingError&)
      {
        fits = false;
      }
    }
    if (fits)
    {
      trial.GridsOfPage = runs;
      return trial;
    }
  }
  throw PackingError("the bricks (" + std::to_string(one.UsedTexels) + " texels) do not fit " +
    std::to_string(layout::MaxAtlasPages) + " atlas pages of at most " +
    std::to_string(maxPageTexels) +
    " texels each; use the bindless storage or a coarser level of "
    "detail");
}

Hierarchy PageHierarchy(const Hierarchy& h, const AtlasPages& pages, int page)
{
  Hierarchy out;
  out.Origin = h.Origin;
  out.Spacing0 = h.Spacing0;
  out.RefinementRatio = h.RefinementRatio;
  out.VertexCentred = h.VertexCentred;
  out.ArrayName = h.ArrayName;
  for (std::size_t g : pages.GridsOfPage[static_cast<std::size_t>(page)])
  {
    out.Grids.push_back(h.Grids[g]);
    if (h.HasValues())
    {
      out.Values.push_back(h.Values[g]); // shares the values
    }
  }
  return out;
}

} // namespace amrsp
