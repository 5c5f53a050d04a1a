// blend_distance.frag: dual depth peeling with the distance modulation, the
// full-screen pass after each peel pass (docs/modulation.md). The peel pass
// stored this pass's front and back layers unblended (rgb, local factor); their
// opacity needs the next fragment along the ray, known only now:
// - the front layer (at near) is followed by the nearest fragment left for
//   later (the next min-max target's near), or, if none is left, by this
//   pass's back layer (at far, if far > near), or else by the back layer of
//   an earlier pass (previous_far);
// - the back layer (at far) is followed by the previous pass's back layer
//   (previous_far, < 0 if there was none: then it is the pixel's last).
// alpha = saturate(|eye depth(next) - eye depth(this)| / norm) * local factor.
// Outputs: 0 front contribution (under-blended into the front accumulation),
// 1 back layer (rgb = a c, a = 1 - a: blended over the back accumulation),
// 2 the far depth for the next pass. With DISTANCE_MAX: 0 the larger distance
// (MAX-blended into R32F), 1 the far depth.
#include "common/oit_shared.h"
#include "common/local_modulation.glsl"

layout(binding = OIT_TEXUNIT_PEEL_NEXT_LAYER) uniform sampler2D front_layer; // rgb, local factor
layout(binding = OIT_TEXUNIT_PEEL_LAYER) uniform sampler2D back_layer;       // rgb, local factor
layout(binding = OIT_TEXUNIT_DEPTH_MINMAX) uniform sampler2D minmax;         // this pass: (-near, far)
layout(binding = OIT_TEXUNIT_DEPTH_NEXT) uniform sampler2D next_minmax;      // left for later
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D previous_far; // < 0: none

#ifdef DISTANCE_MAX
layout(location = 0) out vec4 out_distance;
layout(location = 1) out vec4 out_far;
#else
layout(location = 0) out vec4 out_front;
layout(location = 1) out vec4 out_back;
layout(location = 2) out vec4 out_far;
#endif

float eye_distance(float a, float b)
{
    return abs(oit_eye_depth(gl_FragCoord.xy, a) - oit_eye_depth(gl_FragCoord.xy, b));
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 front = texelFetch(front_layer, pixel, 0);
    vec4 back = texelFetch(back_layer, pixel, 0);
    vec2 range = texelFetch(minmax, pixel, 0).xy;
    float near = -range.x, far = range.y;
    vec2 later = texelFetch(next_minmax, pixel, 0).xy;
    float previous = texelFetch(previous_far, pixel, 0).r;
    bool has_back = back.a > 0.0;

    float front_distance = 0.0;
    if (front.a > 0.0) {
        if (-later.x <= later.y) // fragments left between near and far
            front_distance = eye_distance(-later.x, near);
        else if (has_back)
            front_distance = eye_distance(far, near);
        else if (previous >= 0.0) // the back layers peeled before
            front_distance = eye_distance(previous, near);
    }
    float back_distance = 0.0;
    if (has_back && previous >= 0.0)
        back_distance = eye_distance(previous, far);
    float far_out = has_back ? far : previous;
#ifdef DISTANCE_MAX
    out_distance = vec4(max(front_distance, back_distance), 0.0, 0.0, 0.0);
    out_far = vec4(far_out, 0.0, 0.0, 0.0);
#else
    float front_alpha = oit_distance_alpha(front_distance) * front.a;
    float back_alpha = oit_distance_alpha(back_distance) * back.a;
    out_front = vec4(front.rgb * front_alpha, front_alpha);
    out_back = vec4(back.rgb * back_alpha, 1.0 - back_alpha);
    out_far = vec4(far_out, 0.0, 0.0, 0.0);
#endif
}
