// SPDX-License-Identifier: BSD-3-Clause
// Where a sample falls in a brick: shared by the single-pass shader (SinglePassAMRRay.glsl, at
// //AMRSP::BrickSample) and the multi-pass node shader (MultiPassAMR.frag.glsl), so that both take
// the same value at the same point. The reads are the storage's (Storage*.glsl).
//
// A data node's block covers the cells firstCell..lastCell of its level, whose cells measure
// cellSize (level-0 index units); `offset` is the texel of the block's lower-corner cell (in the
// atlas, or in the node's own brick with bindless textures).

// p (level-0 index units) -> `texel`, the texel to fetch for cell data (the nearest cell, clamped
// into the block so float error never reaches a neighbouring brick) or the lower texel of the
// trilinear stencil for vertex data (kept one texel below the brick's upper end), and `where`,
// p's texture coordinate in texels for hardware trilinear filtering (vertex data; 0 for cells).
void amrspBrickPosition(vec3 p, vec3 cellSize, ivec3 firstCell, ivec3 lastCell, ivec3 offset,
  out ivec3 texel, out vec3 where)
{
#ifdef AMRSP_VERTEX_CENTRED
  // vertex (i,j,k) of the block's first cell is texel offset + (i,j,k); texel centres at +0.5
  vec3 u = clamp(p / cellSize - vec3(firstCell), vec3(0.0), vec3(lastCell - firstCell + 1));
  where = vec3(offset) + u + 0.5;
  texel = offset + min(ivec3(floor(u)), lastCell - firstCell);
#else
  ivec3 cell = clamp(ivec3(floor(p / cellSize)), firstCell, lastCell);
  texel = offset + (cell - firstCell);
  where = vec3(0.0);
#endif
}
