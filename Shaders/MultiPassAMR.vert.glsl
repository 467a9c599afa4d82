//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// Proxy geometry of the multi-pass AMR raycaster (the baseline of Kaehler & Abel 2013, section 6):
// the box of ONE kD-tree data node per draw. The vertex buffer holds the 36 corners of the unit
// cube (two triangles per face, counter-clockwise seen from outside); the node's box, given in
// level-0 index units by the same uniforms the fragment shader clips the ray with, places them.
// The mapper culls front faces, so every pixel the box covers runs the fragment shader once, also
// when the eye is inside the box. The ray is rebuilt per fragment from gl_FragCoord.

in vec3 amrspCorner; // 0 or 1 per axis: lower or upper side of the box

uniform mat4 amrspMCDCMatrix; // model -> normalized device coordinates (column-major)
uniform vec3 amrspOrigin;     // model position of level-0 index (0, 0, 0)
uniform vec3 amrspSpacing0;   // model size of a level-0 cell
uniform vec3 amrspNodeLo;     // the node's box, level-0 index units
uniform vec3 amrspNodeHi;

void main()
{
  vec3 index = mix(amrspNodeLo, amrspNodeHi, amrspCorner);
  gl_Position = amrspMCDCMatrix * vec4(amrspOrigin + index * amrspSpacing0, 1.0);
}
