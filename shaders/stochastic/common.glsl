// common.glsl: stochastic transparency's coverage masks (Enderton, Sintorn,
// Shirley & Luebke 2010), the same in both geometry passes. A fragment of
// opacity a covers a subset of its pixel's S samples, from a hash of the seed,
// the pixel, the primitive and the fragment's depth (so both passes draw the
// same mask for the same fragment):
//   stratified (Laine & Karras 2011 style; the default): exactly round(a S)
//     distinct samples, the first of a seeded random permutation of the S;
//   independent: each sample with probability a.
// The samples are the pixel's centre S times over (no anti-aliasing): only
// their depth slots differ.
#include "common/oit_shared.h"
#include "common/frame.glsl"

layout(location = OIT_UNIFORM_STOCHASTIC_SAMPLES) uniform int u_samples;
layout(location = OIT_UNIFORM_STOCHASTIC_SEED) uniform uint u_seed;
layout(location = OIT_UNIFORM_STOCHASTIC_MASKS) uniform int u_masks;

// PCG-style integer hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020)
uint stochastic_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint stochastic_mask(float alpha)
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint h = stochastic_hash(u_seed ^ stochastic_hash(uint(pixel.x) + 65536u * uint(pixel.y)));
    h = stochastic_hash(h ^ uint(gl_PrimitiveID));
    h = stochastic_hash(h ^ floatBitsToUint(gl_FragCoord.z));
    uint mask = 0u;
    if (u_masks == OIT_STOCHASTIC_MASKS_INDEPENDENT) {
        for (int s = 0; s < u_samples; ++s) {
            h = stochastic_hash(h);
            if (float(h >> 8u) * (1.0 / 16777216.0) < alpha)
                mask |= 1u << uint(s);
        }
        return mask;
    }
    int covered = int(floor(alpha * float(u_samples) + 0.5));
    // the first `covered` of a Fisher-Yates permutation of 0..S-1
    int order[OIT_STOCHASTIC_SAMPLES_MAX];
    for (int s = 0; s < u_samples; ++s)
        order[s] = s;
    for (int s = 0; s < covered; ++s) {
        h = stochastic_hash(h);
        int pick = s + int(h % uint(u_samples - s));
        int chosen = order[pick];
        order[pick] = order[s];
        order[s] = chosen;
        mask |= 1u << uint(chosen);
    }
    return mask;
}
