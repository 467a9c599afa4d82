// SPDX-License-Identifier: BSD-3-Clause
//
// Single-pass raycaster of structured AMR data (Kaehler & Abel 2013, section 4.3): the ray of one
// pixel, shared by the fragment-shader caster (SinglePassAMR.frag.glsl, one fragment per pixel
// of the proxy box's back faces) and the compute-shader caster (SinglePassAMR.comp.glsl, one
// invocation per pixel of the rays' image). Each stage file places this source at its
// CastRay marker, right after the defines, and calls amrspCastRay from its main().
//
// Per pixel: rebuild the ray from the pixel's window position, walk the encoded kD-tree with
// kd-restart (each restart descends from the root to the node that contains the ray's current
// point and ends at the nearest split plane crossed or the node's exit), sample every data
// segment at its level's rate, and composite front to back. The traversal mirrors Core/src/KdTraversal.cxx step by step
// (same float arithmetic, plane and tie rules) and the sampling mirrors amrsp::RenderKdTree
// (docs/design.md, "Sampling rule"); keep the three in sync.
//
// Variants are selected by the mapper with #defines inserted at the marker below:
//   AMRSP_LEVEL_COUNT   number of levels of the hierarchy (sizes the per-level uniform arrays)
//   AMRSP_PACKING       data in one packed R32F atlas, or
//   AMRSP_BINDLESS      one R32F texture per brick, reached through GL_ARB_bindless_texture
//                       handles stored in the amrspHandles texture (index: the data node's brick)
//   AMRSP_LINEAR        the bricks back to back in 2D R32F textures (amrspLinear, amrspLinear1..)
//                       of 2^AMRSP_LINEAR_WIDTH_LOG2 texels per row, found through the
//                       amrspBrickTable texture (amrsp/LinearBricks.h), whose first word keeps
//                       the page above AMRSP_LINEAR_BASE_BITS; AMRSP_LINEAR_PAGES: their number
//                       when there are several
//   AMRSP_WATERFALL     (bindless) serve one distinct handle at a time with GL_ARB_shader_ballot,
//                       for drivers that require dynamically uniform handles
//   AMRSP_POWER_OF_TWO_REFINEMENT every level's finest cells per cell is a power of two per axis
//                       (amrspLevelToFinestLog2 holds the exponents)
//   AMRSP_UNIFORM_REFINEMENT_LOG2 k: every level refines the one above by 2^k on every axis (with
//                       AMRSP_POWER_OF_TWO_REFINEMENT); the per-level constants are then computed
//                       from the level instead of read from the per-level uniform arrays
//   AMRSP_CELL_CENTRED  nearest-cell sampling of cell bricks
//   AMRSP_VERTEX_CENTRED trilinear sampling of vertex bricks (one texel larger per axis)
//   AMRSP_USE_DEPTH     clip rays at the depth of the opaque geometry already drawn
//   AMRSP_BLEND_MODE    0 composite, 1 maximum, 2 minimum, 3 average intensity, 4 iso-surfaces
//                       (amrsp::BlendMode)
//   AMRSP_SHADE         gradient shading (composite and iso-surfaces); rules in amrsp/Shading.h
//   AMRSP_SHADOWS       shadow rays toward the light (composite and iso-surfaces)
//   AMRSP_SKIP_EMPTY    empty-space skipping (composite only): data segments whose node's value
//                       range has zero opacity in the transfer table are not sampled
//   AMRSP_SMOOTH_CELLS  smooth reconstruction of cell data (with AMRSP_CELL_CENTRED): trilinear in
//                       the sample level's dual cell, corners from the sample's grid (covered
//                       cells too) or, outside it, looked up through the tree (a coarser level's
//                       trilinear value there), as amrsp::RenderSettings::SmoothCellData; the
//                       gradient's neighbours (AMRSP_SHADE) are reconstructed the same way
//   AMRSP_FLAT_LOOP     march the ray in one loop of single traversal or sample operations
//                       instead of nested segment, descent and sample loops (Shaders/RaySteps.glsl;
//                       the same segments, samples and image)
//   AMRSP_ROPES         neighbour links (amrsp/KdTreeRopes.h) in amrspRopes: a ray that leaves a
//                       leaf through one face continues from that face's rope (where the level
//                       of detail is off), as amrsp::TraverseKdTree
//   AMRSP_ABLATION      diagnostic ablations that locate a frame's time (not images): 1 traversal
//                       only (every data segment adds a constant instead of being sampled), 2
//                       sampling only (the first data segment's brick is sampled
//                       amrspAblationSamples times over the rest of the ray, no further traversal)
//   AMRSP_ACCELERATION_COUNTS diagnostic output: the ray's work counts instead of its colour (opaque,
//                       8-bit exact): red skipped data segments, green 1 when the ray stopped
//                       early, blue data segments reached; counted as amrsp::RenderStats counts
//   AMRSP_LOOP_COUNT    diagnostic output: one count of the ray's loops instead of its colour,
//                       as a 24-bit integer (red the low byte, opaque): 1 segment-loop
//                       iterations, 2 descent steps, 3 samples (amrsp/WorkCounters.h)
//   AMRSP_OCCUPANCY_PROBE diagnostic output (GL_NV_shader_thread_group): where the ray ran
//                       instead of its colour, opaque and 8-bit exact: red the multiprocessor
//                       (gl_SMIDNV), green the warp slot on it (gl_WarpIDNV), blue the chip's
//                       multiprocessors (gl_SMCountNV), for every ray that meets the volume

#ifndef AMRSP_LEVEL_COUNT
#error "AMRSP_LEVEL_COUNT must be defined"
#endif
#if defined(AMRSP_BINDLESS)
#extension GL_ARB_bindless_texture : require
#if defined(AMRSP_WATERFALL)
#extension GL_ARB_shader_ballot : require
#endif
#elif !defined(AMRSP_PACKING) && !defined(AMRSP_LINEAR)
#error "AMRSP_PACKING, AMRSP_BINDLESS or AMRSP_LINEAR must be defined"
#endif
#ifdef AMRSP_OCCUPANCY_PROBE
#extension GL_NV_shader_thread_group : require
#endif
#ifndef AMRSP_BLEND_MODE
#define AMRSP_BLEND_MODE 0
#endif
#if !defined(AMRSP_CELL_CENTRED) && !defined(AMRSP_VERTEX_CENTRED)
#error "AMRSP_CELL_CENTRED or AMRSP_VERTEX_CENTRED must be defined"
#endif

// The tree layout, shared verbatim with the C++ encoder (Shaders/KdTreeLayout.glsl).
#define AMRSP_FN
//AMRSP::KdTreeLayout

uniform usampler3D amrspTree;      // RG32UI, one texel per kD node
uniform usampler3D amrspDataNodes; // RG32UI, one texel per data node (texel 0 unused)
#ifdef AMRSP_ROPES
uniform usampler3D amrspRopes;   // RGBA32UI, three texels per kD node: box and ropes
uniform vec3 amrspRopeCellSize;  // a finest-level cell, level-0 index units (exact power of two)
#endif
uniform sampler2D amrspTransfer;   // RGBA32F, 1 row: colour and unit-distance opacity
#ifdef AMRSP_SMOOTH_CELLS
// RG32UI, three texels per brick (3 b + axis): its grid's cells lo, hi (exclusive) on that axis,
// in cells of the grid's level (signed integers stored bit for bit)
uniform usampler3D amrspBrickBoxes;
#endif
#ifdef AMRSP_USE_DEPTH
uniform sampler2D amrspDepth;      // depth of the opaque geometry, viewport-sized
#endif

uniform mat4 amrspDCMCMatrix; // normalized device -> model coordinates (column-major)
uniform vec4 amrspViewport;   // lower-left corner and size of the viewport, window pixels
uniform vec4 amrspEyeMC;      // camera position in model coordinates; w = 0: parallel projection

uniform vec3 amrspOrigin;   // model position of level-0 index (0, 0, 0)
uniform vec3 amrspSpacing0; // model size of a level-0 cell
uniform vec3 amrspRootLo;   // root box, level-0 index units
uniform vec3 amrspRootHi;
uniform vec3 amrspClipLo;   // where rays are integrated, level-0 index units: the root box, or
uniform vec3 amrspClipHi;   // its intersection with vtkVolumeMapper's cropping sub-volume
uniform int amrspRootLoFinest[3]; // root box in cells of the finest level (exact integers)
uniform int amrspRootHiFinest[3];
uniform vec3 amrspLevelCellSize[AMRSP_LEVEL_COUNT];      // cell size, level-0 index units
uniform int amrspLevelToFinest[3 * AMRSP_LEVEL_COUNT];   // finest cells per cell of a level
#ifdef AMRSP_POWER_OF_TWO_REFINEMENT
uniform int amrspLevelToFinestLog2[3 * AMRSP_LEVEL_COUNT]; // their base-2 logarithms
#endif
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
uniform float amrspFinestCellSize; // cell size of the finest level, level-0 index units (2^-k(L-1))
#endif
uniform float amrspLevelStep[AMRSP_LEVEL_COUNT];         // sampling distance D, model units
uniform int amrspMaxSegments;                             // guard against corrupt textures
#if defined(AMRSP_ABLATION) && AMRSP_ABLATION == 2
uniform int amrspAblationSamples; // samples of the one brick per ray
#endif

uniform vec2 amrspTransferRange; // scalar at the first table entry, 1 / (last - first)
uniform float amrspTransferSize; // number of table entries
uniform float amrspUnitDistance; // vtkVolumeProperty::ScalarOpacityUnitDistance
// Early ray termination: a composite ray stops once its opacity reaches this (1: never early).
uniform float amrspOpacityThreshold;
#ifdef AMRSP_SKIP_EMPTY
// R8, indexed like amrspDataNodes: 1 where the node's value range has zero opacity in the
// transfer table (amrsp::TableRangeTransparent, evaluated by the mapper per table)
uniform sampler3D amrspTransparentFlags;
#endif

// Level of detail at type (a) nodes, as amrsp::LevelOfDetail: stop descending when one cell of
// the node's data level is smaller than amrspLodThreshold pixels at the ray's entry.
uniform float amrspLodThreshold;         // pixels; 0 = always the finest level
uniform float amrspPixelSizePerDistance; // perspective: model size of a pixel at distance 1
uniform float amrspParallelPixelSize;    // parallel projection: model size of a pixel (> 0)

#if defined(AMRSP_SHADE) || defined(AMRSP_SHADOWS) || AMRSP_BLEND_MODE == 4
// Shading, shadows and iso-surfaces (the rules of Core/include/amrsp/Shading.h).
#define AMRSP_SHADOW_MAX_STEPS 4096
#define AMRSP_SHADOW_MIN_TRANSMITTANCE 1.0e-3
#define AMRSP_ISO_REFINE_STEPS 8
#define AMRSP_MAX_ISO_VALUES 8
uniform float amrspAmbient;       // vtkVolumeProperty Ambient, Diffuse, Specular, SpecularPower
uniform float amrspDiffuse;
uniform float amrspSpecular;
uniform float amrspSpecularPower;
uniform int amrspLightPositional; // 1: point light at amrspLightPositionMC; 0: directional
uniform vec3 amrspLightPositionMC;
uniform vec3 amrspLightDirectionMC; // unit, toward the light (directional)
uniform vec3 amrspLightColour;      // diffuse colour x intensity
uniform float amrspShadowStep;      // shadow-ray step, model units
uniform float amrspIsoValues[AMRSP_MAX_ISO_VALUES]; // ascending
uniform int amrspIsoCount;
#endif

// Ray set-up, slab test and transfer function, shared with the multi-pass shader
// (Shaders/RayCommon.glsl).
//AMRSP::RayCommon

uvec2 amrspFetchNode(uint index)
{
  return texelFetch(amrspTree, amrspTexelOf(index), 0).rg;
}

uvec2 amrspFetchDataNode(uint index)
{
  return texelFetch(amrspDataNodes, amrspTexelOf(index), 0).rg;
}

#ifdef AMRSP_ROPES
uvec4 amrspFetchRope(uint node, uint k)
{
  return texelFetch(amrspRopes, amrspTexelOf(amrspRopeTexelIndex(node, k)), 0);
}

// Where the ray leaves the box [lo, hi]: as amrspIntersectBox's exit.
float amrspExitDistance(vec3 lo, vec3 hi, vec3 ro, vec3 rd)
{
  float t = AMRSP_INF;
  for (int a = 0; a < 3; ++a)
  {
    if (rd[a] != 0.0)
    {
      t = min(t, ((rd[a] > 0.0 ? hi[a] : lo[a]) - ro[a]) / rd[a]);
    }
  }
  return t;
}

// The one axis whose far face of [lo, hi] the ray reaches at tLeave; -1 for none or several.
int amrspExitAxis(vec3 lo, vec3 hi, vec3 ro, vec3 rd, float tLeave)
{
  int axis = -1;
  for (int a = 0; a < 3; ++a)
  {
    if (rd[a] != 0.0 && ((rd[a] > 0.0 ? hi[a] : lo[a]) - ro[a]) / rd[a] == tLeave)
    {
      if (axis >= 0)
      {
        return -1;
      }
      axis = a;
    }
  }
  return axis;
}
#endif

// ---- Per-level constants. A level comes from a texel, so it differs between fragments, and
// indexing a uniform array with it is a gather, lane by lane, on SIMD drivers. With uniform
// power-of-two refinement the constants are exact powers of two computed from the level.

#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
// Base-2 logarithm of the finest-level cells per cell of `level` (the same on every axis).
int amrspToFinestLog2Uniform(int level)
{
  return AMRSP_UNIFORM_REFINEMENT_LOG2 * (AMRSP_LEVEL_COUNT - 1 - level);
}
#endif

#ifdef AMRSP_POWER_OF_TWO_REFINEMENT
// Base-2 logarithms of the finest-level cells per cell of `level`, per axis.
ivec3 amrspToFinestLog2(int level)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return ivec3(amrspToFinestLog2Uniform(level));
#else
  return ivec3(amrspLevelToFinestLog2[3 * level], amrspLevelToFinestLog2[3 * level + 1],
    amrspLevelToFinestLog2[3 * level + 2]);
#endif
}
#endif

// Finest-level cells per cell of `level` on `axis`.
int amrspToFinestOnAxis(int level, int axis)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return 1 << amrspToFinestLog2Uniform(level);
#else
  return amrspLevelToFinest[3 * level + axis];
#endif
}

// Finest-level cells per cell of `level`, per axis.
ivec3 amrspToFinest(int level)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return ivec3(1 << amrspToFinestLog2Uniform(level));
#else
  return ivec3(amrspLevelToFinest[3 * level], amrspLevelToFinest[3 * level + 1],
    amrspLevelToFinest[3 * level + 2]);
#endif
}

// Cell size of `level` on `axis`, level-0 index units (exactly amrspLevelCellSize[level][axis]).
float amrspCellSizeOnAxis(int level, int axis)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return float(amrspToFinestOnAxis(level, axis)) * amrspFinestCellSize; // powers of two: exact
#else
  return amrspLevelCellSize[level][axis];
#endif
}

// Cell size of `level`, level-0 index units (exactly amrspLevelCellSize[level]).
vec3 amrspCellSize(int level)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return vec3(amrspCellSizeOnAxis(level, 0));
#else
  return amrspLevelCellSize[level];
#endif
}

// Sampling distance D of `level`, model units (exactly amrspLevelStep[level]: the steps of a
// uniform power-of-two refinement differ by powers of two).
float amrspStep(int level)
{
#ifdef AMRSP_UNIFORM_REFINEMENT_LOG2
  return amrspLevelStep[0] * amrspCellSizeOnAxis(level, 0);
#else
  return amrspLevelStep[level];
#endif
}

// Integer division rounding towards minus infinity (b > 0), and its ceiling counterpart.
int amrspFloorDiv(int a, int b)
{
  int q = a / b;
  return (q * b > a) ? q - 1 : q;
}

int amrspCeilDiv(int a, int b)
{
  return -amrspFloorDiv(-a, b);
}

//AMRSP::GridStorage

//AMRSP::BrickSample

// The scalar at point p (level-0 index units) inside the kD node whose data node is `dataNode`
// and whose brick reference is brickRef (amrspBrickRef(dataNode)): the node's block covers the
// cells firstCell..lastCell of the node's data level, whose cells measure cellSize (level-0 index
// units). How the bricks are stored is the storage piece's (amrspReadStorage).
float amrspSampleBrick(uvec2 dataNode, uvec2 brickRef, vec3 p, vec3 cellSize, ivec3 firstCell,
  ivec3 lastCell)
{
  // texel of the node's lower-corner cell, in the atlas (packing) or in its brick (bindless)
  ivec3 texel;
  vec3 where;
  amrspBrickPosition(p, cellSize, firstCell, lastCell, amrspDataOffset(dataNode), texel, where);
  return amrspReadStorage(dataNode, brickRef, texel, where);
}

// amrspSampleBrick for a point lookup, which reads the brick reference itself.
float amrspSampleDataNode(uvec2 dataNode, vec3 p, vec3 cellSize, ivec3 firstCell, ivec3 lastCell)
{
  return amrspSampleBrick(dataNode, amrspBrickRef(dataNode), p, cellSize, firstCell, lastCell);
}

// The cells firstCell..lastCell of data level `level` that cover the node box loF..hiF (exact
// finest-level cells): the cells a segment in that node samples.
void amrspLeafCells(int level, ivec3 loF, ivec3 hiF, out ivec3 firstCell, out ivec3 lastCell)
{
#ifdef AMRSP_POWER_OF_TWO_REFINEMENT
  // arithmetic shifts floor the quotient (integer division per lane is slow on SIMD drivers)
  ivec3 shift = amrspToFinestLog2(level);
  firstCell = loF >> shift;
  lastCell = -((-hiF) >> shift) - 1;
#else
  ivec3 toData = amrspToFinest(level);
  firstCell = ivec3(amrspFloorDiv(loF.x, toData.x), amrspFloorDiv(loF.y, toData.y),
    amrspFloorDiv(loF.z, toData.z));
  lastCell = ivec3(amrspCeilDiv(hiF.x, toData.x), amrspCeilDiv(hiF.y, toData.y),
               amrspCeilDiv(hiF.z, toData.z)) - 1;
#endif
}

// Narrows a node box (level-0 index units lo..hi, exact finest-level cells loF..hiF) to its lower
// (below the split plane on `axis`) or upper child's box.
void amrspChildBox(inout vec3 lo, inout vec3 hi, inout ivec3 loF, inout ivec3 hiF, int axis,
  float plane, int planeF, bool lower)
{
  if (lower)
  {
    hi[axis] = plane;
    hiF[axis] = planeF;
  }
  else
  {
    lo[axis] = plane;
    loF[axis] = planeF;
  }
}

// (one line: GLSL before 4.20 has no line continuation)
#if defined(AMRSP_SMOOTH_CELLS) || defined(AMRSP_SHADE) || defined(AMRSP_SHADOWS) || AMRSP_BLEND_MODE == 4
// Point location, as the core's LocateDataNode: from the root to the leaf containing p (level-0
// index units); a point on a split plane goes to the upper side. Returns the data index (0: empty
// leaf or outside the root box) and the leaf's box in exact finest-level cells.
uint amrspLocateDataNode(vec3 p, out ivec3 loF, out ivec3 hiF)
{
  vec3 lo = amrspRootLo;
  vec3 hi = amrspRootHi;
  loF = ivec3(amrspRootLoFinest[0], amrspRootLoFinest[1], amrspRootLoFinest[2]);
  hiF = ivec3(amrspRootHiFinest[0], amrspRootHiFinest[1], amrspRootHiFinest[2]);
  if (any(lessThan(p, lo)) || any(greaterThanEqual(p, hi)))
  {
    return 0u;
  }
  uvec2 texel = amrspFetchNode(0u);
  for (int depth = 0; depth < amrspMaxSegments; ++depth) // a guard against corrupt textures
  {
    uint child = amrspNodeFirstChild(texel);
    if (child == 0u)
    {
      break;
    }
    int axis = int(amrspNodeAxis(texel));
    uint level = amrspNodeLevel(texel);
    uint split = amrspNodeSplit(texel);
    float plane = lo[axis] + float(split) * amrspCellSizeOnAxis(int(level), axis);
    int planeF = loF[axis] + int(split) * amrspToFinestOnAxis(int(level), axis);
    bool lower = p[axis] < plane;
    amrspChildBox(lo, hi, loF, hiF, axis, plane, planeF, lower);
    texel = amrspFetchNode(lower ? child : child + 1u);
  }
  return amrspNodeData(texel);
}

// The nearest-cell value at p (level-0 index units) in the leaf containing it, with the leaf's
// data node, data level and cells (amrspLeafCells); false outside every leaf with data.
bool amrspLocateSample(vec3 p, out uvec2 dataNode, out int level, out ivec3 loF, out ivec3 hiF,
  out ivec3 firstCell, out ivec3 lastCell, out float value)
{
  uint data = amrspLocateDataNode(p, loF, hiF);
  dataNode = amrspFetchDataNode(data);
  level = int(amrspDataLevel(dataNode));
  amrspLeafCells(level, loF, hiF, firstCell, lastCell);
  value = data != 0u
    ? amrspSampleDataNode(dataNode, p, amrspCellSize(level), firstCell, lastCell)
    : 0.0;
  return data != 0u;
}
#endif

//AMRSP::SmoothCells

#ifdef AMRSP_SKIP_EMPTY
// Whether the data node's block is empty space under the current transfer function.
bool amrspDataNodeTransparent(uint dataIndex)
{
  return texelFetch(amrspTransparentFlags, amrspTexelOf(dataIndex), 0).r > 0.5;
}
#endif

//AMRSP::Shading

//AMRSP::RaySteps

// The ray through the pixel centre `pixel` (window coordinates of the rays' image, as
// gl_FragCoord.xy): false where it leaves the pixel as it is (it misses the box, or has nothing to
// show); else `result`, its premultiplied colour and opacity (blended "over" with ONE,
// ONE_MINUS_SRC_ALPHA), or with AMRSP_ACCELERATION_COUNTS / AMRSP_LOOP_COUNT its opaque work counts.
bool amrspCastRay(vec2 pixel, out vec4 result)
{
  result = vec4(0.0);
  if (!amrspBeginRay(pixel))
  {
#ifdef AMRSP_FRAGMENT_STAGE
    // at once, as the invocation's first act: lavapipe of Mesa 26.1 (zink) crashed in the bindless
    // waterfall of smooth cells when rays that missed were discarded only after the march
    discard;
#else
    return false;
#endif
  }
#ifdef AMRSP_FLAT_LOOP
  amrspMarchFlat();
#else
  amrspMarchNested();
#endif
  vec3 colour = amrspColour;
  float alpha = amrspAlpha;
#if AMRSP_BLEND_MODE != 0 && AMRSP_BLEND_MODE != 4
  // the kept scalar through the transfer function, without opacity correction
  if (!amrspAnySample)
  {
    return false;
  }
  float kept = amrspKept;
#if AMRSP_BLEND_MODE == 3
  kept = amrspWeightedSum / amrspSampledLength;
#endif
  vec4 keptTF = amrspTransferFunction(kept);
  alpha = min(keptTF.a, 1.0);
  colour = keptTF.rgb * alpha;
#endif
#ifdef AMRSP_ACCELERATION_COUNTS
  // as amrsp::RenderStats: a ray terminated early is a composite ray that reached a threshold < 1
  bool workTerminated = AMRSP_BLEND_MODE == 0 && amrspOpacityThreshold < 1.0 &&
    alpha >= amrspOpacityThreshold;
  result = vec4(float(min(amrspWorkDataSegments - amrspWorkSampledSegments, 255)) / 255.0,
    workTerminated ? 1.0 : 0.0, float(min(amrspWorkDataSegments, 255)) / 255.0, 1.0);
  return true;
#endif
#ifdef AMRSP_OCCUPANCY_PROBE
  // after the whole ray, so that the schedule is a real frame's
  result = vec4(float(min(gl_SMIDNV, 255u)), float(min(gl_WarpIDNV, 255u)),
             float(min(gl_SMCountNV, 255u)), 255.0) / 255.0;
  return true;
#endif
#ifdef AMRSP_LOOP_COUNT
  int c = min(amrspWorkCount, 0xffffff);
  result = vec4(float(c & 255), float((c >> 8) & 255), float(c >> 16), 255.0) / 255.0;
  return true;
#endif
  if (alpha <= 0.0)
  {
    return false;
  }
  result = vec4(colour, alpha);
  return true;
}
