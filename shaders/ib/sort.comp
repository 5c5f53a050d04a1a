// sort.comp: turns each pixel's linked list into a contiguous run sorted front
// to back (insertion sort in the run itself, from either end). Each tile (one work group of
// OIT_IB_TILE_SIZE squared pixels) takes one block of the run buffer with one
// atomicAdd, its pixels their places in the block from a shared counter, so
// the runs of neighbouring pixels lie together in memory; the head image then
// holds the run's start and the count image its length. A tile with fragments
// is appended to the tile list that the neighbour passes run over
// (ib/tiles.glsl). Also counts the list statistics with one atomic per
// non-empty pixel (a histogram bin; the longest list only when this run is
// longer than the longest read so far): non-empty pixels are the histogram's
// sum, empty ones the rest (alg_ib.c). In a band of rows only the rows it
// composes are counted, and in a frame drawn in bands the runs of the open
// last bin are counted by length too.
// Compute pass, one invocation per pixel of the band's rows of tiles.
#include "common/oit_shared.h"
#include "ib/tiles.glsl"

layout(local_size_x = OIT_IB_TILE_SIZE, local_size_y = OIT_IB_TILE_SIZE) in;

// frames drawn in bands: pixels by the length of their run, lengths in the open
// last bin only (OIT_SSBO_IB_LONG_RUNS in oit_shared.h)
layout(std430, binding = OIT_SSBO_IB_LONG_RUNS) buffer ib_long_run_buffer {
    uint ib_long_runs[];
};

shared uint tile_fragments; // the tile's fragments counted so far: each run's offset in the block
shared uint tile_start;     // the tile's block in the run buffer

void main()
{
    ivec2 pixel = ib_band_pixel(gl_GlobalInvocationID);
    bool inside = ib_inside(pixel);
    if (gl_LocalInvocationIndex == 0u)
        tile_fragments = 0u;
    memoryBarrierShared();
    barrier();
    uint head = inside ? imageLoad(ib_heads, pixel).x : OIT_LIST_END;
    uint run_length = 0u;
    // adjacent nodes where the later one in the list lies in front: a move for
    // the forward insertion below, none for the backward one (counted between
    // neighbours only, a cheap guess at which end moves fewer fragments)
    uint later_in_front = 0u;
    uvec2 previous = uvec2(0u);
    // the nodes are only read here: through the buffer texture (see ib_common.glsl)
    for (uint node = head; node != OIT_LIST_END; ++run_length) {
        uvec4 data = texelFetch(ib_nodes_texture, int(node));
        later_in_front += run_length > 0u && ib_in_front(data.xy, previous) ? 1u : 0u;
        previous = data.xy;
        node = data.w;
    }
    uint offset = run_length > 0u ? atomicAdd(tile_fragments, run_length) : 0u;
    memoryBarrierShared();
    barrier();
    if (gl_LocalInvocationIndex == 0u && tile_fragments > 0u) {
        tile_start = atomicAdd(ib_counters[OIT_IB_COUNTER_RUN_ALLOCATOR], tile_fragments);
        ib_tiles[atomicAdd(ib_counters[OIT_IB_COUNTER_TILES], 1u)] =
            gl_WorkGroupID.x | ((gl_WorkGroupID.y + uint(ib_band_tile_row())) << 16);
    }
    memoryBarrierShared();
    barrier();
    if (!inside)
        return;
    uint start = run_length > 0u ? tile_start + offset : 0u;
    // Insertion sort in the run, from the end the count above favours:
    // forwards the sorted part grows from the start and each node moves the
    // ones behind it back; backwards it grows from the end and each node moves
    // the ones in front of it forward. The order is total (depth, triangle),
    // so both give the same run; the moves (storage-buffer loads and stores,
    // lane by lane in llvmpipe) are most of the sort's time.
    bool backwards = 2u * later_in_front > run_length;
    uint end = start + run_length;
    uint size = 0u;
    for (uint node = head; node != OIT_LIST_END; ++size) {
        uvec4 data = texelFetch(ib_nodes_texture, int(node));
        uint slot = backwards ? end - 1u - size : start + size;
        while (true) {
            uint other = backwards ? slot + 1u : slot - 1u;
            if (backwards ? other >= end : slot <= start)
                break;
            uvec2 key = ib_core[other].xy;
            if (!(backwards ? ib_in_front(key, data.xy) : ib_in_front(data.xy, key)))
                break;
            ib_core[slot] = ib_core[other];
            slot = other;
        }
        ib_core[slot] = uvec4(data.xyz, 0u);
        node = data.w;
    }
    imageStore(ib_heads, pixel, uvec4(start, 0u, 0u, 0u));
    imageStore(ib_counts, pixel, uvec4(run_length, 0u, 0u, 0u));
    if (run_length > 0u && ib_counted(pixel)) {
        atomicAdd(ib_counters[OIT_IB_COUNTER_HISTOGRAM + int(min(run_length, uint(OIT_IB_HISTOGRAM_BINS - 1)))], 1u);
        if (run_length > ib_counters[OIT_FRAME_COUNTER_MAX_LIST])
            atomicMax(ib_counters[OIT_FRAME_COUNTER_MAX_LIST], run_length);
        if (ib_banded != 0 && run_length >= uint(OIT_IB_HISTOGRAM_BINS - 1))
            atomicAdd(ib_long_runs[min(run_length, uint(OIT_IB_LONG_RUN_LENGTHS - 1))], 1u);
    }
}
