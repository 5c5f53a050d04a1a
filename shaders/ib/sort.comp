// sort.comp: turns each pixel's linked list into a contiguous run sorted front
// to back (insertion sort in the run itself). The run's place comes from one
// atomicAdd per pixel, so runs are contiguous but in no particular pixel order;
// the head image then holds the run's start and the count image its length.
// Also counts the list statistics (longest list, non-empty pixels, histogram).
// Compute pass, one invocation per pixel.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!ib_inside(pixel))
        return;
    uint head = imageLoad(ib_heads, pixel).x;
    uint run_length = 0u;
    // the nodes are only read here: through the buffer texture (see ib_common.glsl)
    for (uint node = head; node != OIT_LIST_END; node = texelFetch(ib_nodes_texture, int(node)).w)
        ++run_length;
    uint start = run_length > 0u ? atomicAdd(ib_counters[OIT_IB_COUNTER_RUN_ALLOCATOR], run_length) : 0u;
    uint size = 0u;
    for (uint node = head; node != OIT_LIST_END; ++size) {
        uvec4 data = texelFetch(ib_nodes_texture, int(node));
        uint slot = start + size;
        // move the fragments behind this one a place back
        while (slot > start && ib_in_front(data.xy, ib_core[slot - 1u].xy)) {
            ib_core[slot] = ib_core[slot - 1u];
            --slot;
        }
        ib_core[slot] = uvec4(data.xyz, 0u);
        node = data.w;
    }
    imageStore(ib_heads, pixel, uvec4(start, 0u, 0u, 0u));
    imageStore(ib_counts, pixel, uvec4(run_length, 0u, 0u, 0u));
    atomicAdd(ib_counters[OIT_IB_COUNTER_HISTOGRAM + int(min(run_length, uint(OIT_IB_HISTOGRAM_BINS - 1)))], 1u);
    if (run_length > 0u) {
        atomicMax(ib_counters[OIT_FRAME_COUNTER_MAX_LIST], run_length);
        atomicAdd(ib_counters[OIT_FRAME_COUNTER_NONEMPTY_PIXELS], 1u);
    }
}
