// compose.frag: mboit's resolve (full-screen pass; the RGBA8 output is written
// once). E5 in mboit/common.glsl: the transmittance-weighted average colour
// covers 1 - exp(-b0) of the pixel, the exact coverage (up to the opacity clamp
// of mboit/common.glsl), over the background, seen through exp(-b0).
#include "common/oit_shared.h"
#include "common/frame.glsl"

layout(binding = OIT_TEXUNIT_MBOIT_B0) uniform sampler2D mboit_b0;        // total optical depth
layout(binding = OIT_TEXUNIT_MBOIT_ACCUM) uniform sampler2D mboit_accum;  // (sum T a c, sum T a)

layout(location = 0) out vec4 out_colour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float total_transmittance = exp(-texelFetch(mboit_b0, pixel, 0).r);
    vec4 sum = texelFetch(mboit_accum, pixel, 0);
    vec3 average = sum.a > 0.0 ? sum.rgb / sum.a : vec3(0.0);
    out_colour = vec4(average * (1.0 - total_transmittance) + u_background * total_transmittance, 1.0);
}
