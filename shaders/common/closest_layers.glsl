// closest_layers.glsl: the k closest layers of every pixel, shared by kbuffer
// and hybrid (src/core/closest_layers.c). Buffers and slot layout: oit_shared.h.
//
// select (every fragment):   closest_layers_insert(key) puts the fragment's key
//                            among the pixel's k smallest, lock-free (atomicMin loop)
// store (every fragment):    closest_layers_claim(key, owner, colour) stores it in a
//                            slot with its key, or says it belongs to the tail
// compose (every pixel):     closest_layers_compose() sorts the claimed slots by
//                            (key, triangle), composites them front to back and puts
//                            the tail, which each algorithm resolves, behind
// Nothing here reads vertex inputs, so full-screen passes include it as they are.
#ifndef CLOSEST_LAYERS_GLSL
#define CLOSEST_LAYERS_GLSL

#include "common/oit_shared.h"
#include "common/frame.glsl"

// Helper invocations (the extra lanes of 2x2 quads) must not touch memory, and
// llvmpipe lets their atomics through (see ll/ll_nodes.glsl): every pass returns
// early in them. The shader's first line enables GL_ARB_ES3_1_compatibility.
#ifdef GL_ARB_ES3_1_compatibility
#define CLOSEST_LAYERS_HELPER_INVOCATION gl_HelperInvocation
#else
#define CLOSEST_LAYERS_HELPER_INVOCATION false
#endif

layout(location = OIT_UNIFORM_CLOSEST_LAYERS) uniform int u_layers; // k

layout(std430, binding = OIT_SSBO_CLOSEST_SLOTS) coherent buffer closest_slot_buffer {
    uvec4 closest_slots[]; // key, owner (triangle + 1), packUnorm2x16(r, g), packUnorm2x16(b, a)
};
layout(std430, binding = OIT_SSBO_CLOSEST_TAIL_COUNTS) buffer closest_tail_count_buffer {
    uint closest_tail_counts[];
};
layout(std430, binding = OIT_SSBO_CLOSEST_COUNTERS) buffer closest_counter_buffer {
    uint closest_counters[OIT_CLOSEST_COUNTER_COUNT];
};

uint closest_layers_pixel(ivec2 pixel) { return uint(pixel.y * u_viewport.x + pixel.x); }
uint closest_layers_first_slot(ivec2 pixel) { return closest_layers_pixel(pixel) * uint(u_layers); }

// The sort key of a canonical depth in [0, 1]: its bits, which order as the
// floats do for non-negative ones (-0 is taken as +0, which it equals).
uint closest_layers_key(float depth) { return depth <= 0.0 ? 0u : floatBitsToUint(depth); }

// select: insert `key` into the pixel's ascending k keys. Each step leaves the
// smaller of the two in slot i and carries the larger on; an empty slot ends
// it. Whatever the interleaving with other fragments of the pixel, every slot
// only ever decreases, so once all fragments are in the slots hold the k
// smallest keys of the pixel, ascending, duplicates (exact ties) included.
void closest_layers_insert(ivec2 pixel, uint key)
{
    uint first = closest_layers_first_slot(pixel);
    for (int i = 0; i < u_layers; ++i) {
        uint previous = atomicMin(closest_slots[first + uint(i)].x, key);
        if (previous == OIT_CLOSEST_EMPTY_KEY)
            return;
        key = max(key, previous);
    }
}

// store: claim one of the slots whose key is `key` for `owner` (triangle + 1)
// and store the colour there; false if the fragment is not among the k (its
// key is past the last slot's) or lost every tied slot to fragments with the
// same key: it belongs to the tail. The keys are final here (the select pass
// and a barrier came before), so plain reads see them.
bool closest_layers_claim(ivec2 pixel, uint key, uint owner, vec4 colour)
{
    uint first = closest_layers_first_slot(pixel);
    for (int i = 0; i < u_layers; ++i) {
        uint slot = first + uint(i);
        uint slot_key = closest_slots[slot].x;
        if (slot_key > key)
            break; // ascending: no later slot has it
        if (slot_key == key && atomicCompSwap(closest_slots[slot].y, 0u, owner) == 0u) {
            closest_slots[slot].zw = uvec2(packUnorm2x16(colour.rg), packUnorm2x16(colour.ba));
            atomicAdd(closest_counters[OIT_CLOSEST_COUNTER_CORE], 1u);
            return true;
        }
    }
    atomicAdd(closest_counters[OIT_CLOSEST_COUNTER_TAIL], 1u);
    atomicAdd(closest_tail_counts[closest_layers_pixel(pixel)], 1u);
    return false;
}

// compose: the pixel's claimed slots sorted by (key, triangle), composited front
// to back in float as ll does, `tail` behind them (premultiplied: rgb = its
// colour times its coverage, a = its coverage; each algorithm's compose.frag
// resolves it), the background behind all. Also counts the list lengths
// (core + tail) for the statistics.
vec3 closest_layers_compose(ivec2 pixel, vec4 tail)
{
    uint first = closest_layers_first_slot(pixel);
    uint keys[OIT_APPROX_LAYERS_MAX];
    uint owners[OIT_APPROX_LAYERS_MAX];
    uvec2 colours[OIT_APPROX_LAYERS_MAX];
    int count = 0;
    for (int i = 0; i < u_layers; ++i) {
        uvec4 slot = closest_slots[first + uint(i)];
        if (slot.x == OIT_CLOSEST_EMPTY_KEY)
            break; // ascending: the rest are empty too
        if (slot.y == 0u)
            continue; // a key nobody claimed (cannot happen while both passes agree on alpha)
        // insertion sort by (key, owner): the keys come ascending, so only the
        // owners of tied keys move (they claimed in whatever order they ran)
        int j = count;
        for (; j > 0; --j) {
            if (keys[j - 1] < slot.x || (keys[j - 1] == slot.x && owners[j - 1] < slot.y))
                break;
            keys[j] = keys[j - 1];
            owners[j] = owners[j - 1];
            colours[j] = colours[j - 1];
        }
        keys[j] = slot.x;
        owners[j] = slot.y;
        colours[j] = slot.zw;
        ++count;
    }
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    for (int i = 0; i < count; ++i) {
        vec4 fragment = vec4(unpackUnorm2x16(colours[i].x), unpackUnorm2x16(colours[i].y));
        colour += transmittance * fragment.a * fragment.rgb;
        transmittance *= 1.0 - fragment.a;
    }

    uint length = uint(count) + closest_tail_counts[closest_layers_pixel(pixel)];
    if (length > 0u) {
        atomicMax(closest_counters[OIT_CLOSEST_COUNTER_MAX_LIST], length);
        atomicAdd(closest_counters[OIT_CLOSEST_COUNTER_NONEMPTY_PIXELS], 1u);
        uint bin = min(length, uint(OIT_CLOSEST_HISTOGRAM_BINS - 1));
        atomicAdd(closest_counters[OIT_CLOSEST_COUNTER_HISTOGRAM + bin], 1u);
    }
    return colour + transmittance * (tail.rgb + (1.0 - tail.a) * u_background);
}

#endif
