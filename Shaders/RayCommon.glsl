// SPDX-License-Identifier: BSD-3-Clause
//
// Ray set-up, slab test and transfer-function lookup shared by the single-pass and the multi-pass
// fragment shaders (spliced in by the mappers at their //AMRSP::RayCommon marker, after the
// uniforms it reads are declared: amrspDCMCMatrix, amrspViewport, amrspEyeMC, amrspTransfer,
// amrspTransferRange, amrspTransferSize and, with AMRSP_USE_DEPTH, amrspDepth).
//
// AMRSP_REDUCED_IMAGE (with AMRSP_USE_DEPTH): the rays go into an image smaller than the viewport
// (an interactive frame of the single-pass mapper); amrspViewport is that image, and the
// viewport-sized depth is read at the pixel amrspDepthScale (viewport / image size) times farther.

#ifdef AMRSP_REDUCED_IMAGE
uniform vec2 amrspDepthScale;
#endif

#define AMRSP_INF 3.0e38

// Slab test, as amrsp::IntersectBox.
bool amrspIntersectBox(vec3 lo, vec3 hi, vec3 o, vec3 d, out float tEnter, out float tExit)
{
  tEnter = -AMRSP_INF;
  tExit = AMRSP_INF;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    float t0 = (lo[a] - o[a]) / d[a];
    float t1 = (hi[a] - o[a]) / d[a];
    if (t0 > t1)
    {
      float s = t0;
      t0 = t1;
      t1 = s;
    }
    tEnter = max(tEnter, t0);
    tExit = min(tExit, t1);
  }
  return tEnter < tExit;
}

// Colour and unit-distance opacity of a scalar: the table's entries span amrspTransferRange,
// sampled linearly between entry centres and clamped at both ends. With AMRSP_LOG_TRANSFER (a
// log-scaled colour or opacity function) the table is indexed by log10 of the scalar and its
// range is in log10 units; a scalar at or below 0 takes the first entry (GLSL's log2 is
// undefined there). Level 0 explicitly: implicit derivatives are undefined in a compute shader
// and in a fragment shader's non-uniform control flow.
vec4 amrspTransferFunction(float scalar)
{
#ifdef AMRSP_LOG_TRANSFER
  scalar = scalar > 0.0 ? log2(scalar) * 0.30102999566398120 : -3.0e38;
#endif
  float u = clamp((scalar - amrspTransferRange.x) * amrspTransferRange.y, 0.0, 1.0);
  float x = (u * (amrspTransferSize - 1.0) + 0.5) / amrspTransferSize;
  return textureLod(amrspTransfer, vec2(x, 0.5), 0.0);
}

// The ray through the pixel centre `pixel` (window coordinates, as gl_FragCoord.xy) in model
// coordinates: `entry` is the eye (perspective, as the CPU integrators' pinhole camera) or the
// point on the near plane (parallel projection), `dirMC` is unit length, and `tMax` is the
// model-space distance from `entry` to the opaque geometry already drawn (AMRSP_INF where there is
// none or without AMRSP_USE_DEPTH).
void amrspPixelRay(vec2 pixel, out vec3 entry, out vec3 dirMC, out float tMax)
{
  vec2 ndc = 2.0 * (pixel - amrspViewport.xy) / amrspViewport.zw - 1.0;
  vec4 nearMC = amrspDCMCMatrix * vec4(ndc, -1.0, 1.0);
  vec4 farMC = amrspDCMCMatrix * vec4(ndc, 1.0, 1.0);
  vec3 nearPoint = nearMC.xyz / nearMC.w;
  dirMC = normalize(farMC.xyz / farMC.w - nearPoint);
  entry = amrspEyeMC.w != 0.0 ? amrspEyeMC.xyz : nearPoint;
  tMax = AMRSP_INF;
#ifdef AMRSP_USE_DEPTH
#ifdef AMRSP_REDUCED_IMAGE
  float depth = texelFetch(amrspDepth, ivec2((pixel - amrspViewport.xy) * amrspDepthScale), 0).r;
#else
  float depth = texelFetch(amrspDepth, ivec2(pixel - amrspViewport.xy), 0).r;
#endif
  if (depth < 1.0)
  {
    vec4 hitMC = amrspDCMCMatrix * vec4(ndc, 2.0 * depth - 1.0, 1.0);
    tMax = dot(hitMC.xyz / hitMC.w - entry, dirMC);
  }
#endif
}
