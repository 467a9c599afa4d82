//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// Last step of the multi-pass AMR raycaster: the premultiplied colour and opacity accumulated
// front to back over all node draws (an RGBA32F texture the size of the viewport) is composited
// over the renderer's framebuffer by one full-screen quad (vtkOpenGLQuadHelper) that the mapper
// blends with (ONE, ONE_MINUS_SRC_ALPHA), as the single-pass mapper blends its own output.

uniform sampler2D amrspAccumulated; // viewport-sized, nearest filtering

// vtkOpenGLQuadHelper's vertex shader maps the quad onto the viewport with texture coordinates
// [0, 1]^2, so texCoord hits the centre of the texel of this pixel.
in vec2 texCoord;

//VTK::Output::Dec

void main()
{
  vec4 accumulated = texture(amrspAccumulated, texCoord);
  if (accumulated.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = accumulated;
}
