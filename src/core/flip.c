/*
 * flip.c: the perceptual error FLIP, LDR version (Andersson, Nilsson,
 * Akenine-Moeller, Oskarsson, Astroem and Fairchild, "FLIP: A Difference
 * Evaluator for Alternating Images", HPG 2020 / PACMCGIT 3(2), article 15),
 * written from the paper's description; the authors' BSD-3 code was read to
 * confirm the constants and the order of the steps, none of it is copied.
 *
 * Per pixel, for an sRGB image against its reference, seen at ppd pixels per
 * degree of visual angle (default: a 0.7 m wide 3840-pixel monitor at 0.7 m,
 * 3840 * (0.7 / 0.7) * pi / 180 = 67.02):
 * 1. colour: sRGB -> linear RGB -> XYZ (D65) -> YyCxCz (the linearised
 *    CIELAB opponent space: Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn),
 *    Cz = 200 (Y/Yn - Z/Zn)); each channel filtered by the spatial form of
 *    its contrast sensitivity function, a sum of Gaussians
 *    S(r) = sum_i a_i sqrt(pi / b_i) exp(-pi^2 r^2 / b_i), r in degrees,
 *    normalised to sum 1 over a square of radius
 *    ceil(3 sqrt(b_max / (2 pi^2)) ppd) pixels (b_max = 0.04), edges
 *    clamped: achromatic a1 = 1, b1 = 0.0047; red-green a1 = 1,
 *    b1 = 0.0053; blue-yellow a1 = 34.1, b1 = 0.04, a2 = 13.5, b2 = 0.025.
 *    Back to linear RGB, clamped to [0, 1], -> XYZ -> L*a*b*, Hunt-adjusted
 *    (a*, b* times 0.01 L*); HyAB distance |dL| + sqrt(da^2 + db^2) raised
 *    to qc = 0.7, then compressed into [0, 1]: below pc * cmax (pc = 0.4)
 *    linearly to [0, pt] (pt = 0.95), above it linearly to [pt, 1], where
 *    cmax is the HyAB distance of Hunt-adjusted green and blue raised to qc.
 * 2. features: on Y/Yn of the unfiltered images, edges (the first
 *    derivative of a Gaussian) and points (its second derivative), standard
 *    deviation 0.5 * 0.082 * ppd pixels, radius ceil(3 sd), each kernel's
 *    positive weights normalised to sum 1 and its negative ones to -1; the
 *    feature difference is the larger of the differences of the gradient
 *    magnitudes sqrt(fx^2 + fy^2) of edges and of points, times 1/sqrt(2),
 *    raised to qf = 0.5.
 * 3. FLIP = colour^(1 - feature), in [0, 1].
 * All the kernels are separable (a Gaussian, or a Gaussian times a 1-D
 * derivative, whose 2-D normalisation is the product of the 1-D ones; the
 * blue-yellow filter is two separable Gaussians, weighted as in the 2-D sum),
 * so each filter is a row pass and a column pass, in double precision.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

#define FLIP_PI 3.14159265358979323846
#define FLIP_QC 0.7
#define FLIP_PC 0.4
#define FLIP_PT 0.95
#define FLIP_QF 0.5
#define FLIP_EDGE_WIDTH 0.082 /* degrees: peak to trough of the edge detector, 2 standard deviations */
#define FLIP_CSF_B_MAX 0.04

/* ------------------------------------------------------------- colour */

/* Linear RGB -> XYZ from the sRGB primaries and the D65 white point
 * (IEC 61966-2-1 chromaticities), its inverse, and the white's XYZ (Y = 1).
 * Derived per call (a few dozen operations), so that the function keeps no
 * state and threads may call it at once. */
typedef struct flip_colour {
    double rgb_to_xyz[9], xyz_to_rgb[9], white[3];
} flip_colour;

static void invert3(const double m[9], double out[9])
{
    double c00 = m[4] * m[8] - m[5] * m[7], c01 = m[5] * m[6] - m[3] * m[8], c02 = m[3] * m[7] - m[4] * m[6];
    double det = m[0] * c00 + m[1] * c01 + m[2] * c02;
    out[0] = c00 / det;
    out[1] = (m[2] * m[7] - m[1] * m[8]) / det;
    out[2] = (m[1] * m[5] - m[2] * m[4]) / det;
    out[3] = c01 / det;
    out[4] = (m[0] * m[8] - m[2] * m[6]) / det;
    out[5] = (m[2] * m[3] - m[0] * m[5]) / det;
    out[6] = c02 / det;
    out[7] = (m[1] * m[6] - m[0] * m[7]) / det;
    out[8] = (m[0] * m[4] - m[1] * m[3]) / det;
}

static void derive_matrices(flip_colour *m)
{
    const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}}, w[2] = {0.3127, 0.3290};
    double p[9]; /* columns: the primaries' XYZ at Y = 1 */
    for (int c = 0; c < 3; ++c) {
        p[0 * 3 + c] = xy[c][0] / xy[c][1];
        p[1 * 3 + c] = 1.0;
        p[2 * 3 + c] = (1.0 - xy[c][0] - xy[c][1]) / xy[c][1];
    }
    double pi[9], wxyz[3] = {w[0] / w[1], 1.0, (1.0 - w[0] - w[1]) / w[1]}, s[3];
    invert3(p, pi);
    for (int r = 0; r < 3; ++r)
        s[r] = pi[r * 3] * wxyz[0] + pi[r * 3 + 1] * wxyz[1] + pi[r * 3 + 2] * wxyz[2];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            m->rgb_to_xyz[r * 3 + c] = p[r * 3 + c] * s[c];
    invert3(m->rgb_to_xyz, m->xyz_to_rgb);
    memcpy(m->white, wxyz, sizeof wxyz);
}

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    const double d = 6.0 / 29.0;
    return t > d * d * d ? cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

/* linear RGB -> Hunt-adjusted L*a*b* */
static void rgb_to_hunt_lab(const flip_colour *m, const double rgb[3], double out[3])
{
    double f[3];
    for (int r = 0; r < 3; ++r)
        f[r] = lab_f((m->rgb_to_xyz[r * 3] * rgb[0] + m->rgb_to_xyz[r * 3 + 1] * rgb[1] +
                      m->rgb_to_xyz[r * 3 + 2] * rgb[2]) /
                     m->white[r]);
    double l = 116.0 * f[1] - 16.0;
    out[0] = l;
    out[1] = 0.01 * l * 500.0 * (f[0] - f[1]);
    out[2] = 0.01 * l * 200.0 * (f[1] - f[2]);
}

static double hyab(const double a[3], const double b[3])
{
    double da = a[1] - b[1], db = a[2] - b[2];
    return fabs(a[0] - b[0]) + sqrt(da * da + db * db);
}

/* ------------------------------------------------------------ filters */

/* out = the plane filtered by row kernel kx and column kernel ky (both of
 * 2 radius + 1 taps, correlation), edges clamped; tmp is w x h scratch. */
static void filter_separable(const double *in, int w, int h, const double *kx, const double *ky, int radius,
                             double *tmp, double *out)
{
    for (int y = 0; y < h; ++y) {
        const double *row = in + (size_t)y * w;
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            for (int k = -radius; k <= radius; ++k) {
                int xx = x + k < 0 ? 0 : x + k >= w ? w - 1 : x + k;
                sum += kx[k + radius] * row[xx];
            }
            tmp[(size_t)y * w + x] = sum;
        }
    }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            for (int k = -radius; k <= radius; ++k) {
                int yy = y + k < 0 ? 0 : y + k >= h ? h - 1 : y + k;
                sum += ky[k + radius] * tmp[(size_t)yy * w + x];
            }
            out[(size_t)y * w + x] = sum;
        }
}

/* exp(-pi^2 (x / ppd)^2 / b) for x in [-radius, radius], normalised to sum 1; returns the sum before */
static double csf_gaussian(double b, double ppd, int radius, double *k)
{
    double sum = 0.0;
    for (int x = -radius; x <= radius; ++x) {
        double d = x / ppd;
        k[x + radius] = exp(-FLIP_PI * FLIP_PI * d * d / b);
        sum += k[x + radius];
    }
    for (int i = 0; i <= 2 * radius; ++i)
        k[i] /= sum;
    return sum;
}

/* a 1-D kernel's positive weights scaled to sum 1, its negative ones to -1 */
static void normalise_signed(double *k, int n)
{
    double pos = 0.0, neg = 0.0;
    for (int i = 0; i < n; ++i)
        if (k[i] > 0.0)
            pos += k[i];
        else
            neg -= k[i];
    for (int i = 0; i < n; ++i)
        k[i] = k[i] > 0.0 ? k[i] / pos : neg > 0.0 ? k[i] / neg : 0.0;
}

typedef struct flip_planes {
    double *yy, *cx, *cz, *lum; /* YyCxCz, and Y/Yn for the features */
} flip_planes;

/* ------------------------------------------------------------ metric */

oit_status oit_image_flip(const oit_image *image, const oit_image *reference, double ppd, float *map,
                          double *mean, oit_error *err)
{
    *mean = 0.0;
    if (!image->rgba || !reference->rgba)
        return oit_fail(err, OIT_E_INPUT, "FLIP: no image to compare");
    if (image->width != reference->width || image->height != reference->height)
        return oit_fail(err, OIT_E_INPUT, "FLIP: image sizes differ: %dx%d and reference %dx%d", image->width,
                        image->height, reference->width, reference->height);
    if (!(ppd > 0.0 && ppd <= 1000.0))
        return oit_fail(err, OIT_E_INPUT, "FLIP: pixels per degree must be in (0, 1000], got %g", ppd);
    flip_colour m;
    derive_matrices(&m);
    int w = image->width, h = image->height;
    size_t n = (size_t)w * (size_t)h;
    if (n == 0)
        return OIT_OK;

    /* kernels */
    int csf_radius = (int)ceil(3.0 * sqrt(FLIP_CSF_B_MAX / (2.0 * FLIP_PI * FLIP_PI)) * ppd);
    double sd = 0.5 * FLIP_EDGE_WIDTH * ppd;
    int feature_radius = (int)ceil(3.0 * sd);
    int csf_taps = 2 * csf_radius + 1, feature_taps = 2 * feature_radius + 1;
    /* 4 CSF kernels (achromatic, red-green, blue-yellow's two), gaussian, edge, point */
    double *kernels = malloc(sizeof(double) * ((size_t)4 * csf_taps + (size_t)3 * feature_taps));
    /* per image: yy cx cz lum; shared: tmp, two filtered planes; per image: lab (3) */
    double *planes = malloc(sizeof(double) * n * 17);
    if (!kernels || !planes) {
        free(kernels);
        free(planes);
        return oit_fail(err, OIT_E_RUNTIME, "FLIP: out of memory for %dx%d", w, h);
    }
    double *k_a = kernels, *k_rg = k_a + csf_taps, *k_by1 = k_rg + csf_taps, *k_by2 = k_by1 + csf_taps;
    double *k_gauss = k_by2 + csf_taps, *k_edge = k_gauss + feature_taps, *k_point = k_edge + feature_taps;
    csf_gaussian(0.0047, ppd, csf_radius, k_a); /* a2 = 0: one Gaussian, its weight cancels */
    csf_gaussian(0.0053, ppd, csf_radius, k_rg);
    double s1 = csf_gaussian(0.04, ppd, csf_radius, k_by1), s2 = csf_gaussian(0.025, ppd, csf_radius, k_by2);
    /* the 2-D sum of each term is a_i sqrt(pi / b_i) s_i^2 */
    double m1 = 34.1 * sqrt(FLIP_PI / 0.04) * s1 * s1, m2 = 13.5 * sqrt(FLIP_PI / 0.025) * s2 * s2;
    double w_by1 = m1 / (m1 + m2), w_by2 = m2 / (m1 + m2);
    double gsum = 0.0;
    for (int x = -feature_radius; x <= feature_radius; ++x) {
        double g = exp(-(double)x * x / (2.0 * sd * sd));
        k_gauss[x + feature_radius] = g;
        k_edge[x + feature_radius] = -x * g;
        k_point[x + feature_radius] = ((double)x * x / (sd * sd) - 1.0) * g;
        gsum += g;
    }
    for (int i = 0; i < feature_taps; ++i)
        k_gauss[i] /= gsum;
    normalise_signed(k_edge, feature_taps);
    normalise_signed(k_point, feature_taps);

    flip_planes p[2];
    double *lab[2];
    for (int i = 0; i < 2; ++i) {
        p[i].yy = planes + n * (size_t)(4 * i);
        p[i].cx = p[i].yy + n;
        p[i].cz = p[i].cx + n;
        p[i].lum = p[i].cz + n;
        lab[i] = planes + n * (size_t)(8 + 3 * i); /* 3 per pixel, interleaved */
    }
    double *tmp = planes + n * 14, *fa = tmp + n, *fb = fa + n;

    double lut[256];
    for (int v = 0; v < 256; ++v)
        lut[v] = srgb_to_linear(v / 255.0);
    const oit_image *images[2] = {image, reference};
    for (int i = 0; i < 2; ++i)
        for (size_t q = 0; q < n; ++q) {
            const uint8_t *px = images[i]->rgba + q * 4;
            double rgb[3] = {lut[px[0]], lut[px[1]], lut[px[2]]}, xyz[3];
            for (int r = 0; r < 3; ++r)
                xyz[r] = (m.rgb_to_xyz[r * 3] * rgb[0] + m.rgb_to_xyz[r * 3 + 1] * rgb[1] +
                          m.rgb_to_xyz[r * 3 + 2] * rgb[2]) /
                         m.white[r];
            p[i].yy[q] = 116.0 * xyz[1] - 16.0;
            p[i].cx[q] = 500.0 * (xyz[0] - xyz[1]);
            p[i].cz[q] = 200.0 * (xyz[1] - xyz[2]);
            p[i].lum[q] = (p[i].yy[q] + 16.0) / 116.0;
        }

    /* colour pipeline: filter in place (yy, cx, cz), then to Hunt-adjusted L*a*b* */
    for (int i = 0; i < 2; ++i) {
        filter_separable(p[i].yy, w, h, k_a, k_a, csf_radius, tmp, fa);
        memcpy(p[i].yy, fa, sizeof(double) * n);
        filter_separable(p[i].cx, w, h, k_rg, k_rg, csf_radius, tmp, fa);
        memcpy(p[i].cx, fa, sizeof(double) * n);
        filter_separable(p[i].cz, w, h, k_by1, k_by1, csf_radius, tmp, fa);
        filter_separable(p[i].cz, w, h, k_by2, k_by2, csf_radius, tmp, fb);
        for (size_t q = 0; q < n; ++q)
            p[i].cz[q] = w_by1 * fa[q] + w_by2 * fb[q];
        for (size_t q = 0; q < n; ++q) {
            double y = (p[i].yy[q] + 16.0) / 116.0;
            double xyz[3] = {(y + p[i].cx[q] / 500.0) * m.white[0], y, (y - p[i].cz[q] / 200.0) * m.white[2]};
            double rgb[3];
            for (int r = 0; r < 3; ++r) {
                double v = m.xyz_to_rgb[r * 3] * xyz[0] + m.xyz_to_rgb[r * 3 + 1] * xyz[1] +
                           m.xyz_to_rgb[r * 3 + 2] * xyz[2];
                rgb[r] = v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
            }
            rgb_to_hunt_lab(&m, rgb, lab[i] + q * 3);
        }
    }
    double green_rgb[3] = {0.0, 1.0, 0.0}, blue_rgb[3] = {0.0, 0.0, 1.0}, green[3], blue[3];
    rgb_to_hunt_lab(&m, green_rgb, green);
    rgb_to_hunt_lab(&m, blue_rgb, blue);
    double cmax = pow(hyab(green, blue), FLIP_QC), pccmax = FLIP_PC * cmax;

    /* feature pipeline: |edge| and |point| of each image, kept in the free planes
     * (yy: edge magnitude, cx: point magnitude; the colour planes are done) */
    for (int i = 0; i < 2; ++i) {
        filter_separable(p[i].lum, w, h, k_edge, k_gauss, feature_radius, tmp, fa);
        filter_separable(p[i].lum, w, h, k_gauss, k_edge, feature_radius, tmp, fb);
        for (size_t q = 0; q < n; ++q)
            p[i].yy[q] = sqrt(fa[q] * fa[q] + fb[q] * fb[q]);
        filter_separable(p[i].lum, w, h, k_point, k_gauss, feature_radius, tmp, fa);
        filter_separable(p[i].lum, w, h, k_gauss, k_point, feature_radius, tmp, fb);
        for (size_t q = 0; q < n; ++q)
            p[i].cx[q] = sqrt(fa[q] * fa[q] + fb[q] * fb[q]);
    }

    double total = 0.0;
    for (size_t q = 0; q < n; ++q) {
        double e = pow(hyab(lab[0] + q * 3, lab[1] + q * 3), FLIP_QC);
        double colour = e < pccmax ? FLIP_PT / pccmax * e : FLIP_PT + (e - pccmax) / (cmax - pccmax) * (1.0 - FLIP_PT);
        double edge = fabs(p[0].yy[q] - p[1].yy[q]), point = fabs(p[0].cx[q] - p[1].cx[q]);
        double feature = pow((edge > point ? edge : point) / sqrt(2.0), FLIP_QF);
        double value = pow(colour, 1.0 - feature);
        if (map)
            map[q] = (float)value;
        total += value;
    }
    *mean = total / (double)n;
    free(kernels);
    free(planes);
    return OIT_OK;
}
