// peel.frag: one depth-peeling layer (geometry pass, depth test LESS).
// Layers follow (depth, triangle index), the order every exact algorithm and
// the reference composite in, with the depth from oit_canonical_depth()
// (common/canonical_depth.glsl: coincident faces tie exactly). A fragment is a
// candidate if it comes after the previous layer's (depth, triangle): behind
// its depth, or at exactly its depth (read with texelFetch from a 32-bit float
// texture and compared with the same oit_canonical_depth() that wrote it) with
// a larger triangle index. Among the candidates the depth test LESS keeps the
// nearest, and among equal depths the first drawn, which is the lowest
// triangle: GL applies the depth test in primitive order, and the model is one
// draw call in triangle order. So coincident faces are peeled one after the
// other instead of all but one being lost, as in plain depth peeling. The
// winner's triangle index goes to the tie target for the next pass.
// With DP_NEIGHBOURS defined (alg_dp.c builds it so for curvature, dist-curv)
// it also writes the layer's normal and component for blend_curvature.frag.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#ifdef DP_NEIGHBOURS
#include "common/octahedral.glsl"
#endif

layout(location = OIT_UNIFORM_DP_HAS_PREVIOUS) uniform int has_previous;
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D previous_depth;
layout(binding = OIT_TEXUNIT_TIE_PREVIOUS) uniform usampler2D previous_tie;

layout(location = 0) out vec4 out_layer; // premultiplied colour, alpha
#ifdef DP_NEIGHBOURS
layout(location = 1) out uvec4 out_normal; // octahedral normal, component + 1
#endif
layout(location = OIT_DP_TIE_LOCATION) out uint out_tie; // triangle index

void main()
{
    float z = oit_canonical_depth();
    if (has_previous != 0) {
        ivec2 pixel = ivec2(gl_FragCoord.xy);
        float previous = texelFetch(previous_depth, pixel, 0).r;
        if (z < previous ||
            (z == previous && uint(gl_PrimitiveID) <= texelFetch(previous_tie, pixel, 0).r))
            discard;
    }
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    gl_FragDepth = z; // stored exactly as compared in the next pass
    out_tie = uint(gl_PrimitiveID);
#ifdef DP_NEIGHBOURS
    // curvature sets the opacity later: straight colour and the local factor
    out_layer = vec4(colour.rgb, oit_local_alpha(1.0, v_component, v_section_cap, v_eye_position));
    out_normal = uvec4(oit_pack_normal(v_eye_normal), v_component + 1u, 0u, 0u);
#else
    if (u_distance_mode >= 0) // distance modulation: straight colour and the local factor
        out_layer = vec4(colour.rgb, oit_local_alpha(1.0, v_component, v_section_cap, v_eye_position));
    else
        out_layer = vec4(colour.rgb * colour.a, colour.a);
#endif
}
