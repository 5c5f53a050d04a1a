// blend_distance.frag: depth peeling with the distance modulation. A layer's
// opacity is its distance along the ray to the next layer, so layer k-1 is
// blended only after layer k has been peeled (delayed by one layer):
//   alpha = saturate(|eye depth(k) - eye depth(k-1)| / norm) * local factor,
// 0 where layer k-1 is the pixel's last (as ib and the reference). Hands the
// premultiplied colour to the under-blender. Full-screen pass.
// With DISTANCE_MAX defined it writes the distance instead (MAX-blended into an
// R32F target), the first sweep that finds the frame's largest distance.
#include "common/oit_shared.h"
#include "common/local_modulation.glsl"

layout(binding = OIT_TEXUNIT_PEEL_LAYER) uniform sampler2D layer_colour;     // k-1: rgb, local factor
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D layer_depth;  // k-1
layout(binding = OIT_TEXUNIT_PEEL_NEXT_LAYER) uniform sampler2D next_colour; // k: a > 0 where it exists
layout(binding = OIT_TEXUNIT_DEPTH_NEXT) uniform sampler2D next_depth;       // k

layout(location = 0) out vec4 out_colour;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 layer = texelFetch(layer_colour, pixel, 0);
    bool has_next = texelFetch(next_colour, pixel, 0).a > 0.0;
    float distance = 0.0;
    if (layer.a > 0.0 && has_next)
        distance = abs(oit_eye_depth(gl_FragCoord.xy, texelFetch(next_depth, pixel, 0).r) -
                       oit_eye_depth(gl_FragCoord.xy, texelFetch(layer_depth, pixel, 0).r));
#ifdef DISTANCE_MAX
    out_colour = vec4(distance, 0.0, 0.0, 0.0);
#else
    float alpha = oit_distance_alpha(distance) * layer.a;
    out_colour = vec4(layer.rgb * alpha, alpha);
#endif
}
