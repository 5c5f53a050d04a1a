// ll_nodes.glsl: the per-pixel linked lists' buffers and node layout, shared by
// the ll shaders (and by what builds on them). Layout and bindings: oit_shared.h.
#ifndef LL_NODES_GLSL
#define LL_NODES_GLSL

#include "common/oit_shared.h"

// Helper invocations (the extra lanes of 2x2 quads along triangle edges, even
// the edges where llvmpipe splits the clipped full-screen triangle) must not
// write memory, but Mesa llvmpipe 22.3 lets their buffer and image stores
// through, which corrupts the lists. Every ll pass returns early in them; the
// shader enables GL_ARB_ES3_1_compatibility (gl_HelperInvocation under #version
// 430) in its first line, since #extension must precede all declarations.
#ifdef GL_ARB_ES3_1_compatibility
#define LL_HELPER_INVOCATION gl_HelperInvocation
#else
#define LL_HELPER_INVOCATION false
#endif

// LL_EMPTY_PIXEL_DISCARD: the full-screen passes discard a pixel whose list is
// empty, before any other work, rather than return. llvmpipe runs a shader on
// 8 pixels at once and every statement for all of them under a mask: a
// `return` skips nothing, a discard of all 8 lets it skip some of what follows
// (the sort of an empty 600x600 frame: 7.3-7.9 ms with return, 5.2-5.8 with
// discard; docs/algorithms.md, "Where ll's time goes"). A GPU skips them.

// Node i: x = packUnorm2x16(r, g), y = packUnorm2x16(b, a), z = depth bits, w = triangle.
layout(std430, binding = OIT_SSBO_FRAGMENT_NODES) buffer ll_node_buffer {
    uvec4 ll_nodes[];
};
// Next pointers as the fill built the lists (newest first).
layout(std430, binding = OIT_SSBO_FRAGMENT_NEXT) buffer ll_next_buffer {
    uint ll_next[];
};
// Next pointers after the sort: front to back.
layout(std430, binding = OIT_SSBO_FRAGMENT_SORTED_NEXT) buffer ll_sorted_next_buffer {
    uint ll_sorted_next[];
};
// The same three buffers read through buffer textures, for passes that only read
// them (after a GL_TEXTURE_FETCH_BARRIER_BIT): see OIT_TEXUNIT_LL_* in oit_shared.h.
layout(binding = OIT_TEXUNIT_LL_NODES) uniform usamplerBuffer ll_nodes_texture;
layout(binding = OIT_TEXUNIT_LL_NEXT) uniform usamplerBuffer ll_next_texture;
layout(binding = OIT_TEXUNIT_LL_SORTED_NEXT) uniform usamplerBuffer ll_sorted_next_texture;
uvec4 ll_node_fetch(uint node) { return texelFetch(ll_nodes_texture, int(node)); }
uint ll_next_fetch(uint node) { return texelFetch(ll_next_texture, int(node)).x; }
uint ll_sorted_next_fetch(uint node) { return texelFetch(ll_sorted_next_texture, int(node)).x; }
layout(std430, binding = OIT_SSBO_FRAME_COUNTERS) buffer ll_counter_buffer {
    uint ll_counters[OIT_LL_COUNTER_COUNT];
};
// First node of each pixel's list: as filled, and after the sort the front-most.
layout(binding = OIT_IMAGE_LIST_HEAD, r32ui) uniform uimage2D ll_heads;

uvec4 ll_pack_node(vec4 colour, float depth, uint triangle)
{
    return uvec4(packUnorm2x16(colour.rg), packUnorm2x16(colour.ba), floatBitsToUint(depth),
                 triangle);
}

vec4 ll_node_colour(uvec4 node)
{
    return vec4(unpackUnorm2x16(node.x), unpackUnorm2x16(node.y));
}

// The depth order every algorithm uses: window depth, then triangle index, so
// fragments at equal depth always come in the same order. With
// LL_ORDER_PRIMITIVE (adaptive's sort, linked_lists.h) the sorts order by
// triangle index, then depth instead: the order the draw call submits the
// fragments in, whatever order the fill's atomics ran in.
bool ll_in_front(float depth_a, uint triangle_a, float depth_b, uint triangle_b)
{
#if defined(LL_ORDER_PRIMITIVE) && LL_ORDER_PRIMITIVE
    return triangle_a < triangle_b || (triangle_a == triangle_b && depth_a < depth_b);
#else
    return depth_a < depth_b || (depth_a == depth_b && triangle_a < triangle_b);
#endif
}

// Insertion sort done on the list itself (thesis algorithm 10): takes the nodes
// of the list at `head` one by one along ll_next and links each into place in
// ll_sorted_next, so the original list stays intact. Returns the sorted list's
// first node; `length` gets the number of nodes.
uint ll_sort_in_place(uint head, out uint length)
{
    uint sorted_head = OIT_LIST_END;
    float head_depth = 0.0;
    uint head_triangle = 0u;
    length = 0u;
    for (uint node = head; node != OIT_LIST_END; node = ll_next_fetch(node)) {
        uvec2 key = ll_node_fetch(node).zw;
        float depth = uintBitsToFloat(key.x);
        ++length;
        if (sorted_head == OIT_LIST_END || ll_in_front(depth, key.y, head_depth, head_triangle)) {
            ll_sorted_next[node] = sorted_head;
            sorted_head = node;
            head_depth = depth;
            head_triangle = key.y;
            continue;
        }
        // walk the sorted list to the last node in front of this one
        uint previous = sorted_head;
        uint current = ll_sorted_next[previous];
        while (current != OIT_LIST_END) {
            uvec2 current_key = ll_node_fetch(current).zw;
            if (ll_in_front(depth, key.y, uintBitsToFloat(current_key.x), current_key.y))
                break;
            previous = current;
            current = ll_sorted_next[current];
        }
        ll_sorted_next[node] = current;
        ll_sorted_next[previous] = node;
    }
    return sorted_head;
}

// What every sort variant does after sorting a pixel: store the sorted head
// and count the pixel into the statistics with as few atomics as the figures
// allow: one histogram increment; the longest list only when this one is longer
// than the longest so far (a stale read only costs an extra atomicMax: the
// value never falls); the fragments only of lists in the open last bin. The C
// side derives the non-empty pixels, the fragments sorted (checked against the
// fill) and psi from the histogram. Every atomic on this one shared buffer was
// what a short list's sort waited on: llvmpipe's two threads pass its cache
// lines back and forth (docs/algorithms.md, "Where ll's time goes"). Empty
// pixels never get here (LL_EMPTY_PIXEL_DISCARD).
void ll_finish_sort(ivec2 pixel, uint sorted_head, uint length)
{
    imageStore(ll_heads, pixel, uvec4(sorted_head, 0u, 0u, 0u));
    uint bin = min(length, uint(OIT_LL_HISTOGRAM_BINS - 1));
    atomicAdd(ll_counters[OIT_LL_COUNTER_HISTOGRAM + bin], 1u);
    if (length > ll_counters[OIT_FRAME_COUNTER_MAX_LIST])
        atomicMax(ll_counters[OIT_FRAME_COUNTER_MAX_LIST], length);
    if (bin == uint(OIT_LL_HISTOGRAM_BINS - 1))
        atomicAdd(ll_counters[OIT_LL_COUNTER_SORTED_FRAGMENTS], length);
}

#endif
