// blur.comp: one direction of the separable Gaussian blur of beta over surface
// neighbours (sigma 0.85, 5 taps: the fragment and two neighbours each side,
// reached through the links; weights renormalised over the taps that exist).
// ib_pass: bit 0 = source copy, bit 1 = direction (0 left/right, 1 bottom/top).
// Fixed values stay. Compute pass, one invocation per pixel of the band's rows
// of tiles.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(location = OIT_UNIFORM_IB_PASS) uniform int pass_parameter;

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    int source_copy = pass_parameter & 1;
    int axis = (pass_parameter >> 1) & 1;
    // exp(-x^2 / (2 * 0.85^2)) for x = 0, 1, 2
    const float weights[3] = float[3](1.0, 0.500574, 0.062785);
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
        if ((flags & IB_FREE_BETA) != 0u) {
            float sum = x.y * weights[0];
            float weight = weights[0];
            for (int side = 0; side < 2; ++side) {
                int d = 2 * axis + side;
                ib_fragment g = f;
                for (int step = 1; step <= 2; ++step) {
                    ib_fragment h;
                    if (!ib_neighbour(g, d, h))
                        break;
                    sum += weights[step] * ib_fields_values(ib_fields_raw(h.slot, source_copy)).y;
                    weight += weights[step];
                    g = h;
                }
            }
            x.y = sum / weight;
        }
        ib_store_fields(f.slot, 1 - source_copy, x, flags);
    }
}
