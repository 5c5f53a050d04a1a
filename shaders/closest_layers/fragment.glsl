// fragment.glsl: what the select and store passes of kbuffer and hybrid ask of
// the current fragment (geometry passes fed by common/geometry.vert): whether
// it is a layer at all, its sort key and its colour. Both passes compute them
// with the same code, so they agree on which fragments exist and on their keys
// (canonical depth is `precise`: the same bits in every program).
#ifndef CLOSEST_LAYERS_FRAGMENT_GLSL
#define CLOSEST_LAYERS_FRAGMENT_GLSL

#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "common/closest_layers.glsl"

// The fragment's key (canonical depth bits), or OIT_CLOSEST_EMPTY_KEY when it is
// no layer: a helper invocation, or opacity 0 (hidden parts are not stored, as in ll).
uint closest_layers_fragment_key()
{
    if (CLOSEST_LAYERS_HELPER_INVOCATION || !(oit_fragment_alpha() > 0.0))
        return OIT_CLOSEST_EMPTY_KEY;
    return closest_layers_key(oit_canonical_depth());
}

// The store pass: true if the fragment took a slot of the core (or is no layer);
// false if it belongs to the tail, with its shaded colour (straight alpha) in `colour`.
bool closest_layers_store(out vec4 colour)
{
    colour = vec4(0.0);
    uint key = closest_layers_fragment_key();
    if (key == OIT_CLOSEST_EMPTY_KEY)
        return true;
    colour = oit_shade_fragment();
    return closest_layers_claim(ivec2(gl_FragCoord.xy), key, uint(gl_PrimitiveID) + 1u, colour);
}

#endif
