// SPDX-License-Identifier: BSD-3-Clause
//
// The bit layout of the kD-tree textures (Kaehler & Abel 2013, section 4.2). This one file is
// compiled both as GLSL (included into the raycasting shader) and as C++ (through
// amrsp/KdTreeLayout.h, which defines uint/uvec2/ivec3 and AMRSP_FN before including it), so the
// encoder on the CPU and the decoder on the GPU cannot disagree. Keep it in the common subset of
// GLSL 1.50+ and C++17: unsigned arithmetic, no overloading, no references.
//
// Tree texture: RG32UI, one texel per kD node, the root at linear index 0.
//   red   bits  0- 1  split axis (0 = x, 1 = y, 2 = z; 3 = none, i.e. a leaf)
//         bits  2- 7  level: a leaf's data level; an inner node's split level (the level whose cell
//                     faces the split plane lies on, the unit of the split position)
//         bits  8-31  linear texel index of the first child; the second child is at index + 1.
//                     0 (the root's own index) means "no children": the node is a leaf.
//   green bits  0-10  split position in cells of the split level, relative to the node's lower
//                     corner (1 .. 2047)
//         bits 11-31  index into the data-nodes texture; 0 means "no data" (type (c) inner node, or
//                     an empty leaf outside every grid). Data index 0 is never used by a node.
// Data-nodes texture: RG32UI, one texel per data node (types (a) and (b)); texel 0 is unused.
//   red   storage-strategy specific: packing stores the atlas texel that holds the node's lower
//         corner (x bits 0-10, y bits 11-21, z bits 22-31); bindless stores the same offset inside
//         the node's own brick texture.
//   green bits  0- 5  data level (the level of the grid whose cells the node shows)
//         bits  6-29  brick index (the AMR grid; the index into the bindless handles texture)
//         bits 30-31  packing: the atlas page (texture) holding the brick; 0 with one atlas
// Rope texture (neighbour links, Popov et al. 2007): RGBA32UI, three texels per kD node n, at
// linear indices 3 n (AMRSP_ROPE_BOX), 3 n + 1 and 3 n + 2:
//   3 n      the node's box in finest-level cells: lo.x, lo.y, lo.z, hi.x (signed, bit for bit)
//   3 n + 1  hi.y, hi.z, the rope across the lower x face, the rope across the upper x face
//   3 n + 2  the ropes across the lower y, upper y, lower z and upper z faces
// A rope is the index of the deepest node whose box holds the whole face of n's box seen from
// outside n; 0 (the root, never a neighbour) where the face lies on the root box.
// Linear texel index i maps to the texel (i % 256, (i / 256) % 256, i / 65536) in every texture.

#define AMRSP_TEXTURE_ROW 256u
#define AMRSP_AXIS_SHIFT 0u
#define AMRSP_AXIS_BITS 2u
#define AMRSP_AXIS_NONE 3u
#define AMRSP_LEVEL_SHIFT 2u
#define AMRSP_LEVEL_BITS 6u
#define AMRSP_CHILD_SHIFT 8u
#define AMRSP_CHILD_BITS 24u
#define AMRSP_SPLIT_SHIFT 0u
#define AMRSP_SPLIT_BITS 11u
#define AMRSP_DATA_SHIFT 11u
#define AMRSP_DATA_BITS 21u
#define AMRSP_DN_LEVEL_SHIFT 0u
#define AMRSP_DN_LEVEL_BITS 6u
#define AMRSP_DN_BRICK_SHIFT 6u
#define AMRSP_DN_BRICK_BITS 24u
#define AMRSP_DN_PAGE_SHIFT 30u
#define AMRSP_DN_PAGE_BITS 2u
#define AMRSP_DN_OFFSET_X_SHIFT 0u
#define AMRSP_DN_OFFSET_X_BITS 11u
#define AMRSP_DN_OFFSET_Y_SHIFT 11u
#define AMRSP_DN_OFFSET_Y_BITS 11u
#define AMRSP_DN_OFFSET_Z_SHIFT 22u
#define AMRSP_DN_OFFSET_Z_BITS 10u

AMRSP_FN uint amrspField(uint word, uint shift, uint bits)
{
  return (word >> shift) & ((1u << bits) - 1u);
}

AMRSP_FN uint amrspPutField(uint value, uint shift, uint bits)
{
  return (value & ((1u << bits) - 1u)) << shift;
}

AMRSP_FN uint amrspNodeAxis(uvec2 node)
{
  return amrspField(node.x, AMRSP_AXIS_SHIFT, AMRSP_AXIS_BITS);
}

AMRSP_FN uint amrspNodeLevel(uvec2 node)
{
  return amrspField(node.x, AMRSP_LEVEL_SHIFT, AMRSP_LEVEL_BITS);
}

AMRSP_FN uint amrspNodeFirstChild(uvec2 node)
{
  return amrspField(node.x, AMRSP_CHILD_SHIFT, AMRSP_CHILD_BITS);
}

AMRSP_FN uint amrspNodeSplit(uvec2 node)
{
  return amrspField(node.y, AMRSP_SPLIT_SHIFT, AMRSP_SPLIT_BITS);
}

AMRSP_FN uint amrspNodeData(uvec2 node)
{
  return amrspField(node.y, AMRSP_DATA_SHIFT, AMRSP_DATA_BITS);
}

AMRSP_FN uvec2 amrspPackNode(uint axis, uint level, uint firstChild, uint split, uint data)
{
  return uvec2(amrspPutField(axis, AMRSP_AXIS_SHIFT, AMRSP_AXIS_BITS) |
      amrspPutField(level, AMRSP_LEVEL_SHIFT, AMRSP_LEVEL_BITS) |
      amrspPutField(firstChild, AMRSP_CHILD_SHIFT, AMRSP_CHILD_BITS),
    amrspPutField(split, AMRSP_SPLIT_SHIFT, AMRSP_SPLIT_BITS) |
      amrspPutField(data, AMRSP_DATA_SHIFT, AMRSP_DATA_BITS));
}

AMRSP_FN uint amrspDataLevel(uvec2 dataNode)
{
  return amrspField(dataNode.y, AMRSP_DN_LEVEL_SHIFT, AMRSP_DN_LEVEL_BITS);
}

AMRSP_FN uint amrspDataBrick(uvec2 dataNode)
{
  return amrspField(dataNode.y, AMRSP_DN_BRICK_SHIFT, AMRSP_DN_BRICK_BITS);
}

AMRSP_FN uint amrspDataPage(uvec2 dataNode)
{
  return amrspField(dataNode.y, AMRSP_DN_PAGE_SHIFT, AMRSP_DN_PAGE_BITS);
}

AMRSP_FN ivec3 amrspDataOffset(uvec2 dataNode)
{
  return ivec3(int(amrspField(dataNode.x, AMRSP_DN_OFFSET_X_SHIFT, AMRSP_DN_OFFSET_X_BITS)),
    int(amrspField(dataNode.x, AMRSP_DN_OFFSET_Y_SHIFT, AMRSP_DN_OFFSET_Y_BITS)),
    int(amrspField(dataNode.x, AMRSP_DN_OFFSET_Z_SHIFT, AMRSP_DN_OFFSET_Z_BITS)));
}

AMRSP_FN uvec2 amrspPackDataNode(uint level, uint brick, uint ox, uint oy, uint oz, uint page)
{
  return uvec2(amrspPutField(ox, AMRSP_DN_OFFSET_X_SHIFT, AMRSP_DN_OFFSET_X_BITS) |
      amrspPutField(oy, AMRSP_DN_OFFSET_Y_SHIFT, AMRSP_DN_OFFSET_Y_BITS) |
      amrspPutField(oz, AMRSP_DN_OFFSET_Z_SHIFT, AMRSP_DN_OFFSET_Z_BITS),
    amrspPutField(level, AMRSP_DN_LEVEL_SHIFT, AMRSP_DN_LEVEL_BITS) |
      amrspPutField(brick, AMRSP_DN_BRICK_SHIFT, AMRSP_DN_BRICK_BITS) |
      amrspPutField(page, AMRSP_DN_PAGE_SHIFT, AMRSP_DN_PAGE_BITS));
}

AMRSP_FN ivec3 amrspTexelOf(uint linearIndex)
{
  return ivec3(int(linearIndex % AMRSP_TEXTURE_ROW),
    int((linearIndex / AMRSP_TEXTURE_ROW) % AMRSP_TEXTURE_ROW),
    int(linearIndex / (AMRSP_TEXTURE_ROW * AMRSP_TEXTURE_ROW)));
}

AMRSP_FN uint amrspRopeTexelIndex(uint node, uint k)
{
  return 3u * node + k;
}

// The rope texel (k = 1 or 2) of node n that holds the rope across a face normal to `axis`.
AMRSP_FN uint amrspRopeTexelOfAxis(uint axis)
{
  return axis == 0u ? 1u : 2u;
}

// The rope across the lower (upper = false) or upper face normal to `axis`, from the node's rope
// texel amrspRopeTexelOfAxis(axis).
AMRSP_FN uint amrspRopeOf(uvec4 ropeTexel, uint axis, bool upper)
{
  return axis == 1u ? (upper ? ropeTexel.y : ropeTexel.x) : (upper ? ropeTexel.w : ropeTexel.z);
}

AMRSP_FN ivec3 amrspRopeBoxLo(uvec4 boxTexel)
{
  return ivec3(int(boxTexel.x), int(boxTexel.y), int(boxTexel.z));
}

AMRSP_FN ivec3 amrspRopeBoxHi(uvec4 boxTexel, uvec4 ropeTexelX)
{
  return ivec3(int(boxTexel.w), int(ropeTexelX.x), int(ropeTexelX.y));
}
