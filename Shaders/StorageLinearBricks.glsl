// SPDX-License-Identifier: BSD-3-Clause
// The linear storage: the bricks back to back in 2D R32F textures (amrspLinear, amrspLinear1..,
// AMRSP_LINEAR_PAGES of them when there are several) of 2^AMRSP_LINEAR_WIDTH_LOG2 texels per row,
// found through amrspBrickTable (amrsp/LinearBricks.h), whose first word keeps the page above
// AMRSP_LINEAR_BASE_BITS. The data node holds the texel of its block's lower-corner cell in its
// own brick.
// Each storage piece (StoragePackedAtlas.glsl, StorageBindless.glsl, StorageLinearBricks.glsl)
// defines the same two functions, which are all the rest of the single-pass shader knows of it:
//   uvec2 amrspBrickRef(uvec2 dataNode): what finds the data node's brick beyond its texel offset
//     (a handle, a table entry; nothing for the atlas), read once per segment;
//   float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where): the brick's
//     value at `texel` (cells) or trilinear at `where` (vertices), as amrspBrickPosition gives them.
// Spliced into SinglePassAMRRay.glsl at //AMRSP::GridStorage, after the kD-tree layout's accessors.

uniform sampler2D amrspLinear;     // R32F, the bricks back to back (page 0)
#ifdef AMRSP_LINEAR_PAGES
uniform sampler2D amrspLinear1;
#if AMRSP_LINEAR_PAGES > 2
uniform sampler2D amrspLinear2;
#endif
#if AMRSP_LINEAR_PAGES > 3
uniform sampler2D amrspLinear3;
#endif
#endif
// RG32UI, one texel per brick: its first texel | page << AMRSP_LINEAR_BASE_BITS, and its
// x | y sizes << 16
uniform usampler3D amrspBrickTable;

// Texel `index` of linear page `page`: row index >> AMRSP_LINEAR_WIDTH_LOG2. The page varies
// from ray to ray, so each page's texture has a branch of its own.
float amrspReadLinear(uint page, int index)
{
  ivec2 t = ivec2(index & ((1 << AMRSP_LINEAR_WIDTH_LOG2) - 1), index >> AMRSP_LINEAR_WIDTH_LOG2);
#ifdef AMRSP_LINEAR_PAGES
  if (page == 1u)
  {
    return texelFetch(amrspLinear1, t, 0).r;
  }
#if AMRSP_LINEAR_PAGES > 2
  if (page == 2u)
  {
    return texelFetch(amrspLinear2, t, 0).r;
  }
#endif
#if AMRSP_LINEAR_PAGES > 3
  if (page == 3u)
  {
    return texelFetch(amrspLinear3, t, 0).r;
  }
#endif
#endif
  return texelFetch(amrspLinear, t, 0).r;
}

// What locates the brick of data node `dataNode`: its entry of amrspBrickTable. A segment reads
// it once for all its samples.
uvec2 amrspBrickRef(uvec2 dataNode)
{
  return texelFetch(amrspBrickTable, amrspTexelOf(amrspDataBrick(dataNode)), 0).rg;
}

// The brick whose table entry is `entry` (amrspBrickRef) at texel `texel` of the brick (cells),
// or trilinear at `where` from the texels texel and texel + 1 per axis (vertices), as
// amrspReadBrick.
float amrspReadBrickRef(uvec2 entry, ivec3 texel, vec3 where)
{
  uint page = entry.x >> uint(AMRSP_LINEAR_BASE_BITS);
  int nx = int(entry.y & 0xffffu);
  int nxy = nx * int(entry.y >> 16u);
  int base = int(entry.x & ((1u << uint(AMRSP_LINEAR_BASE_BITS)) - 1u));
  int i = base + texel.x + nx * texel.y + nxy * texel.z;
#ifdef AMRSP_VERTEX_CENTRED
  vec3 f = where - 0.5 - vec3(texel);
  float c000 = amrspReadLinear(page, i);
  float c100 = amrspReadLinear(page, i + 1);
  float c010 = amrspReadLinear(page, i + nx);
  float c110 = amrspReadLinear(page, i + nx + 1);
  float c001 = amrspReadLinear(page, i + nxy);
  float c101 = amrspReadLinear(page, i + nxy + 1);
  float c011 = amrspReadLinear(page, i + nxy + nx);
  float c111 = amrspReadLinear(page, i + nxy + nx + 1);
  return mix(mix(mix(c000, c100, f.x), mix(c010, c110, f.x), f.y),
    mix(mix(c001, c101, f.x), mix(c011, c111, f.x), f.y), f.z);
#else
  return amrspReadLinear(page, i);
#endif
}

float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where)
{
  return amrspReadBrickRef(brickRef, texel, where);
}
