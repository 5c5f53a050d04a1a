// resolve.frag: adaptive transparency's resolve (Salvi, Montgomery and Lefohn,
// "Adaptive Transparency", HPG 2011), over ll's lists after ll's sort put each
// in primitive order (LL_ORDER_PRIMITIVE: triangle index, the order the draw
// call submits the fragments in). Full-screen pass. Two walks per pixel:
//  1. build the adaptive visibility function: at most k = LL_RESOLVE_LAYERS
//     nodes (key, transmittance), ascending by key = (depth, triangle); the
//     function is a step: 1 in front of the first node, node j's transmittance
//     from node j up to node j + 1. A fragment (alpha a) is inserted where its
//     key falls, with the transmittance in front of it times (1 - a), and every
//     node behind it is multiplied by (1 - a). When k + 1 nodes exist, the node
//     j >= 1 whose removal changes the area under the function least goes:
//     the area is (z_j - z_{j-1}) * (t_{j-1} - t_j) in linear eye depth, and
//     node j - 1 takes node j's transmittance (the step moves forward to
//     z_{j-1}: the paper's removal, which never brightens a pixel).
//  2. composite: C = sum of a_i c_i vis(key_i) over the fragments, vis the
//     function's value strictly in front of the fragment's key, plus the
//     background times the last node's transmittance (exact: every node
//     behind a fragment is multiplied, and removal keeps the last value).
// With no list longer than k nothing is removed: vis is the exact product of
// (1 - a) over the fragments in front, and the image is the reference's.
// Empty pixels are discarded (LL_EMPTY_PIXEL_DISCARD): the C side cleared the
// output to the background.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/frame.glsl"
#include "common/local_modulation.glsl"
#include "ll/ll_nodes.glsl"

#ifndef LL_RESOLVE_LAYERS
#error "alg_adaptive.c defines LL_RESOLVE_LAYERS (k)"
#endif
#define ADAPTIVE_K LL_RESOLVE_LAYERS

layout(location = 0) out vec4 out_colour;

// the visibility function: k nodes and room for the one a fragment adds
float node_depth[ADAPTIVE_K + 1];    // window depth (the key's first half)
uint node_triangle[ADAPTIVE_K + 1];  // the key's second half
float node_eye[ADAPTIVE_K + 1];      // linear eye depth: the area's width
float node_t[ADAPTIVE_K + 1];        // transmittance behind the node
int node_count = 0;

// the function's value strictly in front of (depth, triangle)
float adaptive_visibility(float depth, uint triangle)
{
    float t = 1.0;
    for (int j = 0; j < node_count; ++j) {
        if (!ll_in_front(node_depth[j], node_triangle[j], depth, triangle))
            break;
        t = node_t[j];
    }
    return t;
}

void adaptive_insert(float depth, uint triangle, float eye, float alpha)
{
    // the place: after every node in front of the fragment
    int place = 0;
    while (place < node_count && ll_in_front(node_depth[place], node_triangle[place], depth, triangle))
        ++place;
    float in_front = place > 0 ? node_t[place - 1] : 1.0;
    for (int j = node_count; j > place; --j) {
        node_depth[j] = node_depth[j - 1];
        node_triangle[j] = node_triangle[j - 1];
        node_eye[j] = node_eye[j - 1];
        node_t[j] = node_t[j - 1] * (1.0 - alpha);
    }
    node_depth[place] = depth;
    node_triangle[place] = triangle;
    node_eye[place] = eye;
    node_t[place] = in_front * (1.0 - alpha);
    ++node_count;
    if (node_count <= ADAPTIVE_K)
        return;
    // k + 1 nodes: remove the one (not the first) whose removal changes the area least
    int smallest = 1;
    float smallest_area = (node_eye[1] - node_eye[0]) * (node_t[0] - node_t[1]);
    for (int j = 2; j < node_count; ++j) {
        float area = (node_eye[j] - node_eye[j - 1]) * (node_t[j - 1] - node_t[j]);
        if (area < smallest_area) {
            smallest = j;
            smallest_area = area;
        }
    }
    node_t[smallest - 1] = node_t[smallest];
    for (int j = smallest; j + 1 < node_count; ++j) {
        node_depth[j] = node_depth[j + 1];
        node_triangle[j] = node_triangle[j + 1];
        node_eye[j] = node_eye[j + 1];
        node_t[j] = node_t[j + 1];
    }
    --node_count;
}

void main()
{
    if (LL_HELPER_INVOCATION) {
        out_colour = vec4(0.0); // discarded anyway
        return;
    }
    uint head = imageLoad(ll_heads, ivec2(gl_FragCoord.xy)).x;
    if (head == OIT_LIST_END)
        discard; // LL_EMPTY_PIXEL_DISCARD (ll_nodes.glsl): the output holds the background
    uint length = 0u;
    for (uint node = head; node != OIT_LIST_END; node = ll_sorted_next_fetch(node), ++length) {
        uvec4 n = ll_node_fetch(node);
        float depth = uintBitsToFloat(n.z);
        adaptive_insert(depth, n.w, oit_eye_depth(gl_FragCoord.xy, depth), ll_node_colour(n).a);
    }
    vec3 colour = vec3(0.0);
    for (uint node = head; node != OIT_LIST_END; node = ll_sorted_next_fetch(node)) {
        uvec4 n = ll_node_fetch(node);
        vec4 fragment = ll_node_colour(n);
        colour += adaptive_visibility(uintBitsToFloat(n.z), n.w) * fragment.a * fragment.rgb;
    }
    // psi: the C side has it from the sort's histogram unless the longest list is in its open last bin
    uint longest = ll_counters[OIT_FRAME_COUNTER_MAX_LIST];
    if (longest >= uint(OIT_LL_HISTOGRAM_BINS - 1) && 3u * length > 2u * longest)
        atomicAdd(ll_counters[OIT_LL_COUNTER_PSI_PIXELS], 1u);
    out_colour = vec4(colour + node_t[node_count - 1] * u_background, 1.0);
}
