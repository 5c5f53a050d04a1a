// mboit/common.glsl: what both geometry passes of moment-based OIT share
// (Muenstermann, Krumpen, Klein & Peters, "Moment-Based Order-Independent
// Transparency", Proc. ACM CGIT 1(1), i3D 2018; "the paper" below).
// The including shader defines MBOIT_VARIANT (OIT_MBOIT_POWER4, _POWER6 or
// _TRIG3, oit_shared.h) first.
//
// The method, as equations E1..E5 (the labels are ours: the paper's own
// equation numbers could not be checked here, only its published shader code;
// docs/algorithms.md says more):
//  E1  T(z) = prod_{z_l < z} (1 - a_l): the transmittance in front of depth z,
//      multiplicative in the fragments, so it needs their order;
//  E2  A(z) = -ln T(z) = sum_{z_l < z} -ln(1 - a_l): the absorbance is additive:
//      the integral of the step "z_l < z" against the measure
//      Z = sum_l -ln(1 - a_l) delta(z_l) (each fragment's optical depth at its depth);
//  E3  b = sum_l -ln(1 - a_l) b(z_l), b(z) = (1, z, z^2, ...) (power moments) or
//      (1, e^{i p}, e^{2 i p}, ...) (trigonometric moments of the phase p(z)):
//      plain sums, so one additive pass in any order collects them; b0 is the
//      total optical depth and exp(-b0) = prod (1 - a_l) exactly;
//  E4  T(z) ~ exp(-b0 A*(z)), A*(z) the normalised absorbance in front of z
//      reconstructed from m = b / b0 (biased) between the bounds the moments
//      allow (mboit/power.glsl, mboit/trig.glsl);
//  E5  C = (sum_l T(z_l) a_l c_l) / (sum_l T(z_l) a_l) * (1 - exp(-b0)) + C_bg exp(-b0):
//      the composite, renormalised so that the coverage is the exact 1 - exp(-b0)
//      (mboit/compose.frag).
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"
#include "common/optical_depth.glsl"

#ifndef MBOIT_VARIANT
#error "define MBOIT_VARIANT before including mboit/common.glsl"
#endif

const float MBOIT_PI = 3.14159265358979;

// The optical depth and its clamp (opacity at most 1 - e^-10) are
// common/optical_depth.glsl's, shared with wavelet.

// The paper's overestimation strength (the published code
// and its ports use 0.25): the reconstruction gives the weight of the support point at the
// queried depth itself this share, between the lower bound of the absorbance
// (0: the fragment is not in front of itself) and the upper bound (1).
const float MBOIT_OVERESTIMATION = 0.25;

// The paper's moment bias for 32-bit float moments (the values of its
// supplementary document, which the published code and its OpenGL port use):
// the biased moments are (1 - bias) b + bias b*, with b* the moments of a
// distribution that makes the moment matrix safely positive definite (the
// paper's biasing; Peters & Klein 2015 for power moments).
#if MBOIT_VARIANT == OIT_MBOIT_POWER4
const float MBOIT_BIAS = 5e-7;
#elif MBOIT_VARIANT == OIT_MBOIT_POWER6
const float MBOIT_BIAS = 5e-6;
#elif MBOIT_VARIANT == OIT_MBOIT_TRIG3
const float MBOIT_BIAS = 8e-7;
#else
#error "MBOIT_VARIANT is not one of OIT_MBOIT_POWER4, _POWER6, _TRIG3"
#endif

// Trigonometric moments: the wrapping zone (0.1 pi in the paper's
// code). Depths map to phases on the unit circle, and the far end must
// not meet the near end: depths use [0, 2 pi - zone], and a reconstructed
// support point in the zone (2 pi - zone, 2 pi) counts as partly in front of
// everything, ramping from 0 at the far end to 1 where it wraps to the front.
const float MBOIT_WRAPPING_ZONE = 0.1 * MBOIT_PI;

// The fragment's depth: the canonical depth s in [0, 1] (common/canonical_depth.glsl),
// linear in eye depth between the near and far planes. The paper warps
// log(view depth) between the scene's nearest and farthest depth instead;
// here the default camera's near and far planes already hug the model's
// bounding sphere, s is the same in both passes bit for bit, and it is the
// depth every exact algorithm sorts by.
float mboit_depth()
{
    return oit_canonical_depth();
}

// Power moments: s warped linearly to [-1, 1], where the paper's bias vectors
// and bias values for power moments are set.
float mboit_power_warp(float s)
{
    return 2.0 * s - 1.0;
}

// Trigonometric moments: s warped to the phase s * (2 pi - zone) in
// [0, 2 pi - zone] (depth -> e^{i phase}).
float mboit_phase(float s)
{
    return s * (2.0 * MBOIT_PI - MBOIT_WRAPPING_ZONE);
}

// The optical depth -ln(1 - a) of a fragment of opacity a (> 0), clamped
// (common/optical_depth.glsl).
float mboit_optical_depth(float alpha)
{
    return oit_optical_depth(alpha);
}
