// SPDX-License-Identifier: BSD-3-Clause
// The packed-atlas storage (paper, section 5.1): every brick in one R32F 3D texture, or in up to
// four of them (pages, AMRSP_ATLAS_PAGES) when one would exceed the texture limits. The data node
// holds the texel of its block's lower-corner cell in the atlas, and with pages the page.
// The atlas reads are shared with the multi-pass node shader (MultiPassAMR.frag.glsl, which
// splices this piece at its //AMRSP::GridStorage and defines no AMRSP_PACKING).
// Each storage piece (StoragePackedAtlas.glsl, StorageBindless.glsl, StorageLinearBricks.glsl)
// defines the same two functions, which are all the rest of the single-pass shader knows of it:
//   uvec2 amrspBrickRef(uvec2 dataNode): what finds the data node's brick beyond its texel offset
//     (a handle, a table entry; nothing for the atlas), read once per segment;
//   float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where): the brick's
//     value at `texel` (cells) or trilinear at `where` (vertices), as amrspBrickPosition gives them.
// Spliced into SinglePassAMRRay.glsl at //AMRSP::GridStorage, after the kD-tree layout's accessors.

uniform sampler3D amrspAtlas; // R32F, one brick per grid (nearest filtering); page 0
uniform vec3 amrspAtlasSize;  // atlas dimensions, texels
#ifdef AMRSP_ATLAS_PAGES
// the bricks fill several atlas textures (pages); amrspAtlas is page 0
uniform sampler3D amrspAtlas1;
#if AMRSP_ATLAS_PAGES > 2
uniform sampler3D amrspAtlas2;
#endif
#if AMRSP_ATLAS_PAGES > 3
uniform sampler3D amrspAtlas3;
#endif
uniform vec3 amrspAtlasPageSize[AMRSP_ATLAS_PAGES]; // every page's dimensions, texels
#endif

#ifdef AMRSP_ATLAS_PAGES
// amrspReadAtlas from atlas page `page`. The page varies from ray to ray, so each page's texture
// has a branch of its own (a sampler cannot be chosen by a non-uniform index in GLSL 1.50).
float amrspReadAtlasPage(uint page, ivec3 texel, vec3 where)
{
#ifdef AMRSP_VERTEX_CENTRED
  vec3 t = where / amrspAtlasPageSize[page];
#define AMRSP_READ_PAGE(atlas) textureLod(atlas, t, 0.0).r
#else
#define AMRSP_READ_PAGE(atlas) texelFetch(atlas, texel, 0).r
#endif
  if (page == 0u)
  {
    return AMRSP_READ_PAGE(amrspAtlas);
  }
#if AMRSP_ATLAS_PAGES > 2
  if (page == 2u)
  {
    return AMRSP_READ_PAGE(amrspAtlas2);
  }
#endif
#if AMRSP_ATLAS_PAGES > 3
  if (page == 3u)
  {
    return AMRSP_READ_PAGE(amrspAtlas3);
  }
#endif
  return AMRSP_READ_PAGE(amrspAtlas1);
#undef AMRSP_READ_PAGE
}
#endif

// The packed atlas's value at amrspBrickPosition's texel (cells) or where (vertices).
float amrspReadAtlas(ivec3 texel, vec3 where)
{
#ifdef AMRSP_VERTEX_CENTRED
  return textureLod(amrspAtlas, where / amrspAtlasSize, 0.0).r;
#else
  return texelFetch(amrspAtlas, texel, 0).r;
#endif
}

#ifdef AMRSP_PACKING
// The packed atlas needs nothing beyond the data node to find a brick.
uvec2 amrspBrickRef(uvec2 dataNode)
{
  return uvec2(0u);
}

float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where)
{
#ifdef AMRSP_ATLAS_PAGES
  return amrspReadAtlasPage(amrspDataPage(dataNode), texel, where);
#else
  return amrspReadAtlas(texel, where);
#endif
}
#endif
