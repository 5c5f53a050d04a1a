// compose.frag: accumulated colour plus the background seen through it;
// the RGBA8 output is written once. Full-screen pass.
#include "common/oit_shared.h"
#include "common/frame.glsl"

layout(binding = OIT_TEXUNIT_ACCUM_FRONT) uniform sampler2D accumulation; // rgb = C, a = T

layout(location = 0) out vec4 out_colour;

void main()
{
    vec4 front = texelFetch(accumulation, ivec2(gl_FragCoord.xy), 0);
    out_colour = vec4(front.rgb + front.a * u_background, 1.0);
}
