// neighbours_epsilon.comp: the epsilon search (with the mutual check) for the
// fragments neighbours.comp queued: item k of the fill nodes holds the pixel
// (x | y << 16) and the layer | the directions to search << 16. Updates those
// directions of the fragment's links (still none where epsilon finds none).
// Compute pass, one invocation per queued fragment.
#include "common/oit_shared.h"
#include "ib/neighbour_search.glsl"

layout(local_size_x = OIT_IB_ITEMS_PER_GROUP) in;

void main()
{
    // dispatched indirectly (epsilon_dispatch.comp): rows of groups, the last one partly used
    uint item = gl_GlobalInvocationID.x +
                gl_GlobalInvocationID.y * gl_NumWorkGroups.x * uint(OIT_IB_ITEMS_PER_GROUP);
    if (item >= ib_counters[OIT_IB_COUNTER_EPSILON_ITEMS])
        return;
    uvec2 queued = ib_nodes[item].xy;
    ivec2 pixel = ivec2(queued.x & 0xFFFFu, queued.x >> 16);
    uint i = queued.y & 0xFFFFu;
    uint directions = queued.y >> 16;
    uint start = ib_run_start(pixel);
    uint run_length = ib_run_length(pixel);
    vec2 centre = vec2(pixel) + 0.5;
    pixel_ray ray = ray_through(centre);
    uvec4 core = ib_core_fetch(start + i);
    described_fragment described = describe(core, centre);
    uvec2 words = texelFetch(ib_links_texture, int(start + i)).xy;
    for (int d = 0; d < 4; ++d) {
        if ((directions & (1u << d)) == 0u)
            continue;
        ivec2 other = pixel + IB_DIRECTIONS[d];
        vec2 other_centre = centre + vec2(IB_DIRECTIONS[d]);
        uint found = search_by_epsilon(i, core, described, ray, start, run_length,
                                       ray_through(other_centre), other_centre,
                                       ib_run_start(other), ib_run_length(other));
        uint shift = (d & 1) == 0 ? 0u : 16u;
        if (d < 2)
            words.x = (words.x & ~(0xFFFFu << shift)) | (found << shift);
        else
            words.y = (words.y & ~(0xFFFFu << shift)) | (found << shift);
    }
    ib_links[start + i] = words;
}
