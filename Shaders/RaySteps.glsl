// SPDX-License-Identifier: BSD-3-Clause
// The single-pass ray, step by step: its state (globals of the invocation) and the five steps
// amrspCastRay drives, either in nested loops (segments, descent, samples) or in one flat loop that
// takes one traversal or sample operation per iteration (AMRSP_FLAT_LOOP). Spliced into
// SinglePassAMRRay.glsl at //AMRSP::RaySteps, after the traversal, sampling and shading
// functions. Mirrors amrsp::TraverseKdTree and amrsp::RenderKdTree (same segments, samples and
// termination); see the top of SinglePassAMRRay.glsl for the defines.

// ---- The ray (level-0 index units; t is the model-space distance along it)
vec3 amrspRo;
vec3 amrspRd;
vec3 amrspDirMC; // unit direction, model coordinates
float amrspT;    // where the ray's next segment starts
float amrspTEnd; // where its integration ends (root box, clip box, opaque geometry)

// ---- What the ray has accumulated
vec3 amrspColour = vec3(0.0);
float amrspAlpha = 0.0;
// maximum/minimum/average intensity: the scalar kept, or the length-weighted sum and length
float amrspKept = 0.0;
bool amrspAnySample = false;
float amrspWeightedSum = 0.0;
float amrspSampledLength = 0.0;
#if AMRSP_BLEND_MODE == 4
bool amrspHavePrevious = false; // iso-surfaces: the previous present sample along the ray
vec3 amrspPreviousP = vec3(0.0);
float amrspPreviousValue = 0.0;
#endif
#ifdef AMRSP_ACCELERATION_COUNTS
int amrspWorkDataSegments = 0;    // data segments reached (skipped ones included)
int amrspWorkSampledSegments = 0; // of which sampled (the others were skipped as empty space)
#endif
#ifdef AMRSP_LOOP_COUNT
int amrspWorkCount = 0; // the loop iterations AMRSP_LOOP_COUNT selects
#endif
int amrspSegments = 0;     // segments begun (a guard against corrupt textures)
bool amrspStopped = false; // the ray reached the opacity threshold

// ---- Where descents start. kd-restart with push-down: the restart node is the deepest node
// reached so far without a choice between two children, i.e. whose box holds the rest of the ray
// [t, tEnd); each restart descends from it instead of the root, and visits the same leaves as
// from the root. Level-of-detail cut-offs in perspective depend on t, so there every restart is
// from the root.
bool amrspCanPushDown;
uint amrspRestartNode = 0u;
vec3 amrspRestartLo;
vec3 amrspRestartHi;
ivec3 amrspRestartLoF;
ivec3 amrspRestartHiF;
uvec2 amrspRestartTexel;
// Far child of the deepest split plane the last descent crossed, and where the ray leaves it
// (farEnd). The leaf that descent found ends on that plane, so the next leaf lies in this child
// and the next descent starts there: a one-entry short stack, used where push-down is.
bool amrspHaveFar = false;
uint amrspFarNode = 0u;
vec3 amrspFarLo = vec3(0.0);
vec3 amrspFarHi = vec3(0.0);
ivec3 amrspFarLoF = ivec3(0);
ivec3 amrspFarHiF = ivec3(0);
float amrspFarEnd = 0.0;
// The rope across the face the last leaf was left through, and its box (exactly the box a
// descent from the root computes: amrsp/KdTreeRopes.h).
bool amrspUseRopes = false;
bool amrspHaveRope = false;
uint amrspRopeNode = 0u;
ivec3 amrspRopeLoF = ivec3(0);
ivec3 amrspRopeHiF = ivec3(0);

// ---- The current descent and its leaf: the node, its box (level-0 index units and exact
// finest-level cells), where the ray leaves it, and its tree texel
uint amrspNode;
vec3 amrspLo;
vec3 amrspHi;
ivec3 amrspLoF;
ivec3 amrspHiF;
float amrspTLeave;
bool amrspPushDown;
uvec2 amrspTexel;

// ---- The current segment's sampling: n samples, one in each of n equal steps dt
uvec2 amrspSegDataNode;
uvec2 amrspSegBrickRef;
int amrspSegLevel;
ivec3 amrspSegFirstCell;
ivec3 amrspSegLastCell;
vec3 amrspSegCellSize;
bool amrspSegSampled = false; // the leaf has data that is not skipped
int amrspSegN = 0;
int amrspSegK = 0;
float amrspSegDt;
float amrspSegExponent;

// Sets up the ray through the pixel centre `pixel` (window coordinates); false when it misses the
// root box or the clip box.
bool amrspBeginRay(vec2 pixel)
{
  vec3 entry;
  float tMax;
  amrspPixelRay(pixel, entry, amrspDirMC, tMax);
  amrspRo = (entry - amrspOrigin) / amrspSpacing0;
  amrspRd = amrspDirMC / amrspSpacing0;
  float tEnter, tExit, clipEnter, clipExit;
  if (!amrspIntersectBox(amrspRootLo, amrspRootHi, amrspRo, amrspRd, tEnter, tExit) ||
    !amrspIntersectBox(amrspClipLo, amrspClipHi, amrspRo, amrspRd, clipEnter, clipExit))
  {
    return false;
  }
  // the traversal still starts from the root node: the clip box only bounds [t, tEnd)
  amrspT = max(max(tEnter, clipEnter), 0.0);
  amrspTEnd = min(min(tExit, clipExit), tMax);
  amrspCanPushDown = amrspLodThreshold <= 0.0 || amrspParallelPixelSize > 0.0;
#ifdef AMRSP_ROPES
  amrspUseRopes = amrspCanPushDown && amrspLodThreshold <= 0.0;
#endif
  amrspRestartLo = amrspRootLo;
  amrspRestartHi = amrspRootHi;
  amrspRestartLoF = ivec3(amrspRootLoFinest[0], amrspRootLoFinest[1], amrspRootLoFinest[2]);
  amrspRestartHiF = ivec3(amrspRootHiFinest[0], amrspRootHiFinest[1], amrspRootHiFinest[2]);
  amrspRestartTexel = amrspFetchNode(0u);
  return true;
}

// Whether the ray goes on: not at its end, not stopped at the opacity threshold, within the
// guard.
bool amrspRayGoesOn()
{
  return amrspT < amrspTEnd && !amrspStopped && amrspSegments < amrspMaxSegments;
}

// Step 1: where the next descent starts, the rope, the far child or the restart node.
void amrspBeginDescent()
{
  ++amrspSegments;
#if AMRSP_LOOP_COUNT == 1
  ++amrspWorkCount;
#endif
  bool fromRope = amrspHaveRope;
  amrspHaveRope = false;
  // An empty far interval (planes meeting where the leaf ends) is left to the restart.
  bool fromFar = !fromRope && amrspHaveFar && amrspFarEnd > amrspT;
  amrspHaveFar = false;
  amrspTexel = amrspRestartTexel;
  amrspNode = amrspRestartNode;
  amrspLo = amrspRestartLo;
  amrspHi = amrspRestartHi;
  amrspLoF = amrspRestartLoF;
  amrspHiF = amrspRestartHiF;
  amrspTLeave = amrspTEnd;
  if (fromFar)
  {
    amrspTexel = amrspFetchNode(amrspFarNode);
    amrspNode = amrspFarNode;
    amrspLo = amrspFarLo;
    amrspHi = amrspFarHi;
    amrspLoF = amrspFarLoF;
    amrspHiF = amrspFarHiF;
    amrspTLeave = amrspFarEnd;
    if (amrspFarEnd >= amrspTEnd)
    {
      // the far child holds the rest of the ray
      amrspRestartNode = amrspFarNode;
      amrspRestartLo = amrspFarLo;
      amrspRestartHi = amrspFarHi;
      amrspRestartLoF = amrspFarLoF;
      amrspRestartHiF = amrspFarHiF;
      amrspRestartTexel = amrspTexel;
    }
  }
#ifdef AMRSP_ROPES
  if (fromRope)
  {
    amrspTexel = amrspFetchNode(amrspRopeNode);
    amrspNode = amrspRopeNode;
    amrspLoF = amrspRopeLoF;
    amrspHiF = amrspRopeHiF;
    amrspLo = vec3(amrspRopeLoF) * amrspRopeCellSize;
    amrspHi = vec3(amrspRopeHiF) * amrspRopeCellSize;
    amrspTLeave = min(amrspExitDistance(amrspLo, amrspHi, amrspRo, amrspRd), amrspTEnd);
  }
#endif
  amrspPushDown = amrspCanPushDown && !fromRope && (!fromFar || amrspFarEnd >= amrspTEnd);
}

// Step 2: one level down toward the node containing the ray at t (kd-restart); false at a leaf
// (or where the level of detail stops the descent).
bool amrspDescentStep()
{
  uint child = amrspNodeFirstChild(amrspTexel);
  if (child == 0u)
  {
    return false;
  }
  uint lodData = amrspNodeData(amrspTexel);
  if (lodData != 0u && amrspLodThreshold > 0.0)
  {
    uint dataLevel = amrspDataLevel(amrspFetchDataNode(lodData));
    vec3 cell = amrspCellSize(int(dataLevel)) * amrspSpacing0;
    float cellWorld = max(cell.x, max(cell.y, cell.z));
    float pixel = amrspParallelPixelSize > 0.0 ? amrspParallelPixelSize
                                               : amrspT * amrspPixelSizePerDistance;
    if (cellWorld < amrspLodThreshold * pixel)
    {
      return false;
    }
  }
  int axis = int(amrspNodeAxis(amrspTexel));
  uint level = amrspNodeLevel(amrspTexel);
  uint split = amrspNodeSplit(amrspTexel);
  float plane = amrspLo[axis] + float(split) * amrspCellSizeOnAxis(int(level), axis);
  int planeF = amrspLoF[axis] + int(split) * amrspToFinestOnAxis(int(level), axis);
  float o = amrspRo[axis];
  float d = amrspRd[axis];
  bool originBelow = o < plane || (o == plane && d > 0.0);
  float tSplit = d != 0.0 ? (plane - o) / d : AMRSP_INF;
  bool lower;
  if (tSplit >= amrspTLeave || tSplit < 0.0)
  {
    lower = originBelow; // the whole rest of the interval is on the origin's side
  }
  else if (tSplit <= amrspT)
  {
    lower = !originBelow; // already past the plane
  }
  else
  {
    lower = originBelow;
    if (amrspCanPushDown)
    {
      amrspHaveFar = true;
      amrspFarNode = lower ? child + 1u : child;
      amrspFarLo = amrspLo;
      amrspFarHi = amrspHi;
      amrspFarLoF = amrspLoF;
      amrspFarHiF = amrspHiF;
      amrspChildBox(amrspFarLo, amrspFarHi, amrspFarLoF, amrspFarHiF, axis, plane, planeF, !lower);
      amrspFarEnd = amrspTLeave;
    }
    amrspTLeave = tSplit;
    amrspPushDown = false;
  }
  amrspChildBox(amrspLo, amrspHi, amrspLoF, amrspHiF, axis, plane, planeF, lower);
  amrspNode = lower ? child : child + 1u;
  amrspTexel = amrspFetchNode(amrspNode);
#if AMRSP_LOOP_COUNT == 2
  ++amrspWorkCount;
#endif
  if (amrspPushDown)
  {
    amrspRestartNode = amrspNode;
    amrspRestartLo = amrspLo;
    amrspRestartHi = amrspHi;
    amrspRestartLoF = amrspLoF;
    amrspRestartHiF = amrspHiF;
    amrspRestartTexel = amrspTexel;
  }
  return true;
}

// Step 3: the leaf's segment [t, tLeave): what its samples read, and how many there are (0 for
// empty space and skipped data).
void amrspBeginSegment()
{
  amrspSegN = 0;
  amrspSegK = 0;
  amrspSegSampled = false;
  uint data = amrspNodeData(amrspTexel);
#ifdef AMRSP_ACCELERATION_COUNTS
  amrspWorkDataSegments += data != 0u ? 1 : 0;
#endif
#ifdef AMRSP_SKIP_EMPTY
  if (data != 0u && amrspDataNodeTransparent(data))
  {
    data = 0u; // empty space under this transfer function: nothing to sample
  }
#endif
  if (data == 0u)
  {
#if AMRSP_BLEND_MODE == 4
    amrspHavePrevious = false; // empty space breaks the pairing of samples
#endif
    return;
  }
#ifdef AMRSP_ACCELERATION_COUNTS
  ++amrspWorkSampledSegments; // skipped = reached - sampled: counted where sampling starts
#endif
  amrspSegSampled = true;
  amrspSegDataNode = amrspFetchDataNode(data);
  amrspSegBrickRef = amrspBrickRef(amrspSegDataNode); // once per segment, not per sample
  amrspSegLevel = int(amrspDataLevel(amrspSegDataNode));
  amrspLeafCells(amrspSegLevel, amrspLoF, amrspHiF, amrspSegFirstCell, amrspSegLastCell);
  amrspSegCellSize = amrspCellSize(amrspSegLevel);
  // Sampling rule: n = max(1, ceil(length / D)) equal steps, sample k at (k + SampleOffset) dt.
  float segmentLength = amrspTLeave - amrspT;
  amrspSegN = max(1, int(ceil(segmentLength / amrspStep(amrspSegLevel))));
#if defined(AMRSP_ABLATION) && AMRSP_ABLATION == 1
  amrspSegN = 0; // traversal only: a constant per segment keeps the traversal's results live
  amrspColour += (1.0 - amrspAlpha) * 1.0e-3 * vec3(float(amrspSegLevel + 1), 1.0, 1.0);
  amrspAlpha += (1.0 - amrspAlpha) * 1.0e-3;
#elif defined(AMRSP_ABLATION) && AMRSP_ABLATION == 2
  segmentLength = amrspTEnd - amrspT; // sampling only: this brick for the rest of the ray
  amrspTLeave = amrspTEnd;
  amrspSegN = amrspAblationSamples;
#endif
  amrspSegDt = segmentLength / float(max(amrspSegN, 1));
  amrspSegExponent = amrspSegDt / amrspUnitDistance;
}

// Step 4: the segment's next sample, composited; false once a composite or iso-surface ray is
// opaque enough.
bool amrspSampleStep()
{
#if AMRSP_LOOP_COUNT == 3
  ++amrspWorkCount;
#endif
  // amrsp::SampleOffset: not the midpoint, so that no sample lies exactly on a cell face
  float ts = amrspT + (float(amrspSegK) + 0.4618034) * amrspSegDt;
  ++amrspSegK;
  vec3 p = amrspRo + ts * amrspRd;
  float scalar = amrspSampleBrick(amrspSegDataNode, amrspSegBrickRef, p, amrspSegCellSize,
    amrspSegFirstCell, amrspSegLastCell);
#ifdef AMRSP_SMOOTH_CELLS
  scalar = amrspSampleSmooth(p, amrspSegLevel, amrspSegDataNode, amrspLoF, amrspHiF,
    amrspSegFirstCell, amrspSegLastCell, scalar);
#endif
  if (isnan(scalar))
  {
#if AMRSP_BLEND_MODE == 4
    amrspHavePrevious = false;
#endif
    return true; // missing data is transparent
  }
#if AMRSP_BLEND_MODE == 1
  amrspKept = amrspAnySample ? max(amrspKept, scalar) : scalar;
  amrspAnySample = true;
#elif AMRSP_BLEND_MODE == 2
  amrspKept = amrspAnySample ? min(amrspKept, scalar) : scalar;
  amrspAnySample = true;
#elif AMRSP_BLEND_MODE == 3
  amrspWeightedSum += scalar * amrspSegDt;
  amrspSampledLength += amrspSegDt;
  amrspAnySample = true;
#elif AMRSP_BLEND_MODE == 4
  if (amrspHavePrevious)
  {
    amrspIsoCrossings(
      amrspPreviousP, amrspPreviousValue, p, scalar, -amrspDirMC, amrspColour, amrspAlpha);
  }
  amrspHavePrevious = true;
  amrspPreviousP = p;
  amrspPreviousValue = scalar;
  amrspStopped = amrspAlpha >= amrspOpacityThreshold;
#else
  vec4 tf = amrspTransferFunction(scalar);
  if (tf.a > 0.0)
  {
    float a = 1.0 - pow(1.0 - min(tf.a, 1.0), amrspSegExponent);
#if defined(AMRSP_SHADE) || defined(AMRSP_SHADOWS)
    amrspInNode = true;
    amrspNodeLo = amrspLo;
    amrspNodeHi = amrspHi;
    amrspNodeLoF = amrspLoF;
    amrspNodeHiF = amrspHiF;
    amrspNodeDataNode = amrspSegDataNode;
    amrspNodeFirstCell = amrspSegFirstCell;
    amrspNodeLastCell = amrspSegLastCell;
    tf.rgb = amrspShade(tf.rgb, p, scalar, amrspSegCellSize, -amrspDirMC);
#endif
    amrspColour += (1.0 - amrspAlpha) * a * tf.rgb;
    amrspAlpha += (1.0 - amrspAlpha) * a;
    amrspStopped = amrspAlpha >= amrspOpacityThreshold;
  }
#endif
  return !amrspStopped;
}

// Step 5: the segment is done: the ray moves to its end and, where it left the leaf through one
// face, takes that face's rope for the next descent.
void amrspEndSegment()
{
  amrspT = amrspTLeave;
  // a sampled segment ends the ray where it left it opaque enough (every blend mode)
  amrspStopped = amrspStopped || (amrspSegSampled && amrspAlpha >= amrspOpacityThreshold);
  if (amrspStopped)
  {
    return;
  }
#ifdef AMRSP_ROPES
  if (amrspUseRopes && amrspT < amrspTEnd)
  {
    int axis = amrspExitAxis(amrspLo, amrspHi, amrspRo, amrspRd, amrspTLeave);
    if (axis >= 0)
    {
      uint rope = amrspRopeOf(amrspFetchRope(amrspNode, amrspRopeTexelOfAxis(uint(axis))),
        uint(axis), amrspRd[axis] > 0.0);
      if (rope != 0u)
      {
        amrspHaveRope = true;
        amrspRopeNode = rope;
        uvec4 box = amrspFetchRope(rope, 0u);
        amrspRopeLoF = amrspRopeBoxLo(box);
        amrspRopeHiF = amrspRopeBoxHi(box, amrspFetchRope(rope, 1u));
      }
    }
  }
#endif
}

// The ray's segments in nested loops: per segment a descent loop, then a sample loop.
void amrspMarchNested()
{
  while (amrspRayGoesOn())
  {
    amrspBeginDescent();
    while (amrspDescentStep())
    {
    }
    amrspBeginSegment();
    bool goesOn = true;
    while (goesOn && amrspSegK < amrspSegN)
    {
      goesOn = amrspSampleStep();
    }
    if (!goesOn)
    {
      break; // stopped inside the segment: no rope to follow
    }
    amrspEndSegment();
  }
}

// The same steps in one loop, one traversal operation (a descent step, or a leaf's segment set-up)
// or one sample per iteration, so that lanes of a SIMT group at different steps of their rays
// still share iterations (amrsp/WorkCounters.h, flat-loop lockstep steps).
void amrspMarchFlat()
{
  if (!amrspRayGoesOn())
  {
    return;
  }
  amrspBeginDescent();
  bool sampling = false;
  for (;;)
  {
    if (!sampling)
    {
      if (amrspDescentStep())
      {
        continue;
      }
      amrspBeginSegment();
      sampling = amrspSegN > 0;
      if (sampling)
      {
        continue;
      }
    }
    else if (!amrspSampleStep())
    {
      break; // opaque enough
    }
    else if (amrspSegK < amrspSegN)
    {
      continue;
    }
    // the segment is done
    amrspEndSegment();
    if (!amrspRayGoesOn())
    {
      break;
    }
    amrspBeginDescent();
    sampling = false;
  }
}
