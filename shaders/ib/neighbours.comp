// neighbours.comp: links every fragment to its surface neighbour in the pixels
// to the left, right, bottom and top (the fragment of the same surface, which
// is generally not the one of the same layer). Stores the neighbour's layer
// index in that pixel's run. Three searches (ib_search):
//   index:   g is a candidate if its triangle shares a vertex index with f's (thesis);
//   welded:  the same on position-welded vertex ids, so seams do not cut surfaces;
//   epsilon: Carnecky's heuristic eps = eps_z + eps_n (eps_z: depth predicted on
//            f's triangle plane at g's pixel vs g's depth, over the model radius;
//            eps_n = 1 - n_f . n_g; other component: infinite), best candidate
//            with eps <= ib_epsilon_max, kept only if f is also its best partner.
// index / welded pick among the candidates (same component, a shared id) the
// one nearest to the depth f's triangle plane predicts (the thesis took the
// first). Where no candidate shares an id, welded falls back to epsilon: a
// pixel step can jump over a triangle thinner than a pixel (thesis fig. 3.9).
//
// This pass runs the index / welded search. Fragments that need epsilon (every
// fragment for epsilon; for welded those with a direction left without a
// neighbour where the candidate nearest the predicted depth is near enough for
// epsilon to accept: eps >= eps_z) are queued in the fill nodes, free between
// sort and fields, and
// neighbours_epsilon.comp searches them: llvmpipe runs a branch's body for all
// 8 lanes (masked) when any lane takes it, so a rare, costly branch is cheaper
// as a pass over the few fragments that need it.
// Compute pass, one invocation per pixel of the tiles with fragments (ib/tiles.glsl).
#include "common/oit_shared.h"
#include "ib/neighbour_search.glsl"
#include "ib/tiles.glsl"

layout(local_size_x = OIT_IB_TILE_SIZE, local_size_y = OIT_IB_TILE_SIZE) in;

void main()
{
    ivec2 pixel;
    if (!ib_tile_pixel(pixel) || !ib_inside(pixel))
        return;
    uint run_length = ib_run_length(pixel);
    if (run_length == 0u)
        return;
    uint start = ib_run_start(pixel);
    vec2 centre = vec2(pixel) + 0.5;
    // the four neighbouring runs (empty outside the image) and the rays
    // through their centres, once per pixel
    uint other_start[4], other_length[4];
    pixel_ray other_ray[4];
    for (int d = 0; d < 4; ++d) {
        ivec2 other = pixel + IB_DIRECTIONS[d];
        other_start[d] = 0u;
        other_length[d] = 0u;
        if (ib_inside(other)) {
            other_start[d] = ib_run_start(other);
            other_length[d] = ib_run_length(other);
        }
        other_ray[d] = ray_through(centre + vec2(IB_DIRECTIONS[d]));
    }
    for (uint i = 0u; i < run_length; ++i) {
        uint found[4];
        uint missing = 0u; // directions left for epsilon (bits)
        if (ib_search == OIT_IB_SEARCH_EPSILON) {
            for (int d = 0; d < 4; ++d) {
                found[d] = IB_NONE;
                missing |= other_length[d] > 0u ? 1u << d : 0u;
            }
        } else {
            described_fragment described = describe(ib_core_fetch(start + i), centre);
            for (int d = 0; d < 4; ++d) {
                float nearest_gap;
                found[d] = search_by_ids(described, other_ray[d], other_start[d], other_length[d],
                                         nearest_gap);
                // epsilon >= eps_z >= nearest_gap / radius (less eps_n's rounding):
                // past the largest accepted epsilon it can find nothing there
                bool epsilon_may_find =
                    nearest_gap / ib_radius_eye <= ib_epsilon_max + IB_EPSILON_MARGIN;
                missing |= found[d] == IB_NONE && epsilon_may_find ? 1u << d : 0u;
            }
            if (ib_search == OIT_IB_SEARCH_INDEX)
                missing = 0u;
        }
        ib_links[start + i] = uvec2(found[0] | (found[1] << 16), found[2] | (found[3] << 16));
        if (missing != 0u) {
            uint item = atomicAdd(ib_counters[OIT_IB_COUNTER_EPSILON_ITEMS], 1u);
            ib_nodes[item].xy = uvec2(uint(pixel.x) | (uint(pixel.y) << 16), i | (missing << 16));
        }
    }
}
