// neighbour_stats.comp: the per-frame quality of the neighbour links, summed
// on the GPU with atomics (one add per pixel and counter): fragments with all
// four neighbours, links, links whose partner links back (g is f's right
// neighbour and f is g's left one), links that stay on the same component.
// Diagnostics: runs only with oit_algorithm_config.neighbour_quality (Psi is
// counted by compose.frag).
// Compute pass, one invocation per pixel of the tiles with fragments
// (ib/tiles.glsl); reads through the buffer textures, the neighbouring runs'
// starts are loaded once per pixel. In a band of rows, only the rows it composes
// are counted (their neighbours are in the rows it stores).
#include "common/oit_shared.h"
#include "ib/tiles.glsl"

layout(local_size_x = OIT_IB_TILE_SIZE, local_size_y = OIT_IB_TILE_SIZE) in;

// counters[low] += value, carrying into counters[high] when the low word wraps
void add64(int low, int high, uint value)
{
    uint before = atomicAdd(ib_counters[low], value);
    if (before + value < before)
        atomicAdd(ib_counters[high], 1u);
}

void main()
{
    ivec2 pixel;
    if (!ib_tile_pixel(pixel) || !ib_inside(pixel) || !ib_counted(pixel))
        return;
    uint run_length = ib_run_length(pixel);
    if (run_length == 0u)
        return;
    uint start = ib_run_start(pixel);
    uint other_start[4];
    for (int d = 0; d < 4; ++d) {
        ivec2 other = pixel + IB_DIRECTIONS[d];
        other_start[d] = ib_inside(other) ? ib_run_start(other) : 0u;
    }
    uint four = 0u, links = 0u, symmetric = 0u, same_component = 0u;
    for (uint i = 0u; i < run_length; ++i) {
        uint slot = start + i;
        uint component = ib_triangle_component(ib_core_fetch(slot).y);
        uvec2 words = texelFetch(ib_links_texture, int(slot)).xy;
        int count = 0;
        for (int d = 0; d < 4; ++d) {
            uint word = d < 2 ? words.x : words.y;
            uint layer = (d & 1) == 0 ? (word & 0xFFFFu) : (word >> 16);
            if (layer == IB_NONE)
                continue;
            uint other_slot = other_start[d] + layer;
            ++count;
            ++links;
            if (ib_link(other_slot, d ^ 1) == i)
                ++symmetric;
            if (ib_triangle_component(ib_core_fetch(other_slot).y) == component)
                ++same_component;
        }
        if (count == 4)
            ++four;
    }
    atomicAdd(ib_counters[OIT_IB_COUNTER_FOUR_NEIGHBOURS], four); // <= fragments < 2^32
    // up to 4 links per fragment: 64-bit counts (low word, and its wraps)
    add64(OIT_IB_COUNTER_LINKS, OIT_IB_COUNTER_LINKS_WRAPS, links);
    add64(OIT_IB_COUNTER_SYMMETRIC_LINKS, OIT_IB_COUNTER_SYMMETRIC_LINKS_WRAPS, symmetric);
    add64(OIT_IB_COUNTER_SAME_COMPONENT_LINKS, OIT_IB_COUNTER_SAME_COMPONENT_LINKS_WRAPS, same_component);
}
