// mboit/power.glsl: the transmittance in front of a depth from 4 or 6 power
// moments (E4 in mboit/common.glsl): the Hamburger moment problem's bounds
// (the paper takes the 4-moment algorithm from moment shadow mapping, Peters &
// Klein 2015, and the 6-moment one from Peters et al. 2017), written out for
// n = 2 (K - 1) moments with K = 3 (power4) or 4 (power6) support points:
//  1. bias the normalised moments m = b / b0 towards a fixed vector (the paper's biasing);
//  2. the Hankel matrix H_ij = m_{i+j} (i, j < K) is positive definite; solve
//     H c = (1, x, ..., x^{K-1}) with its LDL^T (Cholesky) factorisation;
//  3. the K - 1 roots of sum_j c_j t^j and the queried depth x are the support
//     of the canonical representation of m that has a point at x: the
//     distribution with these moments that puts the most (or least) weight in
//     front of x, hence the bounds;
//  4. the weight in front of x is the integral of the polynomial p of degree
//     K - 1 that is 1 at the roots in front of x, 0 at those behind and the
//     overestimation at x itself; its integral needs only the moments:
//     A(x) / b0 = sum_j p_j m_j (the paper's bounds: overestimation 0 gives the
//     lower bound of the absorbance, 1 the upper one);
//  5. T(x) = exp(-b0 A(x) / b0) (E2, E4).
// Needs mboit/common.glsl (MBOIT_VARIANT, MBOIT_BIAS, MBOIT_OVERESTIMATION).

#if MBOIT_VARIANT == OIT_MBOIT_POWER4
#define MBOIT_POINTS 3
#else
#define MBOIT_POINTS 4
#endif
#define MBOIT_MOMENTS (2 * (MBOIT_POINTS - 1))

// The bias vectors for power moments of depths in [-1, 1] stored as 32-bit
// floats (the paper's supplementary document; m_0 = 1 is not biased): the
// moments of a distribution spread over [-1, 1], so that the mixture's
// Hankel matrix has eigenvalues of the order of the bias.
#if MBOIT_POINTS == 3
const float MBOIT_BIAS_VECTOR[7] = float[7](1.0, 0.0, 0.375, 0.0, 0.375, 0.0, 0.0);
#else
const float MBOIT_BIAS_VECTOR[7] = float[7](1.0, 0.0, 0.48, 0.0, 0.451, 0.0, 0.45);
#endif

// The real roots of c0 + c1 t + ... + c_{K-1} t^{K-1} (2 or 3 of them, all
// real and distinct for a positive definite H). When the leading coefficient
// vanishes (a pixel whose moments are symmetric about x: the canonical
// representation has a point at infinity, of weight 0), the root that runs
// off to infinity comes last, where the interpolation below only divides by
// it (its Newton differences go to 0) and never multiplies by it.
void mboit_polynomial_roots(float c[4], out float roots[3])
{
#if MBOIT_POINTS == 3
    // quadratic, in the form that does not cancel: q = -(c1 + sign(c1) sqrt(disc)) / 2;
    // c0 / q stays finite as c2 -> 0, q / c2 is the root that leaves
    float disc = max(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0);
    float q = -0.5 * (c[1] + (c[1] < 0.0 ? -1.0 : 1.0) * sqrt(disc));
    roots[0] = c[0] / q;
    roots[1] = q / c[2];
    roots[2] = 0.0;
#else
    float a = c[2] / c[3], b = c[1] / c[3], d = c[0] / c[3];
    if (abs(a) <= 1e3) {
        // cubic with three real roots (Viete): t = y - a/3 turns t^3 + a t^2 + b t + d
        // into y^3 + P y + Q = 0 with P < 0, and y = R cos(theta) with R = 2 sqrt(-P/3)
        // gives cos(3 theta) = 3 Q / (P R)
        float P = b - a * a / 3.0;
        float Q = (2.0 * a * a * a - 9.0 * a * b) / 27.0 + d;
        float R = 2.0 * sqrt(max(-P / 3.0, 0.0));
        float cos3 = R > 0.0 ? clamp(3.0 * Q / (P * R), -1.0, 1.0) : 1.0;
        float theta = acos(cos3) / 3.0;
        for (int k = 0; k < 3; ++k)
            roots[k] = R * cos(theta - 2.0 * MBOIT_PI * float(k) / 3.0) - a / 3.0;
    } else {
        // the roots sum to -a, so one is beyond |a| / 3 > 333, far outside the
        // depths [-1, 1] (and float would overflow in a^3): the two others are
        // near the roots of c2 t^2 + c1 t + c0, refined by Newton steps on the
        // cubic; the far one from the sum
        float disc = max(c[1] * c[1] - 4.0 * c[2] * c[0], 0.0);
        float q = -0.5 * (c[1] + (c[1] < 0.0 ? -1.0 : 1.0) * sqrt(disc));
        float near_roots[2] = float[2](c[0] / q, q / c[2]);
        for (int k = 0; k < 2; ++k) {
            float t = near_roots[k];
            for (int step = 0; step < 2; ++step) {
                float value = ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
                float slope = (3.0 * c[3] * t + 2.0 * c[2]) * t + c[1];
                if (slope != 0.0)
                    t -= value / slope;
            }
            roots[k] = t;
        }
        roots[2] = -a - roots[0] - roots[1];
    }
#endif
}

// The normalised absorbance in front of depth x (warped, in [-1, 1]) from the
// normalised moments m[0] = 1, m[1..MBOIT_MOMENTS].
float mboit_power_absorbance(float m_in[7], float x)
{
    // 1. bias
    float m[7];
    for (int j = 0; j < 7; ++j)
        m[j] = mix(m_in[j], MBOIT_BIAS_VECTOR[j], MBOIT_BIAS);

    // 2. LDL^T of the Hankel matrix H_ij = m_{i+j}: L unit lower triangular, D diagonal
    float L[4][4];
    float D[4];
    for (int j = 0; j < MBOIT_POINTS; ++j) {
        float dj = m[2 * j];
        for (int p = 0; p < j; ++p)
            dj -= L[j][p] * L[j][p] * D[p];
        D[j] = dj;
        for (int i = j + 1; i < MBOIT_POINTS; ++i) {
            float lij = m[i + j];
            for (int p = 0; p < j; ++p)
                lij -= L[i][p] * L[j][p] * D[p];
            L[i][j] = lij / dj;
        }
    }
    // H c = (1, x, x^2, ...): forward substitution, scaling, back substitution
    float c[4];
    float power = 1.0;
    for (int i = 0; i < MBOIT_POINTS; ++i) {
        float ci = power;
        for (int p = 0; p < i; ++p)
            ci -= L[i][p] * c[p];
        c[i] = ci;
        power *= x;
    }
    for (int i = 0; i < MBOIT_POINTS; ++i)
        c[i] /= D[i];
    for (int i = MBOIT_POINTS - 1; i >= 0; --i)
        for (int p = i + 1; p < MBOIT_POINTS; ++p)
            c[i] -= L[p][i] * c[p];
    for (int i = MBOIT_POINTS; i < 4; ++i)
        c[i] = 0.0;

    // 3. the other support points
    float roots[3];
    mboit_polynomial_roots(c, roots);

    // 4. the interpolating polynomial's Newton divided differences: points
    // (x, roots...), values (overestimation, 1 in front of x, 0 behind)
    float t[4], f[4];
    t[0] = x;
    f[0] = MBOIT_OVERESTIMATION;
    for (int i = 1; i < MBOIT_POINTS; ++i) {
        t[i] = roots[i - 1];
        f[i] = roots[i - 1] < x ? 1.0 : 0.0;
    }
    for (int level = 1; level < MBOIT_POINTS; ++level)
        for (int i = MBOIT_POINTS - 1; i >= level; --i)
            f[i] = (f[i] - f[i - 1]) / (t[i] - t[i - level]);
    // Newton form -> coefficients (Horner: p = f[K-1], then p = p (t - t_i) + f[i]),
    // each step into a new array: Mesa 22.3's llvmpipe miscompiled the in-place
    // update (poly[j] = poly[j - 1] - t_i poly[j] for j descending)
    float poly[4] = float[4](f[MBOIT_POINTS - 1], 0.0, 0.0, 0.0);
    for (int i = MBOIT_POINTS - 2; i >= 0; --i) {
        float next[4];
        next[0] = f[i] - t[i] * poly[0];
        for (int j = 1; j < 4; ++j)
            next[j] = poly[j - 1] - t[i] * poly[j];
        poly = next;
    }
    // its integral against the (biased) moments
    float absorbance = 0.0;
    for (int j = 0; j < MBOIT_POINTS; ++j)
        absorbance += poly[j] * m[j];
    return absorbance;
}
