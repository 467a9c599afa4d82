//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// Multi-pass raycaster of structured AMR data: the baseline Kaehler & Abel 2013 compare with
// (their reference vg06-kaehler, section 6). The CPU orders the kD-tree's data nodes front to
// back and draws each node's box once; this shader integrates the ray segment inside that ONE
// node and outputs its premultiplied colour and opacity. The mapper blends the draws front to
// back into a cleared RGBA32F target with (ONE_MINUS_DST_ALPHA, ONE).
//
// The segment is [max(tEnter, 0), min(tExit, depth)] of the node box, which the CPU computes in
// the same float arithmetic as the single-pass traversal (SinglePassAMRRay.glsl, amrsp::
// TraverseKdTree), and it is sampled by the same rule as amrsp::RenderKdTree (docs/design.md, "Sampling
// rule"); keep them in sync.
//
// Variants are selected by the mapper with #defines inserted at the marker below:
//   AMRSP_CELL_CENTRED   nearest-cell sampling of cell bricks
//   AMRSP_VERTEX_CENTRED trilinear sampling of vertex bricks (one texel larger per axis)
//   AMRSP_USE_DEPTH      clip rays at the depth of the opaque geometry already drawn
//AMRSP::Defines

#if !defined(AMRSP_CELL_CENTRED) && !defined(AMRSP_VERTEX_CENTRED)
#error "AMRSP_CELL_CENTRED or AMRSP_VERTEX_CENTRED must be defined"
#endif


//VTK::Output::Dec

uniform sampler2D amrspTransfer; // RGBA32F, 1 row: colour and unit-distance opacity
#ifdef AMRSP_USE_DEPTH
uniform sampler2D amrspDepth; // depth of the opaque geometry, viewport-sized
#endif

// ---- per frame
uniform mat4 amrspDCMCMatrix; // normalized device -> model coordinates (column-major)
uniform vec4 amrspViewport;   // lower-left corner and size of the viewport in the target, pixels
uniform vec4 amrspEyeMC;      // camera position in model coordinates; w = 0: parallel projection
uniform vec3 amrspOrigin;     // model position of level-0 index (0, 0, 0)
uniform vec3 amrspSpacing0;   // model size of a level-0 cell
uniform vec2 amrspTransferRange; // scalar at the first table entry, 1 / (last - first)
uniform float amrspTransferSize; // number of table entries
uniform float amrspUnitDistance; // vtkVolumeProperty::ScalarOpacityUnitDistance

// ---- per node (one draw)
uniform vec3 amrspNodeLo;       // the node's box, level-0 index units
uniform vec3 amrspNodeHi;
uniform vec3 amrspCellSize;     // a cell of the node's data level, level-0 index units
uniform float amrspStep;        // sampling distance D of that level, model units
uniform ivec3 amrspFirstCell;   // the node's first and last cell, in its level's index space
uniform ivec3 amrspLastCell;
uniform ivec3 amrspAtlasOffset; // atlas texel of amrspFirstCell

// Ray set-up, slab test and transfer function, shared with the single-pass shader
// (Shaders/RayCommon.glsl).
//AMRSP::RayCommon
//AMRSP::BrickSample
// The packed atlas (amrspAtlas, amrspAtlasSize) and its read amrspReadAtlas, as the single pass
// reads it (Shaders/StoragePackedAtlas.glsl).
//AMRSP::GridStorage

void main()
{
  vec3 entry, dirMC;
  float tMax;
  amrspPixelRay(gl_FragCoord.xy, entry, dirMC, tMax);

  // Level-0 index units; t stays the model-space distance along the ray.
  vec3 ro = (entry - amrspOrigin) / amrspSpacing0;
  vec3 rd = dirMC / amrspSpacing0;

  float tEnter, tExit;
  if (!amrspIntersectBox(amrspNodeLo, amrspNodeHi, ro, rd, tEnter, tExit))
  {
    discard;
  }
  float t = max(tEnter, 0.0);
  float tEnd = min(tExit, tMax);
  if (!(t < tEnd))
  {
    discard; // the node lies behind the eye or behind opaque geometry on this ray
  }

  // Sampling rule: n = max(1, ceil(length / D)) equal steps, sample k at (k + SampleOffset) dt.
  float segmentLength = tEnd - t;
  int n = max(1, int(ceil(segmentLength / amrspStep)));
  float dt = segmentLength / float(n);
  float exponent = dt / amrspUnitDistance;
  vec3 colour = vec3(0.0);
  float alpha = 0.0;
  for (int k = 0; k < n; ++k)
  {
    float ts = t + (float(k) + 0.4618034) * dt; // amrsp::SampleOffset
    vec3 p = ro + ts * rd;
    ivec3 texel;
    vec3 where;
    amrspBrickPosition(
      p, amrspCellSize, amrspFirstCell, amrspLastCell, amrspAtlasOffset, texel, where);
    float scalar = amrspReadAtlas(texel, where);
    if (isnan(scalar))
    {
      continue; // missing data is transparent
    }
    vec4 tf = amrspTransferFunction(scalar);
    if (tf.a > 0.0)
    {
      float a = 1.0 - pow(1.0 - min(tf.a, 1.0), exponent);
      colour += (1.0 - alpha) * a * tf.rgb;
      alpha += (1.0 - alpha) * a;
    }
  }

  if (alpha <= 0.0)
  {
    discard;
  }
  // premultiplied colour and opacity of this segment only; the blending composites the segments
  gl_FragData[0] = vec4(colour, alpha);
}
