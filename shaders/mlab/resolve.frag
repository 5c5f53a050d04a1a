// resolve.frag: composite each pixel's layers front to back in float,
//     C += T * c_i,   T *= t_i,
// then the background times T; the RGBA8 output is written once. Full-screen
// pass. Also gathers the figures of the statistics: the longest per-pixel count
// (fragments, not layers), the non-empty pixels and the sum of the counts, which
// the C side checks against the fragments the insert counted.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/frame.glsl"
#include "mlab/mlab_layers.glsl"

// the layers buffer read through a buffer texture (gathered in SIMD on llvmpipe)
layout(binding = OIT_TEXUNIT_MLAB_LAYERS) uniform usamplerBuffer mlab_layers_texture;

layout(location = 0) out vec4 out_colour;

void main()
{
    if (MLAB_HELPER_INVOCATION) {
        out_colour = vec4(0.0);
        return;
    }
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint count = imageLoad(mlab_counts, pixel).x;
    uint n = min(count, mlab_k);
    uint base = mlab_base(pixel);
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    for (uint i = 0u; i < n; ++i) {
        vec4 layer = mlab_colour(texelFetch(mlab_layers_texture, int(base + i)));
        colour += transmittance * layer.rgb;
        transmittance *= layer.a;
    }
    if (count > 0u) {
        atomicMax(mlab_counters[OIT_MLAB_COUNTER_MAX_LIST], count);
        atomicAdd(mlab_counters[OIT_MLAB_COUNTER_NONEMPTY_PIXELS], 1u);
        atomicAdd(mlab_counters[OIT_MLAB_COUNTER_RESOLVED], count);
    }
    out_colour = vec4(colour + transmittance * u_background, 1.0);
}
