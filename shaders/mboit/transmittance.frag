// mboit/transmittance.frag: the "transmittance" pass (depth test off, additive
// blending into an rgba32f target), built once per variant (MBOIT_VARIANT, as
// moments.frag).
// Every fragment reads its pixel's moments (the "moments" pass), reconstructs
// the transmittance T in front of its own depth (E4 in mboit/common.glsl) and
// adds (T a c, T a): the sums of E5.
#include "mboit/common.glsl"
#if MBOIT_VARIANT == OIT_MBOIT_TRIG3
#include "mboit/trig.glsl"
#else
#include "mboit/power.glsl"
#endif

layout(binding = OIT_TEXUNIT_MBOIT_B0) uniform sampler2D mboit_b0;
layout(binding = OIT_TEXUNIT_MBOIT_MOMENTS) uniform sampler2D mboit_moments;
#if MBOIT_VARIANT != OIT_MBOIT_POWER4
layout(binding = OIT_TEXUNIT_MBOIT_EXTRA) uniform sampler2D mboit_extra;
#endif

layout(location = 0) out vec4 out_accumulation;

// T(s) in front of the canonical depth s at the pixel, from its moments
float mboit_transmittance(ivec2 pixel, float s)
{
    float b0 = texelFetch(mboit_b0, pixel, 0).r;
    if (b0 <= 0.0)
        return 1.0; // nothing absorbs here (cannot happen: this fragment added b0 > 0)
    vec4 moments = texelFetch(mboit_moments, pixel, 0) / b0;
#if MBOIT_VARIANT != OIT_MBOIT_POWER4
    vec2 extra = texelFetch(mboit_extra, pixel, 0).rg / b0;
#endif
#if MBOIT_VARIANT == OIT_MBOIT_TRIG3
    vec2 m[4] = vec2[4](vec2(1.0, 0.0), moments.xy, moments.zw, extra);
    float absorbance = mboit_trig_absorbance(m, mboit_phase(s));
#elif MBOIT_VARIANT == OIT_MBOIT_POWER6
    float m[7] = float[7](1.0, moments.x, moments.y, moments.z, moments.w, extra.x, extra.y);
    float absorbance = mboit_power_absorbance(m, mboit_power_warp(s));
#else
    float m[7] = float[7](1.0, moments.x, moments.y, moments.z, moments.w, 0.0, 0.0);
    float absorbance = mboit_power_absorbance(m, mboit_power_warp(s));
#endif
    // E4: exp of minus the absorbance; the bounds are within [0, b0] in exact
    // arithmetic, the clamp keeps rounding from making T > 1 or negative
    return clamp(exp(-b0 * absorbance), 0.0, 1.0);
}

void main()
{
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) add nothing
    float transmittance = mboit_transmittance(ivec2(gl_FragCoord.xy), mboit_depth());
    out_accumulation = vec4(colour.rgb * colour.a, colour.a) * transmittance;
}
