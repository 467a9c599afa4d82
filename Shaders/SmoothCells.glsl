// SPDX-License-Identifier: BSD-3-Clause
// Smooth reconstruction of cell-centred data (AMRSP_SMOOTH_CELLS): trilinear interpolation in
// the dual cell of the sample's level, its corners found by point location in the kD-tree.
// Spliced into SinglePassAMRRay.glsl at //AMRSP::SmoothCells, after the tree traversal
// functions it uses (amrspLocateDataNode, amrspLeafCells) and the brick reads. Mirrors the
// core's SmoothCornerKdTree and smooth KdTreePointLookup.

#ifdef AMRSP_SMOOTH_CELLS
// Cell `cell` of the data node's grid (any of its cells, covered or not; cells of its level),
// addressed from the node's lower-corner cell firstCell: texel offset + (cell - firstCell).
float amrspFetchGridCell(uvec2 dataNode, ivec3 cell, ivec3 firstCell)
{
  ivec3 texel = amrspDataOffset(dataNode) + (cell - firstCell);
  return amrspReadStorage(dataNode, amrspBrickRef(dataNode), texel, vec3(0.0));
}

// Whether `cell` (cells of the grid's level) is a cell of the data node's grid.
bool amrspGridHasCell(uvec2 dataNode, ivec3 cell)
{
  uint b = 3u * amrspDataBrick(dataNode);
  bool has = true;
  for (int a = 0; a < 3; ++a)
  {
    uvec2 box = texelFetch(amrspBrickBoxes, amrspTexelOf(b + uint(a)), 0).rg;
    has = has && cell[a] >= int(box.x) && cell[a] < int(box.y);
  }
  return has;
}
#endif

#ifdef AMRSP_SMOOTH_CELLS
// A corner of the smooth reconstruction's dual cell that is no cell of the sample's grid: x, a
// cell centre of `level`. The leaf containing x, of level m: for m >= level its nearest cell at
// x; for a coarser leaf the trilinear value of level m at x, its corners the cells of the leaf's
// grid (covered or not) or, where that grid has no such cell, the nearest cell of the leaf
// there; `fallback` outside every leaf. As the core's SmoothCornerKdTree.
float amrspSmoothCorner(vec3 x, int level, float fallback)
{
  uvec2 node;
  int m;
  ivec3 loF, hiF, first, last;
  float vx;
  if (!amrspLocateSample(x, node, m, loF, hiF, first, last, vx))
  {
    return fallback;
  }
  if (m >= level)
  {
    return vx;
  }
  vec3 cellSize = amrspCellSize(m);
  vec3 q = x / cellSize - 0.5;
  vec3 base = floor(q);
  vec3 w = q - base;
  float sum = 0.0;
  for (int corner = 0; corner < 8; ++corner)
  {
    vec3 o = vec3(float(corner & 1), float((corner >> 1) & 1), float((corner >> 2) & 1));
    ivec3 cell = ivec3(base + o);
    float v = vx;
    if (amrspGridHasCell(node, cell))
    {
      v = amrspFetchGridCell(node, cell, first);
    }
    else
    {
      uvec2 yNode;
      int l;
      ivec3 yLoF, yHiF, yFirst, yLast;
      float vy;
      if (amrspLocateSample((base + o + 0.5) * cellSize, yNode, l, yLoF, yHiF, yFirst, yLast, vy))
      {
        v = vy;
      }
    }
    vec3 f = mix(vec3(1.0) - w, w, o);
    sum += f.x * f.y * f.z * v;
  }
  return sum;
}

// Smooth value at p for a sample of data level `level` in the node (dataNode, box loF..hiF in
// finest cells, cells firstCell..lastCell): trilinear in the level's dual cell around p; a corner
// that is a cell of the node's grid (covered by finer grids or not) takes that cell's value, any
// other corner amrspSmoothCorner's; `nearest` (the nearest-cell value at p) for corners outside
// every grid. Linear-exact across level boundaries when every cell, covered ones included,
// holds the field at its centre. As the core's SmoothKdTree.
float amrspSampleSmooth(vec3 p, int level, uvec2 dataNode, ivec3 loF, ivec3 hiF, ivec3 firstCell,
  ivec3 lastCell, float nearest)
{
  vec3 cellSize = amrspCellSize(level);
  vec3 q = p / cellSize - 0.5;
  vec3 base = floor(q);
  vec3 w = q - base;
  ivec3 toData = amrspToFinest(level);
  ivec3 b = ivec3(base);
  // the dual cell's corner cells all in the node (so in its grid): no box test needed
  bool inside = all(greaterThanEqual(b * toData, loF)) && all(lessThanEqual((b + 2) * toData, hiF));
  float sum = 0.0;
  float lowest = 3.4e38, highest = -3.4e38;
  for (int corner = 0; corner < 8; ++corner)
  {
    vec3 o = vec3(float(corner & 1), float((corner >> 1) & 1), float((corner >> 2) & 1));
    ivec3 cell = b + ivec3(o);
    float v;
    if (inside || amrspGridHasCell(dataNode, cell))
    {
      v = amrspFetchGridCell(dataNode, cell, firstCell);
    }
    else
    {
      v = amrspSmoothCorner((base + o + 0.5) * cellSize, level, nearest);
    }
    vec3 f = mix(vec3(1.0) - w, w, o);
    sum += f.x * f.y * f.z * v;
    lowest = min(lowest, v);
    highest = max(highest, v);
  }
  // A convex combination lies within its values. llvmpipe of Mesa 26.1 (LLVM 21) returned sums
  // far above the largest corner on a few samples (two bright pixels, 177 levels off, in the
  // Enzo smooth-cell and cropping baselines; not on LLVM 15 or 19): the clamp changes nothing
  // where the arithmetic is right.
  return clamp(sum, lowest, highest);
}
#endif
