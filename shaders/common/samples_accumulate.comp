// samples_accumulate.comp: anti-aliasing's accumulation (gpu_algorithm.c,
// oit_gpu_accumulate; docs/algorithms.md, "Anti-aliasing"). After each
// sample's frame it adds the RGBA8 output, read as the integers it holds
// (rgba8ui), to the per-pixel sum; after the last it writes the rounded
// average (sum + n / 2) / n back into the output, exactly as the reference
// averages its samples. One invocation per pixel.
#include "common/oit_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = OIT_IMAGE_SAMPLES_OUTPUT, rgba8ui) uniform restrict uimage2D u_output;
layout(binding = OIT_IMAGE_SAMPLES_SUM, rgba16ui) uniform restrict uimage2D u_sum;
uniform int u_step;     // OIT_SAMPLES_STORE, _ADD or _RESOLVE
uniform uint u_samples; // n

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(u_output))))
        return;
    uvec4 sum = imageLoad(u_output, pixel);
    if (u_step != OIT_SAMPLES_STORE)
        sum += imageLoad(u_sum, pixel);
    if (u_step == OIT_SAMPLES_RESOLVE)
        imageStore(u_output, pixel, (sum + u_samples / 2u) / u_samples);
    else
        imageStore(u_sum, pixel, sum);
}
