// curvature_distance.comp: per fragment, the curvature from its surface
// neighbours' normals, mean |n - n_k| / 2 over the 4 (or 8, diagonals reached
// through the surface) neighbours that exist, in [0, 1]; and the distance
// along the ray in linear eye depth: to the next fragment (adjacent), k on
// (skip, or the last one) or to the last one (far end); the last fragment's
// distance is 0. Stored in ib_core[].w; the frame's largest distance goes to
// a counter (atomicMax on the float bits: they order like the values, >= 0;
// distance_max.comp finds only that, for the first sweep of a banded frame).
// Compute pass, one invocation per pixel of the band's rows of tiles.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

const ivec2 DIAGONALS[4] = ivec2[4](ivec2(0, 2), ivec2(0, 3), ivec2(1, 2), ivec2(1, 3));

layout(local_size_x = 8, local_size_y = 8) in;

void main()
{
    ivec2 pixel = ib_band_pixel(gl_GlobalInvocationID);
    if (!ib_inside(pixel))
        return;
    vec2 centre = vec2(pixel) + 0.5;
    uint start = ib_run_start(pixel);
    uint run_length = ib_run_length(pixel);
    float largest = 0.0;
    for (uint i = 0u; i < run_length; ++i) {
        ib_fragment f = ib_fragment(pixel, start + i, i);
        uvec4 core = ib_core[f.slot];
        vec3 n = oit_unpack_normal(core.z);
        float sum = 0.0;
        int count = 0;
        for (int d = 0; d < 4; ++d) {
            ib_fragment g;
            if (ib_neighbour(f, d, g)) {
                sum += length(n - oit_unpack_normal(ib_core[g.slot].z));
                ++count;
            }
        }
        if (ib_curvature_neighbours == 8) {
            for (int k = 0; k < 4; ++k) {
                ib_fragment g;
                if (ib_diagonal(f, DIAGONALS[k].x, DIAGONALS[k].y, g)) {
                    sum += length(n - oit_unpack_normal(ib_core[g.slot].z));
                    ++count;
                }
            }
        }
        float curvature = count > 0 ? clamp(sum / (2.0 * float(count)), 0.0, 1.0) : 0.0;

        uint target = ib_distance_target(i, run_length);
        float distance = 0.0;
        if (target != i)
            distance = ib_depth_distance(centre, uintBitsToFloat(core.x),
                                         uintBitsToFloat(ib_core[start + target].x));
        largest = max(largest, distance);
        uint packed_distance = packHalf2x16(vec2(distance, 0.0)) & 0xFFFFu;
        ib_core[f.slot].w = uint(round(curvature * 65535.0)) | (packed_distance << 16);
    }
    if (largest > 0.0)
        atomicMax(ib_counters[OIT_IB_COUNTER_MAX_DISTANCE], floatBitsToUint(largest));
}
