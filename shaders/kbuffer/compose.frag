// kbuffer/compose.frag: the core front to back, then the tail as the store pass
// blended it, then the background (common/closest_layers.glsl). Full-screen
// pass; the RGBA8 output is written once.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/closest_layers.glsl"

layout(binding = OIT_TEXUNIT_CLOSEST_TAIL) uniform sampler2D tail_over; // premultiplied "over"

vec4 closest_layers_tail(ivec2 pixel)
{
    return texelFetch(tail_over, pixel, 0);
}

layout(location = 0) out vec4 out_colour;

void main()
{
    if (CLOSEST_LAYERS_HELPER_INVOCATION) {
        out_colour = vec4(0.0); // discarded anyway; must not count
        return;
    }
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    out_colour = vec4(closest_layers_compose(pixel, closest_layers_tail(pixel)), 1.0);
}
