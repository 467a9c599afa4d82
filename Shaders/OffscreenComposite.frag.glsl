//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// Composites an offscreen image of premultiplied colour and opacity over the renderer's
// framebuffer with one full-screen quad (vtkOpenGLQuadHelper) that the mapper blends with
// (ONE, ONE_MINUS_SRC_ALPHA), as the single-pass mapper blends its own output. The image is
// either the multi-pass mapper's accumulation (viewport-sized, nearest filtering) or the
// single-pass mapper's reduced image of an interactive frame (smaller, bilinear filtering).

uniform sampler2D amrspImage;

// vtkOpenGLQuadHelper's vertex shader maps the quad onto the viewport with texture coordinates
// [0, 1]^2: at the viewport's size texCoord hits the centre of this pixel's texel.
in vec2 texCoord;

//VTK::Output::Dec

void main()
{
  vec4 image = texture(amrspImage, texCoord);
  if (image.a <= 0.0)
  {
    discard;
  }
  gl_FragData[0] = image;
}
