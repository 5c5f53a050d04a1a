// optical_depth.glsl: the optical depth -ln(1 - a) of a fragment, what the
// additive passes of mboit and wavelet sum (the absorbance is additive where the
// transmittance, prod (1 - a), is multiplicative).
//
// Opacity is clamped below 1 so that the optical depth stays finite (ln 0 is
// undefined in GLSL): a <= 1 - e^-10, i.e. optical depth <= 10, as the MBOIT
// paper's shader code caps the absorbance at 10. An opaque surface then lets
// e^-10 = 4.5e-5 of what is behind it through: 0.012/255, invisible in 8 bits.
const float OIT_MAX_OPTICAL_DEPTH = 10.0;
const float OIT_MAX_OPTICAL_ALPHA = 0.9999546; // 1 - exp(-10), rounded down

// The optical depth -ln(1 - a) of a fragment of opacity a (> 0), clamped.
float oit_optical_depth(float alpha)
{
    return -log(1.0 - min(alpha, OIT_MAX_OPTICAL_ALPHA));
}
