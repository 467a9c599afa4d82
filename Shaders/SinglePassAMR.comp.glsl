//AMRSP::Version
// SPDX-License-Identifier: BSD-3-Clause
//
// The compute-shader caster of the single pass: one invocation per pixel of the rays' image
// (the viewport, or an interactive frame's reduced image), in work groups of
// AMRSP_GROUP_WIDTH x AMRSP_GROUP_HEIGHT pixels, its ray cast by amrspCastRay
// (SinglePassAMRRay.glsl, where the other defines are listed) from the pixel's centre. The
// premultiplied result goes to amrspRayImage (RGBA32F; transparent black where the fragment
// caster would discard), which the mapper then composites "over" the framebuffer with one quad
// (Shaders/OffscreenComposite.frag.glsl), blended as the fragment caster blends: the two
// casters put the same bytes on the screen.
//
// A compute shader runs on every multiprocessor of a GPU, a fragment shader only where the chip
// rasterises (on NVIDIA's H100 and H200, 4 of 132 SMs: docs/design.md).
//AMRSP::Defines
//AMRSP::CastRay

layout(local_size_x = AMRSP_GROUP_WIDTH, local_size_y = AMRSP_GROUP_HEIGHT) in;

// The rays' image: pixel (0, 0) is the ray through window position amrspViewport.xy + 0.5.
layout(rgba32f) uniform writeonly image2D amrspRayImage;

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, ivec2(amrspViewport.zw))))
  {
    return; // the last work groups reach beyond the image
  }
  vec4 result;
  if (!amrspCastRay(amrspViewport.xy + vec2(pixel) + 0.5, result))
  {
    result = vec4(0.0);
  }
  imageStore(amrspRayImage, pixel, result);
}
