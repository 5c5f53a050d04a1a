// fill.frag: the Illustration Buffer's geometry pass (depth test and colour
// writes off). Like ll's fill, each fragment with alpha > 0 takes a node and
// pushes itself onto its pixel's list; it stores only what the rasterizer alone
// knows: window depth, triangle (gl_PrimitiveID) and the interpolated normal.
// Colour and opacity are recomputed from these later. Past the pool's end it
// stores nothing, but the counter still counts it, so the C side grows the
// pool and fills again: no fragment is dropped, nothing is written out of bounds.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "ib/ib_common.glsl"

layout(location = OIT_UNIFORM_IB_POOL_CAPACITY) uniform uint pool_capacity;

void main()
{
    if (IB_HELPER_INVOCATION)
        return;
    if (oit_fragment_alpha() <= 0.0)
        return; // hidden parts (opacity 0, local modulation included) are not stored
    uint node = atomicAdd(ib_counters[OIT_FRAME_COUNTER_FRAGMENTS], 1u);
    if (node == 0xFFFFFFFFu) // the counter wrapped to 0: its high word (the 64-bit count)
        atomicAdd(ib_counters[OIT_IB_COUNTER_FRAGMENTS_WRAPS], 1u);
    if (node >= pool_capacity) // (capacity < 0xFFFFFFFF: the wrapping fragment stores nothing)
        return;
    uint next = imageAtomicExchange(ib_heads, ivec2(gl_FragCoord.xy), node);
    ib_nodes[node] = uvec4(floatBitsToUint(oit_canonical_depth()), uint(gl_PrimitiveID),
                           oit_pack_normal(v_eye_normal), next);
}
