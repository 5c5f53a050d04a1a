// peel_order.glsl: what "behind the previous layer" means for depth peeling.
// Layers follow the order every exact algorithm and the reference sort by:
// (depth, triangle index), depth from oit_canonical_depth(). So a fragment at
// exactly the previous layer's depth (a coincident face) is not lost, as in
// plain depth peeling: it comes later if its triangle index is larger. The
// previous layer's triangle is kept in a depth texture, encoded by
// dp_encode_tie (OIT_DP_TIE_BIAS in oit_shared.h).
#include "common/oit_shared.h"

layout(location = OIT_UNIFORM_DP_HAS_PREVIOUS) uniform int has_previous;
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D previous_depth;
layout(binding = OIT_TEXUNIT_TIE_PREVIOUS) uniform sampler2D previous_tie;

float dp_encode_tie(uint triangle)
{
    return uintBitsToFloat(uint(OIT_DP_TIE_BIAS) + triangle);
}

uint dp_decode_tie(float encoded)
{
    return floatBitsToUint(encoded) - uint(OIT_DP_TIE_BIAS);
}

// Is (z, this triangle) after the previous layer's (depth, triangle)?
bool dp_behind_previous(float z)
{
    if (has_previous == 0)
        return true;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float previous = texelFetch(previous_depth, pixel, 0).r;
    return z > previous ||
           (z == previous && uint(gl_PrimitiveID) > dp_decode_tie(texelFetch(previous_tie, pixel, 0).r));
}
