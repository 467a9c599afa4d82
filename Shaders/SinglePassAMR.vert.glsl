//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// Proxy geometry of the single-pass AMR raycaster (Kaehler & Abel 2013, section 4.3): the faces of
// the root box in model coordinates. The mapper culls front faces, so every pixel the box covers
// runs the fragment shader exactly once, also when the camera is inside the box. The ray itself is
// rebuilt per fragment from gl_FragCoord, so nothing is passed on.

in vec4 vertexMC;

uniform mat4 amrspMCDCMatrix; // model -> normalized device coordinates (column-major)

void main()
{
  gl_Position = amrspMCDCMatrix * vertexMC;
}
