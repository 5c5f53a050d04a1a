// peel.frag: the second of a depth-peeling layer's geometry passes (depth test
// LESS). Of the fragments at the layer's depth (peel_key.frag found it; read
// with texelFetch from a 32-bit float texture and compared exactly with the
// same oit_canonical_depth() that wrote it) and after the previous layer in
// (depth, triangle) order, the depth test keeps the lowest triangle: its index
// is written as the depth (dp_encode_tie), and its colour lands in the layer
// target. So coincident faces are peeled one after the other in triangle
// order, as every exact algorithm and the reference composite them.
// With DP_NEIGHBOURS defined (dp/peel_neighbours.frag: curvature, dist-curv)
// it also writes the layer's normal and component for blend_curvature.frag.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "dp/peel_order.glsl"
#ifdef DP_NEIGHBOURS
#include "common/octahedral.glsl"
#endif

layout(binding = OIT_TEXUNIT_DEPTH_NEAREST) uniform sampler2D nearest_depth;

layout(location = 0) out vec4 out_layer; // premultiplied colour, alpha
#ifdef DP_NEIGHBOURS
layout(location = 1) out uvec4 out_normal; // octahedral normal, component + 1
#endif

void main()
{
    float z = oit_canonical_depth();
    if (z != texelFetch(nearest_depth, ivec2(gl_FragCoord.xy), 0).r || !dp_behind_previous(z))
        discard;
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    gl_FragDepth = dp_encode_tie(uint(gl_PrimitiveID));
#ifdef DP_NEIGHBOURS
    // curvature sets the opacity later: straight colour and the local factor
    out_layer = vec4(colour.rgb, oit_local_alpha(1.0, v_component, v_eye_position));
    out_normal = uvec4(oit_pack_normal(v_eye_normal), v_component + 1u, 0u, 0u);
#else
    if (u_distance_mode >= 0) // distance modulation: straight colour and the local factor
        out_layer = vec4(colour.rgb, oit_local_alpha(1.0, v_component, v_eye_position));
    else
        out_layer = vec4(colour.rgb * colour.a, colour.a);
#endif
}
