// wavelet/transmittance.frag: the "transmittance" pass (depth test off, additive
// blending into an rgba32f target), built once per rank (WAVELET_RANK, as
// coefficients.frag). Every fragment reads its pixel's coefficients, takes its
// own step's out (W3), reconstructs the absorbance in front of its depth (W4)
// and adds (T a c, T a), T = exp(-A~): the sums of W5.
#include "wavelet/common.glsl"

// target t of the coefficients at unit OIT_TEXUNIT_WAVELET_COEFFICIENTS + t
layout(binding = OIT_TEXUNIT_WAVELET_COEFFICIENTS) uniform sampler2D wavelet_coefficients[WAVELET_TARGETS];

layout(location = 0) out vec4 out_accumulation;

// The mean of the projected absorbance over bin b (W2): phi's coefficient and,
// per level j, the one wavelet whose support holds the bin, +-2^{j/2} times its
// coefficient (+ in the first half of its support, - in the second).
float wavelet_bin_mean(float c[WAVELET_COEFFICIENTS], int b)
{
    float mean = c[0];
    for (int j = 0; j <= WAVELET_RANK; ++j) {
        int k = b >> (WAVELET_RANK + 1 - j);
        float sign = ((b >> (WAVELET_RANK - j)) & 1) == 0 ? 1.0 : -1.0;
        mean += sign * exp2(0.5 * float(j)) * c[(1 << j) + k];
    }
    return mean;
}

// W4: the others' absorbance in front of depth s from their coefficients
float wavelet_absorbance(float c[WAVELET_COEFFICIENTS], float s)
{
    float x = s * float(WAVELET_COEFFICIENTS);
    int b = min(int(floor(x)), WAVELET_COEFFICIENTS - 1);
    float f = clamp(x - float(b), 0.0, 1.0);
    float before = b > 0 ? wavelet_bin_mean(c, b - 1) : 0.0;
    return mix(before, wavelet_bin_mean(c, b), f);
}

void main()
{
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) add nothing
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float s = wavelet_depth();
    float own[WAVELET_COEFFICIENTS];
    wavelet_step(oit_optical_depth(colour.a), s, own);
    float c[WAVELET_COEFFICIENTS];
    for (int t = 0; t < WAVELET_TARGETS; ++t) {
        vec4 sums = texelFetch(wavelet_coefficients[t], pixel, 0);
        for (int i = 0; i < 4; ++i)
            c[4 * t + i] = sums[i] - own[4 * t + i];
    }
    // the others' absorbance is >= 0 in exact arithmetic (every bin mean of a sum of
    // non-negative steps is); the clamp keeps rounding from making T > 1
    float transmittance = clamp(exp(-wavelet_absorbance(c, s)), 0.0, 1.0);
    out_accumulation = vec4(colour.rgb * colour.a, colour.a) * transmittance;
}
