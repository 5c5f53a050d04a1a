// fields_init.comp: the transparency fields' initial values (thesis 4.4.1,
// rules of 3.3.1). Per fragment: boundary = directions without a neighbour;
// "under" = some neighbour has a smaller layer index (an occluding surface's
// contour passes between them and f is beneath it); "beside" = some neighbour
// has a larger one (f is just outside such a contour).
//   boundary: alpha = beta = 1, fixed (sources)
//   under:    beta = 0, fixed
//   beside:   gamma = 1, fixed
//   else 0 and free to change. Written to copy 0.
// Compute pass, one invocation per pixel of the band's rows of tiles.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

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
        int boundary = 0;
        bool under = false, beside = false;
        for (int d = 0; d < 4; ++d) {
            uint layer = ib_link(f.slot, d);
            if (layer == IB_NONE)
                ++boundary;
            else if (layer < i)
                under = true;
            else if (layer > i)
                beside = true;
        }
        vec3 values = vec3(0.0);
        uint flags = IB_FREE_ALPHA | IB_FREE_BETA | IB_FREE_GAMMA;
        if (boundary > 0) {
            values.xy = vec2(1.0);
            flags &= ~(IB_FREE_ALPHA | IB_FREE_BETA);
        }
        if (under) {
            values.y = 0.0;
            flags &= ~IB_FREE_BETA;
        }
        if (beside) {
            values.z = 1.0;
            flags &= ~IB_FREE_GAMMA;
        }
        ib_store_fields(f.slot, 0, values, flags);
    }
}
