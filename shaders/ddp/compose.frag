// compose.frag: front layers, then back layers, then the background:
// C = C_front + T_front * (C_back + T_back * background). Full-screen pass.
#include "common/oit_shared.h"
#include "common/frame.glsl"

layout(binding = OIT_TEXUNIT_ACCUM_FRONT) uniform sampler2D front_accumulation; // rgb = C, a = T
layout(binding = OIT_TEXUNIT_ACCUM_BACK) uniform sampler2D back_accumulation;   // rgb = C, a = T

layout(location = 0) out vec4 out_colour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 front = texelFetch(front_accumulation, pixel, 0);
    vec4 back = texelFetch(back_accumulation, pixel, 0);
    out_colour = vec4(front.rgb + front.a * (back.rgb + back.a * u_background), 1.0);
}
