// accumulate.frag: stochastic transparency's pass 2 (depth test off). A
// fragment's visibility is the share of its pixel's S samples whose stored
// depth is at or behind it (its own covered samples count where it is the
// nearest), an estimate of the transmittance in front of it. Target 0
// (additive): (v a c, v a). Target 1 (multiplied by 1 - src): a, the exact
// total transmittance for the alpha-corrected resolve (wboit/compose.frag).
#include "stochastic/common.glsl"
#include "common/shade.glsl"

layout(std430, binding = OIT_SSBO_STOCHASTIC_DEPTH) readonly buffer stochastic_depths {
    uint depth_slots[];
};

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_revealage;

void main()
{
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint base = uint(pixel.y * u_viewport.x + pixel.x) * uint(u_samples);
    uint depth = floatBitsToUint(gl_FragCoord.z);
    int passed = 0;
    for (int s = 0; s < u_samples; ++s)
        if (depth <= depth_slots[base + uint(s)])
            ++passed;
    float visibility = float(passed) / float(u_samples);
    out_accumulation = vec4(colour.rgb * colour.a, colour.a) * visibility;
    out_revealage = vec4(colour.a);
}
