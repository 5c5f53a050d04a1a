// diffusion.comp: one iteration of the fields' diffusion over surface
// neighbours, copy `ib_pass` to the other (ping-pong). Fixed values stay.
//   alpha: physical, alpha += lambda_alpha * L / 4 with the 3x3 Laplacian
//          [0.5 1 0.5; 1 -6 1; 0.5 1 0.5] over the 8 surface neighbours
//          (a missing neighbour counts as equal to the centre);
//   beta, gamma: non-physical, x = max(x, max over the 4 neighbours - lambda)
//          (thesis eq. 3.3 / 3.4: subtract, not the multiply of its listing).
// Compute pass, one invocation per pixel of the band's rows of tiles.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(location = OIT_UNIFORM_IB_PASS) uniform int source_copy;

const ivec2 DIAGONALS[4] = ivec2[4](ivec2(0, 2), ivec2(0, 3), ivec2(1, 2), ivec2(1, 3));

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 pixel = ib_band_pixel(gl_GlobalInvocationID);
    if (!ib_inside(pixel))
        return;
    uint start = ib_run_start(pixel);
    uint run_length = ib_run_length(pixel);
    for (uint i = 0u; i < run_length; ++i) {
        ib_fragment f = ib_fragment(pixel, start + i, i);
        uvec2 raw = ib_fields_raw(f.slot, source_copy);
        vec3 x = ib_fields_values(raw);
        uint flags = ib_fields_flags(raw);
        float laplacian = 0.0;
        vec2 largest = vec2(0.0); // beta, gamma of the neighbours
        for (int d = 0; d < 4; ++d) {
            ib_fragment g;
            if (ib_neighbour(f, d, g)) {
                vec3 y = ib_fields_values(ib_fields_raw(g.slot, source_copy));
                laplacian += y.x - x.x;
                largest = max(largest, y.yz);
            }
        }
        for (int k = 0; k < 4; ++k) {
            ib_fragment g;
            if (ib_diagonal(f, DIAGONALS[k].x, DIAGONALS[k].y, g))
                laplacian += 0.5 * (ib_fields_values(ib_fields_raw(g.slot, source_copy)).x - x.x);
        }
        if ((flags & IB_FREE_ALPHA) != 0u)
            x.x += ib_lambda_alpha * laplacian * 0.25;
        if ((flags & IB_FREE_BETA) != 0u)
            x.y = max(x.y, largest.x - ib_lambda_beta);
        if ((flags & IB_FREE_GAMMA) != 0u)
            x.z = max(x.z, largest.y - ib_lambda_gamma);
        ib_store_fields(f.slot, 1 - source_copy, x, flags);
    }
}
