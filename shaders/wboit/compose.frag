// compose.frag: weighted average colour, covering 1 - revealage of the pixel,
// over the background. Full-screen pass; the RGBA8 output is written once.
#include "common/oit_shared.h"
#include "common/frame.glsl"

layout(binding = OIT_TEXUNIT_ACCUM) uniform sampler2D accumulation; // (sum w a c, sum w a)
layout(binding = OIT_TEXUNIT_REVEALAGE) uniform sampler2D revealage;  // product of (1 - a)

layout(location = 0) out vec4 out_colour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 sum = texelFetch(accumulation, pixel, 0);
    float revealed = texelFetch(revealage, pixel, 0).r;
    vec3 average = sum.rgb / max(sum.a, 1e-5);
    out_colour = vec4(average * (1.0 - revealed) + u_background * revealed, 1.0);
}
