// SPDX-License-Identifier: BSD-3-Clause
#include "amrsp/BrickAtlas.h"
#include "amrsp/KdTreeEncoding.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace amrsp
{

BrickAtlas BuildBrickAtlas(
  const Hierarchy& h, Packer packer, const glm::ivec3& maxDims, std::size_t maxBytes)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("the packed atlas needs values for every grid");
  }
  return FillBrickAtlas(h,
    PackBricks(BrickExtents(h, h.VertexCentred), packer, maxDims,
      static_cast<int64_t>(maxBytes / AtlasTexelBytes)));
}

namespace
{
/// The brick extents of `h` after checking that it has values for every grid and that `layout`
/// places one brick per grid (std::invalid_argument otherwise).
std::vector<glm::ivec3> CheckedBrickExtents(const Hierarchy& h, const AtlasLayout& layout)
{
  if (!h.HasValues())
  {
    throw std::invalid_argument("the packed atlas needs values for every grid");
  }
  std::vector<glm::ivec3> extents = BrickExtents(h, h.VertexCentred);
  if (layout.Origins.size() != extents.size())
  {
    throw std::invalid_argument("the atlas layout has " + std::to_string(layout.Origins.size()) +
      " bricks for " + std::to_string(extents.size()) + " grids");
  }
  return extents;
}
} // namespace

BrickAtlas FillBrickAtlas(const Hierarchy& h, AtlasLayout layout)
{
  const std::vector<glm::ivec3> extents = CheckedBrickExtents(h, layout);
  BrickAtlas atlas;
  atlas.Layout = std::move(layout);
  const glm::ivec3 d = atlas.Layout.Dims;
  atlas.Texels.assign(static_cast<std::size_t>(d.x) * d.y * d.z, 0.0f);
  for (std::size_t g = 0; g < h.Grids.size(); ++g)
  {
    const glm::i64vec3 e(extents[g]);
    const glm::ivec3 o = atlas.Layout.Origins[g];
    const float* src = h.Values[g].data();
    for (int64_t k = 0; k < e.z; ++k)
    {
      for (int64_t j = 0; j < e.y; ++j)
      {
        float* row =
          &atlas.Texels[(static_cast<std::size_t>(o.z + k) * d.y + (o.y + j)) * d.x + o.x];
        std::copy(src, src + e.x, row);
        src += e.x;
      }
    }
  }
  return atlas;
}

AtlasSlabFiller::AtlasSlabFiller(const Hierarchy& h, const AtlasLayout& layout)
  : H(h)
  , Layout(layout)
  , Extents(CheckedBrickExtents(h, layout))
  , ByFirstLayer(h.Grids.size())
{
  for (std::size_t g = 0; g < this->ByFirstLayer.size(); ++g)
  {
    this->ByFirstLayer[g] = g;
    this->TallestBrick = std::max(this->TallestBrick, this->Extents[g].z);
  }
  std::stable_sort(this->ByFirstLayer.begin(), this->ByFirstLayer.end(),
    [&layout](std::size_t a, std::size_t b) { return layout.Origins[a].z < layout.Origins[b].z; });
}

void AtlasSlabFiller::Fill(int z0, int z1, float* out) const
{
  const glm::ivec3 d = this->Layout.Dims;
  if (z0 < 0 || z1 < z0 || z1 > d.z)
  {
    throw std::invalid_argument("the atlas slab [" + std::to_string(z0) + ", " +
      std::to_string(z1) + ") is outside the atlas's " + std::to_string(d.z) + " layers");
  }
  const std::size_t layer = static_cast<std::size_t>(d.x) * static_cast<std::size_t>(d.y);
  std::fill(out, out + layer * static_cast<std::size_t>(z1 - z0), 0.0f);
  // a brick crossing the slab starts above z0 - TallestBrick and below z1
  const auto startsBefore = [this](int z)
  {
    return std::lower_bound(this->ByFirstLayer.begin(), this->ByFirstLayer.end(), z,
      [this](std::size_t g, int layerZ) { return this->Layout.Origins[g].z < layerZ; });
  };
  // copied in grid order, the order of the grids' values in memory
  std::vector<std::size_t> crossing(startsBefore(z0 - this->TallestBrick + 1), startsBefore(z1));
  std::sort(crossing.begin(), crossing.end());
  for (const std::size_t g : crossing)
  {
    const glm::ivec3 e = this->Extents[g];
    const glm::ivec3 o = this->Layout.Origins[g];
    const int k0 = std::max(z0, o.z), k1 = std::min(z1, o.z + e.z);
    for (int z = k0; z < k1; ++z)
    {
      const float* src = this->H.Values[g].data() +
        static_cast<std::size_t>(z - o.z) * static_cast<std::size_t>(e.y) * e.x;
      float* dst = out + static_cast<std::size_t>(z - z0) * layer;
      for (int j = 0; j < e.y; ++j)
      {
        std::copy(src, src + e.x,
          dst + static_cast<std::size_t>(o.y + j) * static_cast<std::size_t>(d.x) + o.x);
        src += e.x;
      }
    }
  }
}

void FillAtlasSlab(const Hierarchy& h, const AtlasLayout& layout, int z0, int z1, float* out)
{
  AtlasSlabFiller(h, layout).Fill(z0, z1, out);
}

std::size_t SeparateBrickBytes(const Hierarchy& h)
{
  std::size_t texels = 0;
  for (const glm::ivec3& e : BrickExtents(h, h.VertexCentred))
  {
    texels += static_cast<std::size_t>(e.x) * e.y * e.z;
  }
  return texels * AtlasTexelBytes;
}

std::size_t HandleTextureBytes(std::size_t bricks)
{
  const glm::ivec3 d = TextureDimsFor(bricks);
  return static_cast<std::size_t>(d.x) * d.y * d.z * 2 * sizeof(uint32_t);
}

} // namespace amrsp
