// hybrid/compose.frag: the core front to back, then the tail as its average
// colour covering 1 - prod(1 - a) of what the core lets through, then the
// background (common/closest_layers.glsl). Full-screen pass; the RGBA8 output
// is written once.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/closest_layers.glsl"

layout(binding = OIT_TEXUNIT_CLOSEST_TAIL) uniform sampler2D tail_sum;             // (sum c a, sum a)
layout(binding = OIT_TEXUNIT_CLOSEST_TAIL_PRODUCT) uniform sampler2D tail_product; // prod (1 - a)

vec4 closest_layers_tail(ivec2 pixel)
{
    vec4 sum = texelFetch(tail_sum, pixel, 0);
    float coverage = 1.0 - texelFetch(tail_product, pixel, 0).r;
    return vec4(sum.rgb / max(sum.a, 1e-5) * coverage, coverage);
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
