// tiles.glsl: the tile list of the compute passes that run over the tiles with
// fragments instead of the whole image. sort.comp appends every tile
// (OIT_IB_TILE_SIZE squared pixels, one work group) that has a fragment;
// tiles_dispatch.comp turns the count into work-group counts, and a pass
// dispatched with them (glDispatchComputeIndirect) finds its pixel with
// ib_tile_pixel. Why: llvmpipe runs a compute invocation's code under a lane
// mask, so an empty pixel's early return skips nothing and a pass over the
// whole image costs about the same per empty pixel as per pixel with a short
// run (docs/illustration-buffer.md, "Cost").
#ifndef IB_TILES_GLSL
#define IB_TILES_GLSL
#include "ib/ib_common.glsl"

layout(std430, binding = OIT_SSBO_IB_TILES) buffer ib_tile_buffer {
    uint ib_tiles[];
};

// This invocation's pixel in a pass dispatched over the tile list; false past
// the list's end (the last row of work groups is only partly used).
bool ib_tile_pixel(out ivec2 pixel)
{
    uint tile = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    pixel = ivec2(0);
    if (tile >= ib_counters[OIT_IB_COUNTER_TILES])
        return false;
    uint tile_xy = ib_tiles[tile];
    pixel = ivec2(tile_xy & 0xFFFFu, tile_xy >> 16) * OIT_IB_TILE_SIZE + ivec2(gl_LocalInvocationID.xy);
    return true;
}

#endif
