// peel_key.frag: the first of a layer's two geometry passes (depth only, depth
// test LESS): of the fragments after the previous layer in (depth, triangle)
// order, the nearest depth. peel.frag then picks the lowest triangle at that
// depth; two passes, because one depth test cannot order by two keys.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "dp/peel_order.glsl"

void main()
{
    float z = oit_canonical_depth();
    if (!dp_behind_previous(z))
        discard;
    if (oit_shade_fragment().a <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    gl_FragDepth = z; // stored exactly as compared in the next passes
}
