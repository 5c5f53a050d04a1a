// compose.frag: walk each pixel's sorted list and composite front to back in
// float; the RGBA8 output is written once. Full-screen pass. Also counts the
// pixels whose list is longer than 2/3 of the longest (psi) when the sort's
// histogram cannot tell (ll_finish_sort in ll_nodes.glsl), and shows the
// buffer views: list-length heat map, peel limit (first N fragments), layer
// (fragment number L only). With the distance modulation (u_distance_mode >= 0)
// a fragment's opacity is saturate(distance along the ray / norm) times its
// local factor (stored in alpha by the fill): to fragment i+1 (adjacent), i+k
// (skip, or the last) or the last (far end); the last fragment's is 0. With an
// automatic region a first run of this pass (distance_pass 1) only finds the
// frame's largest distance. Empty pixels are discarded: the C side clears the
// output to the background first. The views and the distance modulation are
// compiled in only in the variant that uses them (common/variants.glsl).
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/frame.glsl"
#include "common/local_modulation.glsl"
#include "ll/ll_nodes.glsl"

layout(location = OIT_UNIFORM_LL_VIEW) uniform int view;
layout(location = OIT_UNIFORM_LL_VIEW_PARAMETER) uniform int view_parameter;
layout(location = OIT_UNIFORM_LL_DISTANCE_PASS) uniform int distance_pass;

// The distance along the ray from `node` (fragment i) to fragment i+k (adjacent:
// k = 1; skip: k; far end: the last one), or 0 if it is the last.
float ll_distance(uint node)
{
    float depth = uintBitsToFloat(ll_node_fetch(node).z);
    uint steps = u_distance_mode == OIT_IB_DISTANCE_ADJACENT ? 1u
               : u_distance_mode == OIT_IB_DISTANCE_SKIP ? uint(max(u_distance_skip, 1))
               : OIT_LIST_END;
    uint target = node;
    for (uint k = 0u; k < steps && ll_sorted_next_fetch(target) != OIT_LIST_END; ++k)
        target = ll_sorted_next_fetch(target);
    if (target == node)
        return 0.0;
    return abs(oit_eye_depth(gl_FragCoord.xy, uintBitsToFloat(ll_node_fetch(target).z)) -
               oit_eye_depth(gl_FragCoord.xy, depth));
}

layout(location = 0) out vec4 out_colour;

// blue -> green -> yellow -> red; oit_heatmap_colour (image_error.c) is the same
// scale for the legends: change both together
vec3 heat(float t)
{
    t = clamp(t, 0.0, 1.0) * 3.0;
    if (t < 1.0)
        return mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), t);
    if (t < 2.0)
        return mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0), t - 1.0);
    return mix(vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), t - 2.0);
}

void main()
{
    if (LL_HELPER_INVOCATION) {
        out_colour = vec4(0.0); // discarded anyway; skipping the walk also saves time
        return;
    }
    uint head = imageLoad(ll_heads, ivec2(gl_FragCoord.xy)).x;
    if (head == OIT_LIST_END)
        discard; // LL_EMPTY_PIXEL_DISCARD (ll_nodes.glsl): the output holds the background
#if OIT_VARIANT_DISTANCE
    if (distance_pass == 1) { // the frame's largest distance only
        float largest = 0.0;
        for (uint node = head; node != OIT_LIST_END; node = ll_sorted_next_fetch(node))
            largest = max(largest, ll_distance(node));
        if (largest > 0.0)
            atomicMax(ll_counters[OIT_LL_COUNTER_MAX_DISTANCE], floatBitsToUint(largest));
        out_colour = vec4(0.0);
        return;
    }
    float norm = u_distance_norm;
    if (distance_pass == 2) {
        float largest = uintBitsToFloat(ll_counters[OIT_LL_COUNTER_MAX_DISTANCE]);
        norm = largest > 0.0 ? largest : 1.0;
    }
#endif
#if OIT_VARIANT_VIEWS
    uint first = view == OIT_LL_VIEW_LAYER ? uint(max(view_parameter, 0)) : 0u;
    uint end = view == OIT_LL_VIEW_PEEL_LIMIT ? uint(max(view_parameter, 0))
             : view == OIT_LL_VIEW_LAYER ? first + 1u : OIT_LIST_END;
#endif
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    uint length = 0u;
    for (uint node = head; node != OIT_LIST_END; node = ll_sorted_next_fetch(node), ++length) {
#if OIT_VARIANT_VIEWS
        if (length < first || length >= end)
            continue; // still walked: psi needs the length
#endif
        vec4 fragment = ll_node_colour(ll_node_fetch(node));
#if OIT_VARIANT_DISTANCE
        if (u_distance_mode >= 0)
            fragment.a = clamp(ll_distance(node) / norm, 0.0, 1.0) * fragment.a;
#endif
        colour += transmittance * fragment.a * fragment.rgb;
        transmittance *= 1.0 - fragment.a;
    }
    uint longest = ll_counters[OIT_FRAME_COUNTER_MAX_LIST];
    // psi: the C side has it from the histogram unless the longest list is in its open last bin
    if (longest >= uint(OIT_LL_HISTOGRAM_BINS - 1) && 3u * length > 2u * longest)
        atomicAdd(ll_counters[OIT_LL_COUNTER_PSI_PIXELS], 1u);
#if OIT_VARIANT_VIEWS
    if (view == OIT_LL_VIEW_HEATMAP) {
        out_colour = vec4(heat(float(length) / float(max(longest, 1u))), 1.0);
        return;
    }
#endif
    out_colour = vec4(colour + transmittance * u_background, 1.0);
}
