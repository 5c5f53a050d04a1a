// sort.comp: turns each pixel's linked list into a contiguous run sorted front
// to back (insertion sort in the run itself). Each tile (one work group of
// OIT_IB_TILE_SIZE squared pixels) takes one block of the run buffer with one
// atomicAdd, its pixels their places in the block from a shared counter, so
// the runs of neighbouring pixels lie together in memory; the head image then
// holds the run's start and the count image its length. A tile with fragments
// is appended to the tile list that the neighbour passes run over
// (ib/tiles.glsl). Also counts the list statistics with one atomic per
// non-empty pixel (a histogram bin; the longest list only when this run is
// longer than the longest read so far): non-empty pixels are the histogram's
// sum, empty ones the rest (alg_ib.c).
// Compute pass, one invocation per pixel.
#include "common/oit_shared.h"
#include "ib/tiles.glsl"

layout(local_size_x = OIT_IB_TILE_SIZE, local_size_y = OIT_IB_TILE_SIZE) in;

shared uint tile_fragments; // the tile's fragments counted so far: each run's offset in the block
shared uint tile_start;     // the tile's block in the run buffer

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = ib_inside(pixel);
    if (gl_LocalInvocationIndex == 0u)
        tile_fragments = 0u;
    memoryBarrierShared();
    barrier();
    uint head = inside ? imageLoad(ib_heads, pixel).x : OIT_LIST_END;
    uint run_length = 0u;
    // the nodes are only read here: through the buffer texture (see ib_common.glsl)
    for (uint node = head; node != OIT_LIST_END; node = texelFetch(ib_nodes_texture, int(node)).w)
        ++run_length;
    uint offset = run_length > 0u ? atomicAdd(tile_fragments, run_length) : 0u;
    memoryBarrierShared();
    barrier();
    if (gl_LocalInvocationIndex == 0u && tile_fragments > 0u) {
        tile_start = atomicAdd(ib_counters[OIT_IB_COUNTER_RUN_ALLOCATOR], tile_fragments);
        ib_tiles[atomicAdd(ib_counters[OIT_IB_COUNTER_TILES], 1u)] =
            gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
    }
    memoryBarrierShared();
    barrier();
    if (!inside)
        return;
    uint start = run_length > 0u ? tile_start + offset : 0u;
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
    if (run_length > 0u) {
        atomicAdd(ib_counters[OIT_IB_COUNTER_HISTOGRAM + int(min(run_length, uint(OIT_IB_HISTOGRAM_BINS - 1)))], 1u);
        if (run_length > ib_counters[OIT_FRAME_COUNTER_MAX_LIST])
            atomicMax(ib_counters[OIT_FRAME_COUNTER_MAX_LIST], run_length);
    }
}
