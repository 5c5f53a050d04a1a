// peel.frag: one depth-peeling layer (geometry pass, depth test LESS).
// Fragments at or in front of the previous layer's depth are discarded; the
// depth test keeps the nearest of the rest. The previous depth is read with
// texelFetch from a 32-bit float depth texture and compared with
// gl_FragCoord.z, the very value the previous pass stored, so no layer is
// skipped or peeled twice. Fragments at exactly the previous depth (coplanar
// with the kept one) are lost: the known limit of plain depth peeling.
// With DP_NEIGHBOURS defined (dp/peel_neighbours.frag: curvature, dist-curv)
// it also writes the layer's normal and component for blend_curvature.frag.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#ifdef DP_NEIGHBOURS
#include "common/octahedral.glsl"
#endif

layout(location = OIT_UNIFORM_DP_HAS_PREVIOUS) uniform int has_previous;
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D previous_depth;

layout(location = 0) out vec4 out_layer; // premultiplied colour, alpha
#ifdef DP_NEIGHBOURS
layout(location = 1) out uvec4 out_normal; // octahedral normal, component + 1
#endif

void main()
{
    if (has_previous != 0 &&
        gl_FragCoord.z <= texelFetch(previous_depth, ivec2(gl_FragCoord.xy), 0).r)
        discard;
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    gl_FragDepth = gl_FragCoord.z; // stored exactly as compared in the next pass
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
