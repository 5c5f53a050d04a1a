// distance_max.comp: the largest distance along the ray of the band's pixels,
// as curvature_distance.comp measures it (into the same counter, atomicMax on
// the float bits), and nothing else: the first sweep of a frame drawn in bands
// (alg_ib.c), whose compose needs the frame's largest distance (the distance
// modulation's automatic region) before any band composes. The runs are
// sorted; there are no neighbour links yet.
// Compute pass, one invocation per pixel of the band's rows of tiles.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

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
        uint target = ib_distance_target(i, run_length);
        if (target != i)
            largest = max(largest, ib_depth_distance(centre, ib_depth_fetch(start + i),
                                                     ib_depth_fetch(start + target)));
    }
    if (largest > 0.0)
        atomicMax(ib_counters[OIT_IB_COUNTER_MAX_DISTANCE], floatBitsToUint(largest));
}
