// mboit/moments.frag: the "moments" pass (depth test off, additive blending
// into float targets), built once per variant (alg_mboit.c defines
// MBOIT_VARIANT as OIT_MBOIT_POWER4, _POWER6 or _TRIG3). Every fragment
// adds its optical depth -ln(1 - a) times the moment vector of its warped
// depth (E3 in mboit/common.glsl: b = sum_l -ln(1 - a_l) b(z_l), accumulated
// by additive blending, its "single precision" variant without rasterizer
// ordered views): b0 alone in an r32f target, then
//   power4: (x, x^2, x^3, x^4)                         x = 2 s - 1
//   power6: (x, x^2, x^3, x^4) and (x^5, x^6)
//   trig3:  (e^{i p}, e^{2 i p}) and (e^{3 i p})        p = s (2 pi - zone)
#include "mboit/common.glsl"

layout(location = OIT_MBOIT_TARGET_B0) out vec4 out_b0;
layout(location = OIT_MBOIT_TARGET_MOMENTS) out vec4 out_moments;
#if MBOIT_VARIANT != OIT_MBOIT_POWER4
layout(location = OIT_MBOIT_TARGET_EXTRA) out vec4 out_extra;
#endif

void main()
{
    float alpha = oit_fragment_alpha();
    if (alpha <= 0.0)
        discard; // hidden parts (opacity 0) add nothing
    float optical_depth = mboit_optical_depth(alpha);
    float s = mboit_depth();
    out_b0 = vec4(optical_depth, 0.0, 0.0, 0.0);
#if MBOIT_VARIANT == OIT_MBOIT_TRIG3
    float phase = mboit_phase(s);
    // each power of e^{i p} from its own angle (no error compounding by products)
    out_moments = optical_depth * vec4(cos(phase), sin(phase), cos(2.0 * phase), sin(2.0 * phase));
    out_extra = optical_depth * vec4(cos(3.0 * phase), sin(3.0 * phase), 0.0, 0.0);
#else
    float x = mboit_power_warp(s);
    float x2 = x * x;
    out_moments = optical_depth * vec4(x, x2, x2 * x, x2 * x2);
#if MBOIT_VARIANT == OIT_MBOIT_POWER6
    out_extra = optical_depth * vec4(x2 * x2 * x, x2 * x2 * x2, 0.0, 0.0);
#endif
#endif
}
