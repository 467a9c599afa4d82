// SPDX-License-Identifier: BSD-3-Clause
// The bindless storage (paper, section 5.2): one R32F 3D texture per brick, reached through its
// GL_ARB_bindless_texture handle, kept resident and stored in amrspHandles (index: the data
// node's brick). The data node holds the texel of its block's lower-corner cell in its own brick.
// With AMRSP_WATERFALL one distinct handle is served at a time (GL_ARB_shader_ballot), for
// drivers that need dynamically uniform handles. The extensions are required at the top of
// SinglePassAMRRay.glsl (GLSL wants them before any declaration).
// Each storage piece (StoragePackedAtlas.glsl, StorageBindless.glsl, StorageLinearBricks.glsl)
// defines the same two functions, which are all the rest of the single-pass shader knows of it:
//   uvec2 amrspBrickRef(uvec2 dataNode): what finds the data node's brick beyond its texel offset
//     (a handle, a table entry; nothing for the atlas), read once per segment;
//   float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where): the brick's
//     value at `texel` (cells) or trilinear at `where` (vertices), as amrspBrickPosition gives them.
// Spliced into SinglePassAMRRay.glsl at //AMRSP::GridStorage, after the kD-tree layout's accessors.

uniform usampler3D amrspHandles;   // RG32UI, one texel per brick: its 64-bit handle (low, high)

// Reads brick `handle` at texel `texel` (cells), or interpolates it trilinearly at the texel-space
// position `where` (vertices: texel centres at integer + 0.5) from the texels texel and
// texel + 1 per axis, which the caller keeps inside the brick.
float amrspReadBrick(uvec2 handle, ivec3 texel, vec3 where)
{
  // the sampler built in each fetch: a sampler held in a local variable is not accepted by every
  // compiler (glslang 12), the constructor in an argument is
#ifdef AMRSP_VERTEX_CENTRED
  vec3 f = where - 0.5 - vec3(texel);
  float c000 = texelFetch(sampler3D(handle), texel, 0).r;
  float c100 = texelFetch(sampler3D(handle), texel + ivec3(1, 0, 0), 0).r;
  float c010 = texelFetch(sampler3D(handle), texel + ivec3(0, 1, 0), 0).r;
  float c110 = texelFetch(sampler3D(handle), texel + ivec3(1, 1, 0), 0).r;
  float c001 = texelFetch(sampler3D(handle), texel + ivec3(0, 0, 1), 0).r;
  float c101 = texelFetch(sampler3D(handle), texel + ivec3(1, 0, 1), 0).r;
  float c011 = texelFetch(sampler3D(handle), texel + ivec3(0, 1, 1), 0).r;
  float c111 = texelFetch(sampler3D(handle), texel + ivec3(1, 1, 1), 0).r;
  return mix(mix(mix(c000, c100, f.x), mix(c010, c110, f.x), f.y),
    mix(mix(c001, c101, f.x), mix(c011, c111, f.x), f.y), f.z);
#else
  return texelFetch(sampler3D(handle), texel, 0).r;
#endif
}

// What locates the brick of data node `dataNode`: its bindless handle, from amrspHandles. A
// segment reads it once for all its samples.
uvec2 amrspBrickRef(uvec2 dataNode)
{
  return texelFetch(amrspHandles, amrspTexelOf(amrspDataBrick(dataNode)), 0).rg;
}

// amrspReadBrick on the brick whose handle is `handle` (amrspBrickRef).
float amrspReadBrickRef(uvec2 handle, ivec3 texel, vec3 where)
{
#ifdef AMRSP_WATERFALL
  // Each pass serves the invocations holding the first active invocation's handle, which is
  // dynamically uniform among them; the others loop again (at most one pass per distinct handle).
  float value = 0.0;
  for (;;)
  {
    uvec2 first = readFirstInvocationARB(handle);
    if (first == handle)
    {
      value = amrspReadBrick(first, texel, where);
      break;
    }
  }
  return value;
#else
  return amrspReadBrick(handle, texel, where);
#endif
}

float amrspReadStorage(uvec2 dataNode, uvec2 brickRef, ivec3 texel, vec3 where)
{
  return amrspReadBrickRef(brickRef, texel, where);
}
