// wavelet/common.glsl: what both geometry passes of wavelet transparency share
// (Aizenshtein, Smal & McGuire, "Wavelet Transparency", 2022; "the paper").
// The including shader defines WAVELET_RANK (1..OIT_WAVELET_RANK_MAX) first.
//
// The method, as equations W1..W5 (our labels):
//  W1  A(z) = sum_{z_l < z} -ln(1 - a_l): the absorbance in front of depth z in
//      [0, 1] (T(z) = exp(-A(z)), as mboit's E1, E2): a sum of steps, one per
//      fragment, of height its optical depth, at its depth;
//  W2  its projection onto the Haar basis of rank R on [0, 1): the scaling
//      function phi = 1 and the wavelets psi_jk(z) = 2^{j/2} psi(2^j z - k),
//      psi = +1 on [0, 1/2), -1 on [1/2, 1), for the levels j = 0..R, k < 2^j:
//      N = 2^{R+1} coefficients (1 + 1 + 2 + ... + 2^R), which span the functions
//      constant on the N bins [b / N, (b + 1) / N): the projection is A's mean
//      over each bin;
//  W3  the coefficients are linear in A, so every fragment adds those of its own
//      step a H(z - s) in one additive pass in any order:
//        phi:   a (1 - s)
//        psi_jk: k = floor(2^j s), u = 2^j s - k:  -a 2^{-j/2} min(u, 1 - u)
//      (the integral of psi_jk from s to 1; 0 for the other k of level j);
//  W4  the absorbance in front of a fragment at depth s, in bin b at offset
//      f = N s - b: the bin means of the others' absorbance (the fragment's own
//      step subtracted: it is not in front of itself), interpolated linearly
//      from the previous bin's mean at the start of bin b to bin b's at its end:
//        A~(s) = (1 - f) mean_{b-1} + f mean_b,  mean_{-1} = 0 (nothing in front of 0);
//      a fragment in front, in an earlier bin, is in both means whole, one
//      behind, in a later bin, in neither: A~ is exact for them, and errs only
//      through the others in the fragment's own bin, which count by
//      f (1 - their offset) instead of 0 or 1;
//  W5  the composite: mboit's E5, (sum T a c) / (sum T a) (1 - exp(-b0)) +
//      C_bg exp(-b0), with b0 the exact total optical depth (mboit/compose.frag).
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "common/optical_depth.glsl"

#ifndef WAVELET_RANK
#error "define WAVELET_RANK before including wavelet/common.glsl"
#endif
#if WAVELET_RANK < 1 || WAVELET_RANK > OIT_WAVELET_RANK_MAX
#error "WAVELET_RANK is outside 1..OIT_WAVELET_RANK_MAX"
#endif

// N, the coefficients (= bins), and the rgba32f targets that hold them (4 each)
#define WAVELET_COEFFICIENTS (2 << WAVELET_RANK)
#define WAVELET_TARGETS (WAVELET_COEFFICIENTS / 4)

// The fragment's depth: the canonical depth s in [0, 1], mboit's own
// (mboit_depth), so that both approximate the same function of the same depth.
float wavelet_depth()
{
    return oit_canonical_depth();
}

// W3: the Haar coefficients of the step a H(z - s) (index 0: phi; 2^j + k: psi_jk).
void wavelet_step(float a, float s, out float c[WAVELET_COEFFICIENTS])
{
    for (int i = 0; i < WAVELET_COEFFICIENTS; ++i)
        c[i] = 0.0;
    c[0] = a * (1.0 - s);
    for (int j = 0; j <= WAVELET_RANK; ++j) {
        float scaled = s * float(1 << j);
        float k = floor(scaled);
        float u = scaled - k;
        if (k < float(1 << j)) // s = 1: the step is past the end, every psi_jk gets 0
            c[(1 << j) + int(k)] = -a * exp2(-0.5 * float(j)) * min(u, 1.0 - u);
    }
}
