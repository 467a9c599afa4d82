// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/Hierarchy.h"

#include <algorithm>

namespace amrsp
{

bool SameStructure(const Hierarchy& a, const Hierarchy& b)
{
  return a.Origin == b.Origin && a.Spacing0 == b.Spacing0 &&
    a.RefinementRatio == b.RefinementRatio && a.VertexCentred == b.VertexCentred &&
    a.ArrayName == b.ArrayName && a.Grids.size() == b.Grids.size() &&
    std::equal(a.Grids.begin(), a.Grids.end(), b.Grids.begin(),
      [](const Grid& x, const Grid& y) { return x.Level == y.Level && x.Cells == y.Cells; });
}

} // namespace amrsp
