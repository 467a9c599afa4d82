//VTK::System::Dec
// SPDX-License-Identifier: BSD-3-Clause
//
// The fragment-shader caster of the single pass: one fragment per pixel that the proxy box's
// back faces cover (SinglePassAMR.vert.glsl), its ray cast by amrspCastRay
// (SinglePassAMRRay.glsl, where the defines are listed) from gl_FragCoord. The mapper blends the
// premultiplied result "over" the framebuffer (ONE, ONE_MINUS_SRC_ALPHA).
//AMRSP::Defines
#define AMRSP_FRAGMENT_STAGE 1 // amrspCastRay discards a ray that misses the volume
//AMRSP::CastRay

//VTK::Output::Dec

void main()
{
  vec4 result;
  if (!amrspCastRay(gl_FragCoord.xy, result))
  {
    discard;
  }
  gl_FragData[0] = result;
}
