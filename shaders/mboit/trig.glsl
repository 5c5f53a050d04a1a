// mboit/trig.glsl: the transmittance in front of a depth from 3 trigonometric
// (complex) moments (E4 in mboit/common.glsl), the paper's new trigonometric
// variant, the same steps as mboit/power.glsl on the unit circle:
//  1. bias: m_j *= 1 - bias for j >= 1 (mixing with the moments of the uniform
//     distribution on the circle, (1, 0, 0, 0));
//  2. the Toeplitz matrix B_ij = m_{i-j} (m_{-j} = conj(m_j), i, j < 4) is
//     Hermitian positive definite; solve B c = (1, w, w^2, w^3), w = e^{i p} of
//     the queried phase p, with its LDL^H factorisation;
//  3. the 3 roots of sum_j conj(c_j) t^j lie on the unit circle and, with w,
//     support the canonical representation that has a point at w;
//  4. weights: 1 for a root whose phase is in front of p, 0 behind, the
//     overestimation at w itself, and in the wrapping zone a ramp from 0 to 1
//     (a point there is as much behind the far end as in front of the near
//     end); the complex interpolating polynomial's integral is
//     Re(sum_j p_j m_j) = A(p) / b0;
//  5. T = exp(-b0 A(p) / b0).
// Needs mboit/common.glsl.

vec2 mboit_cmul(vec2 a, vec2 b)
{
    return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

vec2 mboit_conj(vec2 a)
{
    return vec2(a.x, -a.y);
}

vec2 mboit_cdiv(vec2 a, vec2 b)
{
    return mboit_cmul(a, mboit_conj(b)) / dot(b, b);
}

// the principal square root
vec2 mboit_csqrt(vec2 a)
{
    float r = length(a);
    float re = sqrt(max(0.5 * (r + a.x), 0.0));
    float im = sqrt(max(0.5 * (r - a.x), 0.0));
    return vec2(re, a.y < 0.0 ? -im : im);
}

// one cube root (of the principal argument)
vec2 mboit_ccbrt(vec2 a)
{
    float r = length(a);
    if (r == 0.0)
        return vec2(0.0);
    float angle = atan(a.y, a.x) / 3.0;
    return pow(r, 1.0 / 3.0) * vec2(cos(angle), sin(angle));
}

// The roots of A t^3 + B t^2 + C t + D (complex; Cardano): t = y - a/3 turns
// the monic cubic into y^3 + P y + Q = 0, whose roots are u - P / (3 u) for
// the three cube roots u of -Q/2 + sqrt(Q^2/4 + P^3/27) (the sign of the square
// root chosen so that u is not small).
void mboit_cubic_roots(vec2 A, vec2 B, vec2 C, vec2 D, out vec2 roots[3])
{
    vec2 a = mboit_cdiv(B, A), b = mboit_cdiv(C, A), d = mboit_cdiv(D, A);
    vec2 a2 = mboit_cmul(a, a);
    vec2 P = b - a2 / 3.0;
    vec2 Q = (2.0 * mboit_cmul(a2, a) - 9.0 * mboit_cmul(a, b)) / 27.0 + d;
    vec2 root = mboit_csqrt(mboit_cmul(Q, Q) / 4.0 + mboit_cmul(mboit_cmul(P, P), P) / 27.0);
    vec2 plus = -0.5 * Q + root, minus = -0.5 * Q - root;
    vec2 u = mboit_ccbrt(dot(plus, plus) >= dot(minus, minus) ? plus : minus);
    const vec2 unity = vec2(-0.5, 0.8660254037844386); // e^{2 pi i / 3}
    for (int k = 0; k < 3; ++k) {
        vec2 y = dot(u, u) > 0.0 ? u - mboit_cdiv(P, 3.0 * u) : vec2(0.0);
        roots[k] = y - a / 3.0;
        u = mboit_cmul(u, unity);
    }
}

// The phase of a point on the circle, in [0, 2 pi).
float mboit_circle_phase(vec2 t)
{
    float phase = atan(t.y, t.x);
    return phase < 0.0 ? phase + 2.0 * MBOIT_PI : phase;
}

// The normalised absorbance in front of the phase p from the normalised
// moments m[0] = (1, 0), m[1..3] (complex).
float mboit_trig_absorbance(vec2 m_in[4], float p)
{
    // 1. bias
    vec2 m[4];
    m[0] = vec2(1.0, 0.0);
    for (int j = 1; j < 4; ++j)
        m[j] = m_in[j] * (1.0 - MBOIT_BIAS);

    // 2. LDL^H of the Toeplitz matrix: below the diagonal B_ij = m_{i-j}, on it 1
    vec2 L[4][4];
    float D[4];
    for (int j = 0; j < 4; ++j) {
        float dj = 1.0;
        for (int k = 0; k < j; ++k)
            dj -= dot(L[j][k], L[j][k]) * D[k];
        D[j] = dj;
        for (int i = j + 1; i < 4; ++i) {
            vec2 lij = m[i - j];
            for (int k = 0; k < j; ++k)
                lij -= mboit_cmul(L[i][k], mboit_conj(L[j][k])) * D[k];
            L[i][j] = lij / dj;
        }
    }
    vec2 w = vec2(cos(p), sin(p));
    vec2 c[4];
    vec2 power = vec2(1.0, 0.0);
    for (int i = 0; i < 4; ++i) {
        vec2 ci = power;
        for (int k = 0; k < i; ++k)
            ci -= mboit_cmul(L[i][k], c[k]);
        c[i] = ci;
        power = mboit_cmul(power, w);
    }
    for (int i = 0; i < 4; ++i)
        c[i] /= D[i];
    for (int i = 3; i >= 0; --i)
        for (int k = i + 1; k < 4; ++k)
            c[i] -= mboit_cmul(mboit_conj(L[k][i]), c[k]);

    // 3. the other support points, pushed back onto the circle (rounding)
    vec2 roots[3];
    mboit_cubic_roots(mboit_conj(c[3]), mboit_conj(c[2]), mboit_conj(c[1]), mboit_conj(c[0]), roots);

    // 4. weights and the complex interpolating polynomial (Newton, then Horner)
    const float zone_start = 2.0 * MBOIT_PI - MBOIT_WRAPPING_ZONE;
    vec2 t[4];
    vec2 f[4];
    t[0] = w;
    f[0] = vec2(MBOIT_OVERESTIMATION, 0.0);
    for (int i = 1; i < 4; ++i) {
        vec2 root = roots[i - 1];
        float magnitude = length(root);
        t[i] = magnitude > 0.0 ? root / magnitude : root;
        float phase = mboit_circle_phase(t[i]);
        float weight = phase < p ? 1.0 : clamp((phase - zone_start) / MBOIT_WRAPPING_ZONE, 0.0, 1.0);
        f[i] = vec2(weight, 0.0);
    }
    for (int level = 1; level < 4; ++level)
        for (int i = 3; i >= level; --i)
            f[i] = mboit_cdiv(f[i] - f[i - 1], t[i] - t[i - level]);
    // (each Horner step into a new array, as in mboit/power.glsl: llvmpipe
    // miscompiled the in-place update)
    vec2 poly[4] = vec2[4](f[3], vec2(0.0), vec2(0.0), vec2(0.0));
    for (int i = 2; i >= 0; --i) {
        vec2 next[4];
        next[0] = f[i] - mboit_cmul(t[i], poly[0]);
        for (int j = 1; j < 4; ++j)
            next[j] = poly[j - 1] - mboit_cmul(t[i], poly[j]);
        poly = next;
    }
    float absorbance = 0.0;
    for (int j = 0; j < 4; ++j)
        absorbance += mboit_cmul(poly[j], m[j]).x;
    return absorbance;
}
