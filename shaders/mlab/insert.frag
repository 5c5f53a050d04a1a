// insert.frag: multi-layer alpha blending's geometry pass (depth test and colour
// writes off; Salvi & Vaidyanathan 2014). Each fragment with alpha > 0 becomes a
// layer (premultiplied colour, transmittance 1 - a, depth key, triangle) and is
// inserted into its pixel's k layers in (depth, triangle) order; when all k are
// taken, the last two of the k + 1 are merged into one:
//     c = c_near + t_near * c_far,   t = t_near * t_far,   key = the near one's.
//
// llvmpipe has no fragment shader interlock, so the read-modify-write of a
// pixel's layers runs under a per-pixel spin lock (imageAtomicCompSwap on an
// r32ui image). The SIMD-safe form: every lane loops until it is done; a lane
// runs the critical section only inside the branch where its own compare-swap
// took the lock (lanes of one SIMD group never wait on each other's release, so
// the group cannot deadlock); memoryBarrier() makes the layer and count writes
// visible before the release. The loop is capped at OIT_MLAB_LOCK_TRIES (llvmpipe
// ends any shader loop after 65535 iterations without a word); a fragment that
// reaches the cap is counted (OIT_MLAB_COUNTER_GAVE_UP) and the frame fails.
// Ordering: insertion is atomic per pixel, in the order the fragments arrive,
// which a GPU does not fix; docs/algorithms.md says what that means for the result.
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "mlab/mlab_layers.glsl"

layout(binding = OIT_IMAGE_MLAB_LOCK, r32ui) coherent uniform uimage2D mlab_locks;

// (depth, triangle) order; a merged layer's key is its nearer part's
bool mlab_in_front(uvec4 a, uvec4 b)
{
    float depth_a = uintBitsToFloat(a.z), depth_b = uintBitsToFloat(b.z);
    return depth_a < depth_b || (depth_a == depth_b && a.w < b.w);
}

// near over far: the layer that composites as the two would, with the near one's key
uvec4 mlab_merge(uvec4 near, uvec4 far)
{
    vec4 a = mlab_colour(near), b = mlab_colour(far);
    return mlab_pack(a.rgb + a.a * b.rgb, a.a * b.a, uintBitsToFloat(near.z), near.w);
}

// The critical section: insert `fragment` into the pixel's layers.
void mlab_insert(ivec2 pixel, uvec4 fragment)
{
    uint count = imageLoad(mlab_counts, pixel).x;
    uint n = min(count, mlab_k);
    uint base = mlab_base(pixel);
    uint p = 0u; // layers in front of the fragment: it goes at p
    while (p < n && mlab_in_front(mlab_layers[base + p], fragment))
        ++p;
    if (n < mlab_k) {
        for (uint i = n; i > p; --i)
            mlab_layers[base + i] = mlab_layers[base + i - 1u];
        mlab_layers[base + p] = fragment;
    } else if (p == mlab_k) { // behind every layer: merged into the last
        mlab_layers[base + mlab_k - 1u] = mlab_merge(mlab_layers[base + mlab_k - 1u], fragment);
    } else { // the k + 1 entries' last two: (layer k - 2 or the fragment, layer k - 1)
        uvec4 near = p + 1u == mlab_k ? fragment : mlab_layers[base + mlab_k - 2u];
        uvec4 merged = mlab_merge(near, mlab_layers[base + mlab_k - 1u]);
        if (p + 1u < mlab_k) {
            for (uint i = mlab_k - 2u; i > p; --i)
                mlab_layers[base + i] = mlab_layers[base + i - 1u];
            mlab_layers[base + p] = fragment;
        }
        mlab_layers[base + mlab_k - 1u] = merged;
    }
    imageStore(mlab_counts, pixel, uvec4(count + 1u, 0u, 0u, 0u));
}

void main()
{
    if (MLAB_HELPER_INVOCATION)
        return;
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        return; // hidden parts (opacity 0) are not stored
    uvec4 fragment = mlab_pack(colour.rgb * colour.a, 1.0 - colour.a, oit_canonical_depth(),
                               uint(gl_PrimitiveID));
    if (atomicAdd(mlab_counters[OIT_MLAB_COUNTER_FRAGMENTS], 1u) == 0xFFFFFFFFu)
        atomicAdd(mlab_counters[OIT_MLAB_COUNTER_FRAGMENTS_WRAPS], 1u);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    bool done = false;
    for (int tries = 0; tries < OIT_MLAB_LOCK_TRIES && !done; ++tries) {
        if (imageAtomicCompSwap(mlab_locks, pixel, 0u, 1u) == 0u) {
            mlab_insert(pixel, fragment);
            memoryBarrier(); // the layers and the count, before the lock is seen free
            imageAtomicExchange(mlab_locks, pixel, 0u);
            done = true;
        }
    }
    if (!done)
        atomicAdd(mlab_counters[OIT_MLAB_COUNTER_GAVE_UP], 1u);
}
