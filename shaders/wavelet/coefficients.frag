// wavelet/coefficients.frag: the "coefficients" pass (depth test off, additive
// blending into float targets), built once per rank (alg_wavelet.c defines
// WAVELET_RANK). Every fragment adds its optical depth -ln(1 - a) into b0 (r32f,
// for the composite's exact coverage) and the Haar coefficients of its
// absorbance step (W3 in wavelet/common.glsl) into N / 4 rgba32f targets.
#include "wavelet/common.glsl"

layout(location = OIT_WAVELET_TARGET_B0) out vec4 out_b0;
layout(location = OIT_WAVELET_TARGET_COEFFICIENTS) out vec4 out_coefficients[WAVELET_TARGETS];

void main()
{
    float alpha = oit_fragment_alpha();
    if (alpha <= 0.0)
        discard; // hidden parts (opacity 0) add nothing
    float optical_depth = oit_optical_depth(alpha);
    float c[WAVELET_COEFFICIENTS];
    wavelet_step(optical_depth, wavelet_depth(), c);
    out_b0 = vec4(optical_depth, 0.0, 0.0, 0.0);
    for (int t = 0; t < WAVELET_TARGETS; ++t)
        out_coefficients[t] = vec4(c[4 * t], c[4 * t + 1], c[4 * t + 2], c[4 * t + 3]);
}
