// mlab_layers.glsl: multi-layer alpha blending's per-pixel layers, shared by the
// insert and resolve passes. Layout and bindings: oit_shared.h (mlab section).
#ifndef MLAB_LAYERS_GLSL
#define MLAB_LAYERS_GLSL

#include "common/oit_shared.h"
#include "common/frame.glsl"

// Helper invocations must not write memory (llvmpipe lets their stores through
// and their reads are garbage; see ll/ll_nodes.glsl). The shader enables
// GL_ARB_ES3_1_compatibility in its first line for gl_HelperInvocation.
#ifdef GL_ARB_ES3_1_compatibility
#define MLAB_HELPER_INVOCATION gl_HelperInvocation
#else
#define MLAB_HELPER_INVOCATION false
#endif

layout(location = OIT_UNIFORM_MLAB_LAYERS) uniform uint mlab_k; // layers per pixel, 1..64

// The layers, k per pixel, front to back. `coherent`: the insert reads and
// writes them inside a pixel's critical section, and the next fragment of that
// pixel (another invocation, maybe another core) must see the writes.
layout(std430, binding = OIT_SSBO_MLAB_LAYERS) coherent buffer mlab_layer_buffer {
    uvec4 mlab_layers[];
};
layout(std430, binding = OIT_SSBO_MLAB_COUNTERS) buffer mlab_counter_buffer {
    uint mlab_counters[OIT_MLAB_COUNTER_COUNT];
};
layout(binding = OIT_IMAGE_MLAB_COUNT, r32ui) coherent uniform uimage2D mlab_counts;

// The index of the pixel's first layer.
uint mlab_base(ivec2 pixel)
{
    return (uint(pixel.y) * uint(u_viewport.x) + uint(pixel.x)) * mlab_k;
}

uvec4 mlab_pack(vec3 premultiplied, float transmittance, float depth, uint triangle)
{
    return uvec4(packUnorm2x16(premultiplied.rg), packUnorm2x16(vec2(premultiplied.b, transmittance)),
                 floatBitsToUint(depth), triangle);
}

// rgb premultiplied colour, a transmittance
vec4 mlab_colour(uvec4 layer)
{
    return vec4(unpackUnorm2x16(layer.x), unpackUnorm2x16(layer.y));
}

#endif
