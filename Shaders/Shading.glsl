// SPDX-License-Identifier: BSD-3-Clause
// Gradient shading, shadow rays and iso-surfaces: the rules of Core/include/amrsp/Shading.h.
// Spliced into SinglePassAMRRay.glsl at //AMRSP::Shading, after the tree traversal, the brick
// reads and the smooth reconstruction, which the point lookups here use.

#if defined(AMRSP_SHADE) || defined(AMRSP_SHADOWS) || AMRSP_BLEND_MODE == 4
// The scalar at point p (level-0 index units) from the kD-tree leaf containing p: a descent from
// the root as kd-restart's, choosing the child by the point (lower when p[axis] < the split
// plane). False outside the root box, in a leaf without data, or where the sample is NaN.
// cellSize: the leaf's data-level cell size. With AMRSP_SMOOTH_CELLS the smooth reconstruction at
// the leaf's level (iso-surface bisection and shadow rays then see the field the samples see).
// Mirrors the core's KdTreePointLookup (smooth with AMRSP_SMOOTH_CELLS).
bool amrspSampleAtPoint(vec3 p, out float value, out vec3 cellSize)
{
  cellSize = vec3(1.0);
  uvec2 dataNode;
  int level;
  ivec3 loF, hiF, firstCell, lastCell;
  if (!amrspLocateSample(p, dataNode, level, loF, hiF, firstCell, lastCell, value))
  {
    return false;
  }
  cellSize = amrspCellSize(level);
#ifdef AMRSP_SMOOTH_CELLS
  value = amrspSampleSmooth(p, level, dataNode, loF, hiF, firstCell, lastCell, value);
#endif
  return !isnan(value);
}

// The kD node of the sample being shaded (set by the sample loop; amrspInNode = false for
// iso-surface hits): a point inside its box [amrspNodeLo, amrspNodeHi) reaches the same leaf by a
// descent (same float planes and tie rule), so its brick is read directly.
bool amrspInNode = false;
vec3 amrspNodeLo;
vec3 amrspNodeHi;
ivec3 amrspNodeLoF; // the same box in exact finest-level cells
ivec3 amrspNodeHiF;
uvec2 amrspNodeDataNode;
ivec3 amrspNodeFirstCell;
ivec3 amrspNodeLastCell;

// A gradient neighbour: the value at q of the leaf containing q, as the sample loop computes it
// there (nearest cell, or the smooth reconstruction at the leaf's level with AMRSP_SMOOTH_CELLS;
// as the core's KdTreePointLookup). False where absent or NaN.
bool amrspSampleNear(vec3 q, out float value)
{
  uvec2 dataNode;
  ivec3 loF, hiF, firstCell, lastCell;
  if (amrspInNode && all(greaterThanEqual(q, amrspNodeLo)) && all(lessThan(q, amrspNodeHi)))
  {
    dataNode = amrspNodeDataNode;
    loF = amrspNodeLoF;
    hiF = amrspNodeHiF;
    firstCell = amrspNodeFirstCell;
    lastCell = amrspNodeLastCell;
  }
  else
  {
    uint data = amrspLocateDataNode(q, loF, hiF);
    if (data == 0u)
    {
      value = 0.0;
      return false;
    }
    dataNode = amrspFetchDataNode(data);
    amrspLeafCells(int(amrspDataLevel(dataNode)), loF, hiF, firstCell, lastCell);
  }
  int level = int(amrspDataLevel(dataNode));
  value = amrspSampleDataNode(dataNode, q, amrspCellSize(level), firstCell, lastCell);
#ifdef AMRSP_SMOOTH_CELLS
  value = amrspSampleSmooth(q, level, dataNode, loF, hiF, firstCell, lastCell, value);
#endif
  return !isnan(value);
}

// Model-space gradient by central differences through the tree (one-sided where a neighbour is
// absent), as amrsp::Gradient: for nearest cells the stencil of p's cell, from its centre (a
// sample exactly on a cell face, which the sampling rule produces, takes one cell's stencil
// whatever the last bit of p; amrsp/Shading.h), for a continuous field p's own.
vec3 amrspGradient(vec3 p, float value, vec3 cellSize)
{
#if defined(AMRSP_CELL_CENTRED) && !defined(AMRSP_SMOOTH_CELLS)
  vec3 b = (floor(p / cellSize) + 0.5) * cellSize;
#else
  vec3 b = p;
#endif
  vec3 g = vec3(0.0);
  for (int a = 0; a < 3; ++a)
  {
    vec3 e = vec3(0.0);
    e[a] = cellSize[a];
    float plus, minus;
    float n = 2.0;
    if (!amrspSampleNear(b + e, plus))
    {
      plus = value;
      n -= 1.0;
    }
    if (!amrspSampleNear(b - e, minus))
    {
      minus = value;
      n -= 1.0;
    }
    g[a] = n > 0.0 ? (plus - minus) / (n * cellSize[a] * amrspSpacing0[a]) : 0.0;
  }
  return g;
}

#ifdef AMRSP_SHADOWS
// Transmittance from p (level-0 index units) toward the light, as amrsp::ShadowTransmittance.
float amrspShadowTransmittance(vec3 p)
{
  vec3 x = amrspOrigin + p * amrspSpacing0;
  vec3 toLight = amrspLightDirectionMC;
  float tLight = AMRSP_INF;
  if (amrspLightPositional != 0)
  {
    toLight = amrspLightPositionMC - x;
    tLight = length(toLight);
    if (!(tLight > 0.0))
    {
      return 1.0;
    }
    toLight /= tLight;
  }
  vec3 d = toLight / amrspSpacing0;
  float tExit = AMRSP_INF;
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] != 0.0)
    {
      tExit = min(tExit, ((d[a] > 0.0 ? amrspRootHi[a] : amrspRootLo[a]) - p[a]) / d[a]);
    }
  }
  float tEnd = min(tExit, tLight);
  float exponent = amrspShadowStep / amrspUnitDistance;
  float transmittance = 1.0;
  for (int k = 0; k < AMRSP_SHADOW_MAX_STEPS; ++k)
  {
    float t = (float(k) + 0.5) * amrspShadowStep;
    if (t >= tEnd)
    {
      break;
    }
    float v;
    vec3 ignored;
    if (!amrspSampleAtPoint(p + t * d, v, ignored))
    {
      continue;
    }
    float opacity = min(amrspTransferFunction(v).a, 1.0);
    transmittance *= pow(1.0 - opacity, exponent);
    if (transmittance < AMRSP_SHADOW_MIN_TRANSMITTANCE)
    {
      break;
    }
  }
  return transmittance;
}
#endif

// The lit colour of base colour c at p (level-0 index units) of the given value, as
// amrsp::ShadeSample; towardEye: unit model vector from the sample to the eye.
vec3 amrspShade(vec3 c, vec3 p, float value, vec3 cellSize, vec3 towardEye)
{
  float transmittance = 1.0;
#ifdef AMRSP_SHADOWS
  transmittance = amrspShadowTransmittance(p);
#endif
#ifdef AMRSP_SHADE
  vec3 x = amrspOrigin + p * amrspSpacing0;
  vec3 l = amrspLightPositional != 0 ? normalize(amrspLightPositionMC - x) : amrspLightDirectionMC;
  vec3 g = amrspGradient(p, value, cellSize);
  float len = length(g);
  float diffuse = 0.0;
  float specular = 0.0;
  if (len > 0.0)
  {
    vec3 n = g / len;
    if (dot(n, towardEye) < 0.0)
    {
      n = -n;
    }
    diffuse = max(0.0, dot(n, l));
    if (diffuse > 0.0)
    {
      specular = pow(max(0.0, dot(n, normalize(l + towardEye))), amrspSpecularPower);
    }
  }
  vec3 lit = amrspAmbient * c +
    transmittance * amrspLightColour * (amrspDiffuse * diffuse * c + amrspSpecular * specular);
  return clamp(lit, 0.0, 1.0);
#else
  return clamp(c * (amrspAmbient + amrspDiffuse * transmittance * amrspLightColour), 0.0, 1.0);
#endif
}
#endif

#if AMRSP_BLEND_MODE == 4
// Composites the iso-value crossings between consecutive samples a and b (values va, vb), refined
// by bisection through the tree, as amrsp::IsoSurfaceTracker::Sample.
void amrspIsoCrossings(vec3 a0, float va, vec3 b0, float vb, vec3 towardEye, inout vec3 colour,
  inout float alpha)
{
  bool rising = vb > va;
  for (int i = 0; i < amrspIsoCount; ++i)
  {
    float iso = amrspIsoValues[rising ? i : amrspIsoCount - 1 - i];
    bool belowA = va < iso;
    if (belowA == (vb < iso))
    {
      continue;
    }
    vec3 a = a0;
    vec3 b = b0;
    vec3 ignored;
    for (int k = 0; k < AMRSP_ISO_REFINE_STEPS; ++k)
    {
      vec3 m = 0.5 * (a + b);
      float vm;
      if (!amrspSampleAtPoint(m, vm, ignored))
      {
        break;
      }
      if ((vm < iso) == belowA)
      {
        a = m;
      }
      else
      {
        b = m;
      }
    }
    vec3 cellSize;
    float vh;
    if (!amrspSampleAtPoint(b, vh, cellSize))
    {
      vh = iso;
      cellSize = vec3(1.0);
    }
    vec4 tf = amrspTransferFunction(iso);
    vec3 rgb = tf.rgb;
#if defined(AMRSP_SHADE) || defined(AMRSP_SHADOWS)
    amrspInNode = false;
    rgb = amrspShade(rgb, b, vh, cellSize, towardEye);
#endif
    float opacity = clamp(tf.a, 0.0, 1.0);
    colour += (1.0 - alpha) * opacity * rgb;
    alpha += (1.0 - alpha) * opacity;
  }
}
#endif
