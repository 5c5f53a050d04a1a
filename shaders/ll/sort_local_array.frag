// sort_local_array.frag: copy each pixel's list into a local array, insertion
// sort it there and link the result into ll_sorted_next. Lists longer than the
// array are sorted in place instead (and counted), so every pixel stays exact.
// Full-screen pass, writes no colour.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "ll/ll_nodes.glsl"

void main()
{
    if (LL_HELPER_INVOCATION)
        return;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint head = imageLoad(ll_heads, pixel).x;
    if (head == OIT_LIST_END)
        discard; // LL_EMPTY_PIXEL_DISCARD (ll_nodes.glsl)

    uint nodes[OIT_LOCAL_ARRAY_CAPACITY];
    float depths[OIT_LOCAL_ARRAY_CAPACITY];
    uint triangles[OIT_LOCAL_ARRAY_CAPACITY];
    uint count = 0u;
    bool too_long = false;
    for (uint node = head; node != OIT_LIST_END; node = ll_next_fetch(node)) {
        if (count == uint(OIT_LOCAL_ARRAY_CAPACITY)) {
            too_long = true;
            break;
        }
        uvec2 key = ll_node_fetch(node).zw;
        nodes[count] = node;
        depths[count] = uintBitsToFloat(key.x);
        triangles[count] = key.y;
        ++count;
    }
    if (!too_long) {
        // insertion sort: each element moves in behind the last one in front of it
        for (uint i = 1u; i < count; ++i) {
            uint node = nodes[i];
            float depth = depths[i];
            uint triangle = triangles[i];
            uint slot = i;
            for (; slot > 0u; --slot) {
                if (!ll_in_front(depth, triangle, depths[slot - 1u], triangles[slot - 1u]))
                    break;
                nodes[slot] = nodes[slot - 1u];
                depths[slot] = depths[slot - 1u];
                triangles[slot] = triangles[slot - 1u];
            }
            nodes[slot] = node;
            depths[slot] = depth;
            triangles[slot] = triangle;
        }
    }

    uint sorted_head;
    uint length;
    if (too_long) {
        atomicAdd(ll_counters[OIT_FRAME_COUNTER_LONG_LIST_PIXELS], 1u);
        sorted_head = ll_sort_in_place(head, length);
    } else {
        for (uint i = 0u; i + 1u < count; ++i)
            ll_sorted_next[nodes[i]] = nodes[i + 1u];
        if (count > 0u)
            ll_sorted_next[nodes[count - 1u]] = OIT_LIST_END;
        sorted_head = count > 0u ? nodes[0] : OIT_LIST_END;
        length = count;
    }
    ll_finish_sort(pixel, sorted_head, length);
}
