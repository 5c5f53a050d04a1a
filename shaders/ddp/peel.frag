// peel.frag: one dual depth peeling pass (no depth test). Reads the (-near, far)
// of the layers left and, per fragment:
//   outside [near, far]    already peeled: discard
//   strictly inside        left for later: its (-z, z) goes to the next min-max
//   z == near              front layer: blended under the front accumulation
//   z == far (> near)      back layer: blended under this pass's back layer
// Outputs a fragment does not use are 0, which MAX and the under-blending
// ignore. Every fragment at exactly the near (far) depth is peeled in the same
// pass and blended in drawing order, so coplanar fragments are all kept.
// Depths are compared exactly: texelFetch of 32-bit floats written from
// oit_canonical_depth() (common/canonical_depth.glsl), the same arithmetic in
// every program.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"

layout(location = OIT_UNIFORM_DDP_PEEL_BACK) uniform int peel_back;
layout(binding = OIT_TEXUNIT_DEPTH_MINMAX) uniform sampler2D minmax;

layout(location = 0) out vec2 out_minmax;
layout(location = 1) out vec4 out_front;
layout(location = 2) out vec4 out_back;

void main()
{
    float z = oit_canonical_depth();
    vec2 left = texelFetch(minmax, ivec2(gl_FragCoord.xy), 0).xy;
    float near = -left.x, far = left.y;
    if (z < near || z > far)
        discard;
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    out_minmax = vec2(-1.0e30); // loses every MAX
    out_front = vec4(0.0);
    out_back = vec4(0.0);
    vec4 premultiplied = vec4(colour.rgb * colour.a, colour.a);
    if (u_distance_mode >= 0) // distance modulation: straight colour and the local factor
        premultiplied = vec4(colour.rgb, oit_local_alpha(1.0, v_component, v_section_cap, v_eye_position));
    if (z == near) {
        out_front = premultiplied;
    } else if (z == far) {
        if (peel_back == 0)
            discard; // the layer limit is reached: this layer stays unpeeled
        out_back = premultiplied;
    } else {
        out_minmax = vec2(-z, z);
    }
}
