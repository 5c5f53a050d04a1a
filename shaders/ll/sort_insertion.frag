// sort_insertion.frag: sort each pixel's list in place (insertion sort over
// the list, second next-pointer buffer). Full-screen pass, writes no colour.
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
    uint length;
    uint sorted_head = ll_sort_in_place(head, length);
    ll_finish_sort(pixel, sorted_head, length);
}
