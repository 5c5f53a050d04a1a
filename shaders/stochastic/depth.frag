// depth.frag: stochastic transparency's pass 1, the stochastic depth buffer.
// Every fragment writes its depth into the slots of the samples its mask
// covers, keeping the nearest (atomicMin; depth test off, no colour written).
#include "stochastic/common.glsl"
#include "common/shade.glsl"

layout(std430, binding = OIT_SSBO_STOCHASTIC_DEPTH) buffer stochastic_depths {
    uint depth_slots[];
};

void main()
{
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard;
    uint mask = stochastic_mask(colour.a);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint base = uint(pixel.y * u_viewport.x + pixel.x) * uint(u_samples);
    uint depth = floatBitsToUint(gl_FragCoord.z);
    for (int s = 0; s < u_samples; ++s)
        if ((mask & (1u << uint(s))) != 0u)
            atomicMin(depth_slots[base + uint(s)], depth);
}
