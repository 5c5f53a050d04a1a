// fill.frag: the linked lists' geometry pass (depth test and colour writes off).
// Every fragment with alpha > 0 takes a node from the pool and pushes itself
// onto its pixel's list. A fragment past the pool's end stores nothing, but the
// counter still counts it, so the C side sees the pool overflow, grows it and
// fills again: no fragment is dropped and nothing is written out of bounds.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "ll/ll_nodes.glsl"

layout(location = OIT_UNIFORM_LL_POOL_CAPACITY) uniform uint pool_capacity;

void main()
{
    if (LL_HELPER_INVOCATION)
        return;
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        return; // hidden parts (opacity 0) are not stored
#if OIT_VARIANT_DISTANCE
    if (u_distance_mode >= 0) // distance modulation: compose sets alpha; keep the local factor
        colour.a = oit_local_alpha(1.0, v_component, v_section_cap, v_eye_position);
#endif
    uint node = atomicAdd(ll_counters[OIT_FRAME_COUNTER_FRAGMENTS], 1u);
    if (node == 0xFFFFFFFFu) // the counter wrapped to 0: its high word, so the C side sees
        atomicAdd(ll_counters[OIT_LL_COUNTER_FRAGMENTS_WRAPS], 1u); // the 64-bit count
    if (node >= pool_capacity) // (capacity < 0xFFFFFFFF: the wrapping fragment stores nothing)
        return;
    ll_nodes[node] = ll_pack_node(colour, oit_canonical_depth(), uint(gl_PrimitiveID));
    ll_next[node] = imageAtomicExchange(ll_heads, ivec2(gl_FragCoord.xy), node);
}
