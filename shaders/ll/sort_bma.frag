// sort_bma.frag: Knowles, Leach and Zambetta's exact sorts for the linked lists
// ("Efficient layered fragment buffer techniques", 2013; "Fast sorting for
// exact OIT of complex scenes", 2014): backwards memory allocation (BMA) with
// the register-block sort (RBS). Full-screen pass, writes no colour.
//
// BMA gives each pixel a private array sized to its list's length interval,
// so short lists do not pay for the longest one's array. The paper draws one
// stencil-masked pass per interval; here each pixel branches on its length
// instead (ll's sort pass has no stencil buffer, and every extra full-screen
// pass costs llvmpipe a walk over the whole frame; llvmpipe runs 8 pixels as
// one group under a mask, so a branch no pixel of a group takes costs only its
// straight-line code: its loops end at once).
// (--sort merge leaves the arrays out: every list past 8 nodes takes the
// merge in the lists.)
//   up to 8 nodes      one register block: no array at all
//   9..16, 17..32,     arrays of 16, 32, 64 (two halves each: the merge
//   33..64             passes go back and forth between them)
//   longer             a merge sort in the lists themselves: runs of 8 nodes
//                      from the register block, merged bottom-up in
//                      ll_sorted_next (a binary counter of pending runs, one
//                      per level), O(n log n) steps with no array at all
// RBS: a block of 8 nodes is read into registers (every index a constant, so
// no private array), sorted by an odd-even transposition network and written
// out as a sorted run; the array sizes merge such runs (widths 8, 16, 32).
//
// Every step is stable (ties keep the list's order) and the order is
// ll_in_front's, so the result is the insertion sort's node for node: the
// images are byte-identical. The work is O(n log n) per pixel, which keeps
// long lists under llvmpipe's 65,535 loop iterations per invocation (a
// 1,200-deep list in the worst order: about 9,000 steps; docs/algorithms.md,
// Limits).
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "ll/ll_nodes.glsl"
// --sort merge (alg_ll.c defines it 1): no private arrays, every list past one
// register block is merged in the lists (faster on llvmpipe: docs/algorithms.md)
#ifndef LL_BMA_NO_ARRAYS
#define LL_BMA_NO_ARRAYS 0
#endif

// A sort key and its node: x = depth bits, y = triangle, z = node.
// LL_BMA_PAD sorts behind every fragment (depths are in [0, 1]).
#define LL_BMA_PAD uvec3(0x7F800000u, 0xFFFFFFFFu, OIT_LIST_END)

bool ll_bma_in_front(uvec3 a, uvec3 b)
{
    return ll_in_front(uintBitsToFloat(a.x), a.y, uintBitsToFloat(b.x), b.y);
}

uvec3 ll_bma_key(uint node)
{
    uvec4 n = ll_node_fetch(node);
    return uvec3(n.z, n.w, node);
}

// compare-exchange of neighbours i < j: swaps only when j is strictly in front (stable)
#define LL_BMA_CX(i, j)                                                                      \
    {                                                                                        \
        bool swap = ll_bma_in_front(b[j], b[i]);                                             \
        uvec3 first = swap ? b[j] : b[i];                                                    \
        b[j] = swap ? b[i] : b[j];                                                           \
        b[i] = first;                                                                        \
    }
#define LL_BMA_EVEN LL_BMA_CX(0, 1) LL_BMA_CX(2, 3) LL_BMA_CX(4, 5) LL_BMA_CX(6, 7)
#define LL_BMA_ODD LL_BMA_CX(1, 2) LL_BMA_CX(3, 4) LL_BMA_CX(5, 6)

// The register block: reads up to 8 nodes from `cursor` along ll_next into b
// (the rest padded), sorts them and moves cursor past them. count = the nodes read.
void ll_bma_block(inout uint cursor, out uvec3 b[OIT_LL_BMA_BLOCK], out uint count)
{
    count = 0u;
    for (int k = 0; k < OIT_LL_BMA_BLOCK; ++k) { // constant bounds: unrolled, b stays in registers
        b[k] = LL_BMA_PAD;
        if (cursor != OIT_LIST_END) {
            b[k] = ll_bma_key(cursor);
            cursor = ll_next_fetch(cursor);
            ++count;
        }
    }
    // odd-even transposition: 8 rounds sort 8 elements
    LL_BMA_EVEN LL_BMA_ODD LL_BMA_EVEN LL_BMA_ODD
    LL_BMA_EVEN LL_BMA_ODD LL_BMA_EVEN LL_BMA_ODD
}

// Links a sorted block's `count` nodes into ll_sorted_next; returns its first.
uint ll_bma_link_block(uvec3 b[OIT_LL_BMA_BLOCK], uint count)
{
    for (int k = 0; k < OIT_LL_BMA_BLOCK; ++k)
        if (uint(k) < count)
            ll_sorted_next[b[k].z] = uint(k) + 1u < count ? b[min(k + 1, OIT_LL_BMA_BLOCK - 1)].z
                                                          : OIT_LIST_END;
    return b[0].z;
}

// Merges two sorted lists in ll_sorted_next, `a` holding the nodes that came
// first in the list (it wins ties); returns the merged list's first node. It
// stops when one list is used up and links the rest of the other whole.
uint ll_bma_merge(uint a, uint b)
{
    if (a == OIT_LIST_END)
        return b;
    if (b == OIT_LIST_END)
        return a;
    uvec3 key_a = ll_bma_key(a), key_b = ll_bma_key(b);
    uint head = OIT_LIST_END, tail = OIT_LIST_END;
    while (a != OIT_LIST_END && b != OIT_LIST_END) {
        bool take_b = ll_bma_in_front(key_b, key_a);
        uint taken = take_b ? b : a;
        if (tail == OIT_LIST_END)
            head = taken;
        else
            ll_sorted_next[tail] = taken;
        tail = taken;
        uint next = ll_sorted_next[taken];
        if (take_b) {
            b = next;
            if (b != OIT_LIST_END)
                key_b = ll_bma_key(b);
        } else {
            a = next;
            if (a != OIT_LIST_END)
                key_a = ll_bma_key(a);
        }
    }
    ll_sorted_next[tail] = a != OIT_LIST_END ? a : b;
    return head;
}

// A BMA interval's array a (2N keys: two halves) holding `count` keys in
// sorted runs of 8: merged bottom-up between the halves (widths 8, 16, ...),
// then linked into ll_sorted_next; sorted_head gets the first node.
#define LL_BMA_MERGE_ARRAY(a, N)                                                            \
    {                                                                                      \
        uint src = 0u, dst = uint(N);                                                      \
        for (uint width = uint(OIT_LL_BMA_BLOCK); width < count; width *= 2u) {            \
            uint i = 0u, i_end = min(width, count);                                        \
            uint j = i_end, j_end = min(2u * width, count);                                \
            for (uint k = 0u; k < count; ++k) {                                            \
                uvec3 left = a[src + min(i, count - 1u)];                                  \
                uvec3 right = a[src + min(j, count - 1u)];                                 \
                bool take_right = j < j_end && (i >= i_end || ll_bma_in_front(right, left)); \
                a[dst + k] = take_right ? right : left;                                    \
                j += take_right ? 1u : 0u;                                                 \
                i += take_right ? 0u : 1u;                                                 \
                if (i == i_end && j == j_end) {                                            \
                    i = j_end;                                                             \
                    i_end = min(j_end + width, count);                                     \
                    j = i_end;                                                             \
                    j_end = min(i_end + width, count);                                     \
                }                                                                          \
            }                                                                              \
            uint t = src;                                                                  \
            src = dst;                                                                     \
            dst = t;                                                                       \
        }                                                                                  \
        uint node = a[src].z;                                                              \
        sorted_head = node;                                                                \
        for (uint k = 1u; k < count; ++k) {                                                \
            uint next = a[src + k].z;                                                      \
            ll_sorted_next[node] = next;                                                   \
            node = next;                                                                   \
        }                                                                                  \
        ll_sorted_next[node] = OIT_LIST_END;                                               \
    }

void main()
{
    if (LL_HELPER_INVOCATION)
        return;
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint head = imageLoad(ll_heads, pixel).x;
    if (head == OIT_LIST_END)
        discard; // LL_EMPTY_PIXEL_DISCARD (ll_nodes.glsl)

    // the interval: the list counted as far as the largest array
    uint length = 0u;
    for (uint node = head; node != OIT_LIST_END && length <= uint(OIT_LL_BMA_LARGEST_ARRAY);
         node = ll_next_fetch(node))
        ++length;
    const uint REGISTERS = 0u, ARRAY_16 = 1u, ARRAY_32 = 2u, ARRAY_64 = 3u, LONG = 4u;
    uint interval = length <= uint(OIT_LL_BMA_BLOCK) ? REGISTERS
#if LL_BMA_NO_ARRAYS
                  : LONG;
#else
                  : length <= 16u ? ARRAY_16
                  : length <= 32u ? ARRAY_32
                  : length <= uint(OIT_LL_BMA_LARGEST_ARRAY) ? ARRAY_64 : LONG;
#endif

    // One loop over the register blocks (the block's code once: llvmpipe
    // compiles every copy of it, taken or not). Short lists: the block is the
    // sorted list; arrays: the blocks are stored as runs; long lists: each block
    // is linked as a run of 8 and merged bottom-up in the lists like a binary
    // counter (pending[level] holds a run of 8 << level nodes that came before
    // the later ones).
#if !LL_BMA_NO_ARRAYS
    uvec3 a16[32], a32[64], a64[2 * OIT_LL_BMA_LARGEST_ARRAY];
#endif
    uint pending[OIT_LL_BMA_LEVELS];
    for (int level = 0; level < OIT_LL_BMA_LEVELS; ++level)
        pending[level] = OIT_LIST_END;
    uint levels = 0u;
    uint count = 0u;
    uint sorted_head = OIT_LIST_END;
    for (uint cursor = head; cursor != OIT_LIST_END;) {
        uvec3 b[OIT_LL_BMA_BLOCK];
        uint block_count;
        ll_bma_block(cursor, b, block_count);
        if (interval == REGISTERS || interval == LONG) {
            uint run = ll_bma_link_block(b, block_count);
            uint level = 0u;
            while (pending[level] != OIT_LIST_END) {
                run = ll_bma_merge(pending[level], run);
                pending[level] = OIT_LIST_END;
                ++level;
            }
            pending[level] = run;
            levels = max(levels, level + 1u);
        }
#if !LL_BMA_NO_ARRAYS
        else {
            for (int k = 0; k < OIT_LL_BMA_BLOCK; ++k) {
                if (uint(k) < block_count) {
                    if (interval == ARRAY_16)
                        a16[min(count + uint(k), 15u)] = b[k];
                    else if (interval == ARRAY_32)
                        a32[min(count + uint(k), 31u)] = b[k];
                    else
                        a64[min(count + uint(k), uint(OIT_LL_BMA_LARGEST_ARRAY - 1))] = b[k];
                }
            }
        }
#endif
        count += block_count;
    }
#if !LL_BMA_NO_ARRAYS
    if (interval == ARRAY_16)
        LL_BMA_MERGE_ARRAY(a16, 16)
    else if (interval == ARRAY_32)
        LL_BMA_MERGE_ARRAY(a32, 32)
    else if (interval == ARRAY_64)
        LL_BMA_MERGE_ARRAY(a64, OIT_LL_BMA_LARGEST_ARRAY)
    else
#endif // the pending runs, from the shortest (the latest) up
        for (uint level = 0u; level < levels; ++level)
            sorted_head = ll_bma_merge(pending[level], sorted_head);
    // The length is what the sorted list holds, walked once more: llvmpipe
    // counts the loop iterations of the whole invocation (and of the 8 pixels
    // it runs together), so one it cut short in a merge or a link would lose
    // nodes after the blocks were all counted. The walk is cut short too then,
    // and the frame fails as with the other sorts (ll_add_counts).
    uint length_sorted = 0u;
    for (uint node = sorted_head; node != OIT_LIST_END; node = ll_sorted_next[node])
        ++length_sorted;
    ll_finish_sort(pixel, sorted_head, min(count, length_sorted));
}
