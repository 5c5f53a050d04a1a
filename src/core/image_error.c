/*
 * image_error.c: how far an image is from a reference (oit render
 * --error-vs-reference, --error-map; oit bench's error columns and flicker;
 * the workbench's error view).
 *
 * All figures are over the RGB channels on the 0..255 scale (alpha ignored):
 * - rmse: root of the mean squared channel difference;
 * - psnr: 10 log10(255^2 / mse) dB, infinite for identical images;
 * - ssim: the structural similarity of Wang, Bovik, Sheikh & Simoncelli 2004
 *   with their constants (11x11 Gaussian window, sigma 1.5, K1 = 0.01, K2 =
 *   0.03, L = 255), computed per channel over every window that lies wholly
 *   inside the image ("valid", as their reference implementation) and
 *   averaged over windows and channels; images narrower than 11 pixels use
 *   the largest odd window that fits;
 * - max: the largest channel difference;
 * - share_over_2: the percentage of pixels with a channel more than 2 off
 *   (the tests' tolerance for exact algorithms).
 * - flip: the mean of the per-pixel LDR FLIP (flip.c) at the paper's default
 *   viewing (OIT_FLIP_PPD_DEFAULT pixels per degree), 0..1.
 * The error map (metric abs) colours each pixel by its largest channel
 * difference d on a logarithmic scale, log2(1 + d) / log2(1 + 64), through
 * the heat ramp the buffer views use (blue, green, yellow, red at 64 and
 * above); exact pixels (d = 0) are black. The legend is a bar with ticks at
 * 1, 2, 8, 32 and 64. The flip map colours each pixel's FLIP value v through
 * magma (magma_table.h) at round(255 v), as the paper's figures do: black
 * (0, 0, 4) at 0, light yellow at 1; its legend's ticks are at 0, .25, .5,
 * .75 and 1.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "magma_table.h"
#include "oit.h"

#define SSIM_WINDOW 11
#define SSIM_SIGMA 1.5
#define SSIM_K1 0.01
#define SSIM_K2 0.03

static oit_status check_pair(const oit_image *image, const oit_image *reference, oit_error *err)
{
    if (!image->rgba || !reference->rgba)
        return oit_fail(err, OIT_E_INPUT, "no image to compare");
    if (image->width != reference->width || image->height != reference->height)
        return oit_fail(err, OIT_E_INPUT, "image sizes differ: %dx%d and reference %dx%d", image->width,
                        image->height, reference->width, reference->height);
    return OIT_OK;
}

/* Separable Gaussian filter of a w x h plane, "valid": out is (w - n + 1) x (h - n + 1). */
static void filter_valid(const double *in, int w, int h, const double *kernel, int n, double *scratch,
                         double *out)
{
    int ow = w - n + 1, oh = h - n + 1;
    for (int y = 0; y < h; ++y) /* rows: w -> ow */
        for (int x = 0; x < ow; ++x) {
            double sum = 0.0;
            for (int k = 0; k < n; ++k)
                sum += kernel[k] * in[(size_t)y * w + x + k];
            scratch[(size_t)y * ow + x] = sum;
        }
    for (int y = 0; y < oh; ++y) /* columns: h -> oh */
        for (int x = 0; x < ow; ++x) {
            double sum = 0.0;
            for (int k = 0; k < n; ++k)
                sum += kernel[k] * scratch[(size_t)(y + k) * ow + x];
            out[(size_t)y * ow + x] = sum;
        }
}

/* Mean SSIM over the RGB channels; -1 when out of memory. */
static double ssim_rgb(const oit_image *a, const oit_image *b)
{
    int w = a->width, h = a->height;
    int n = SSIM_WINDOW;
    int smaller = w < h ? w : h;
    if (smaller < n)
        n = smaller % 2 ? smaller : smaller - 1;
    double kernel[SSIM_WINDOW], kernel_sum = 0.0;
    for (int k = 0; k < n; ++k) {
        double x = k - (n - 1) / 2.0;
        kernel[k] = exp(-x * x / (2.0 * SSIM_SIGMA * SSIM_SIGMA));
        kernel_sum += kernel[k];
    }
    for (int k = 0; k < n; ++k)
        kernel[k] /= kernel_sum;

    size_t pixels = (size_t)w * (size_t)h;
    int ow = w - n + 1, oh = h - n + 1;
    size_t windows = (size_t)ow * (size_t)oh;
    /* planes: x, y, and their products; filtered: the five local moments */
    double *buffer = malloc(sizeof(double) * (5 * pixels + pixels + 5 * windows));
    if (!buffer)
        return -1.0;
    double *plane[5], *moment[5];
    for (int p = 0; p < 5; ++p) {
        plane[p] = buffer + (size_t)p * pixels;
        moment[p] = buffer + 6 * pixels + (size_t)p * windows;
    }
    double *scratch = buffer + 5 * pixels;
    const double c1 = (SSIM_K1 * 255.0) * (SSIM_K1 * 255.0);
    const double c2 = (SSIM_K2 * 255.0) * (SSIM_K2 * 255.0);
    double total = 0.0;
    for (int c = 0; c < 3; ++c) {
        for (size_t i = 0; i < pixels; ++i) {
            double x = a->rgba[i * 4 + c], y = b->rgba[i * 4 + c];
            plane[0][i] = x;
            plane[1][i] = y;
            plane[2][i] = x * x;
            plane[3][i] = y * y;
            plane[4][i] = x * y;
        }
        for (int p = 0; p < 5; ++p)
            filter_valid(plane[p], w, h, kernel, n, scratch, moment[p]);
        double channel = 0.0;
        for (size_t i = 0; i < windows; ++i) {
            double mx = moment[0][i], my = moment[1][i];
            double vx = moment[2][i] - mx * mx, vy = moment[3][i] - my * my;
            double cov = moment[4][i] - mx * my;
            channel += ((2.0 * mx * my + c1) * (2.0 * cov + c2)) /
                       ((mx * mx + my * my + c1) * (vx + vy + c2));
        }
        total += channel / (double)windows;
    }
    free(buffer);
    return total / 3.0;
}

oit_status oit_image_error_compute(const oit_image *image, const oit_image *reference, oit_image_error *out,
                                   oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_status status = check_pair(image, reference, err);
    if (status != OIT_OK)
        return status;
    oit_image_diff diff;
    status = oit_image_compare(image, reference, 2, &diff, err);
    if (status != OIT_OK)
        return status;
    out->rmse = diff.rmse;
    out->psnr_db = diff.psnr_db;
    out->max = diff.max_channel_diff;
    out->share_over_2 = 100.0 * diff.share_over_tolerance;
    out->ssim = ssim_rgb(image, reference);
    if (out->ssim < -0.5)
        return oit_fail(err, OIT_E_RUNTIME, "error figures: out of memory for SSIM of %dx%d", image->width,
                        image->height);
    return oit_image_flip(image, reference, OIT_FLIP_PPD_DEFAULT, NULL, &out->flip, err);
}

/* ------------------------------------------------------------ error map */

/* blue -> green -> yellow -> red: heat() of ll/compose.frag and ib/compose.frag
 * (the buffer views' heatmap), in double where they use float */
static void heat(double t, uint8_t rgb[3])
{
    t = t < 0.0 ? 0.0 : t > 1.0 ? 3.0 : t * 3.0;
    double r, g, b;
    if (t < 1.0)
        r = 0.0, g = t, b = 1.0 - t;
    else if (t < 2.0)
        r = t - 1.0, g = 1.0, b = 0.0;
    else
        r = 1.0, g = 3.0 - t, b = 0.0;
    rgb[0] = (uint8_t)lround(r * 255.0);
    rgb[1] = (uint8_t)lround(g * 255.0);
    rgb[2] = (uint8_t)lround(b * 255.0);
}

double oit_error_map_position(int difference)
{
    if (difference <= 0)
        return 0.0;
    double t = log2(1.0 + difference) / log2(1.0 + OIT_ERROR_MAP_SATURATION);
    return t > 1.0 ? 1.0 : t;
}

void oit_error_map_colour(int difference, uint8_t rgb[3])
{
    if (difference <= 0) {
        rgb[0] = rgb[1] = rgb[2] = 0;
        return;
    }
    heat(oit_error_map_position(difference), rgb);
}

void oit_heatmap_colour(int64_t length, int64_t longest, uint8_t rgb[3])
{
    heat((double)length / (double)(longest > 1 ? longest : 1), rgb);
}

/* 3x5 digits, '+' and '.', one row of three bits per line, top first */
static const uint8_t glyphs[12][5] = {
    {7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7}, {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1}, {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}, {0, 2, 7, 2, 0}, {0, 0, 0, 0, 2},
};

static void put_text(oit_image *out, int x, int y, const char *text)
{
    for (; *text; ++text, x += 4) {
        int g = *text == '+' ? 10 : *text == '.' ? 11 : *text - '0';
        if (g < 0 || g > 11)
            continue;
        for (int row = 0; row < 5; ++row)
            for (int col = 0; col < 3; ++col)
                if (glyphs[g][row] & (4 >> col)) {
                    int px = x + col, py = y + row;
                    if (px < 0 || px >= out->width || py < 0 || py >= out->height)
                        continue;
                    uint8_t *p = out->rgba + ((size_t)py * out->width + px) * 4;
                    p[0] = p[1] = p[2] = 255;
                }
    }
}

void oit_flip_map_colour(double value, uint8_t rgb[3])
{
    double v = value < 0.0 ? 0.0 : value > 1.0 ? 1.0 : value;
    memcpy(rgb, magma_table[(int)lround(v * 255.0)], 3);
}

oit_status oit_error_metric_parse(const char *word, oit_error_metric *out, oit_error *err)
{
    if (strcmp(word, "abs") == 0)
        *out = OIT_ERROR_METRIC_ABS;
    else if (strcmp(word, "flip") == 0)
        *out = OIT_ERROR_METRIC_FLIP;
    else
        return oit_fail(err, OIT_E_INPUT, "--error-metric must be abs or flip, got '%s'", word);
    return OIT_OK;
}

oit_status oit_image_error_map(const oit_image *image, const oit_image *reference, bool legend, oit_image *out,
                               oit_error *err)
{
    return oit_image_error_map_metric(image, reference, OIT_ERROR_METRIC_ABS, legend, out, err);
}

oit_status oit_image_error_map_metric(const oit_image *image, const oit_image *reference, oit_error_metric metric,
                                      bool legend, oit_image *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    oit_status status = check_pair(image, reference, err);
    if (status != OIT_OK)
        return status;
    int width = image->width, height = image->height;
    size_t pixels = (size_t)width * (size_t)height;
    bool flip = metric == OIT_ERROR_METRIC_FLIP;
    float *values = NULL;
    if (flip) {
        values = malloc(sizeof(float) * (pixels ? pixels : 1));
        if (!values)
            return oit_fail(err, OIT_E_RUNTIME, "FLIP map: out of memory for %dx%d", width, height);
        double mean;
        status = oit_image_flip(image, reference, OIT_FLIP_PPD_DEFAULT, values, &mean, err);
        if (status != OIT_OK) {
            free(values);
            return status;
        }
    }
    status = oit_image_alloc(out, width, height + (legend ? OIT_ERROR_MAP_LEGEND_HEIGHT : 0), err);
    if (status != OIT_OK) {
        free(values);
        return status;
    }
    memset(out->rgba, 0, (size_t)out->width * (size_t)out->height * 4);
    for (size_t i = 0; i < pixels; ++i) {
        if (flip) {
            oit_flip_map_colour(values[i], out->rgba + i * 4);
            continue;
        }
        int d = 0;
        for (int c = 0; c < 3; ++c) {
            int e = abs((int)image->rgba[i * 4 + c] - (int)reference->rgba[i * 4 + c]);
            d = e > d ? e : d;
        }
        oit_error_map_colour(d, out->rgba + i * 4);
    }
    free(values);
    for (size_t i = 0; i < (size_t)out->width * (size_t)out->height; ++i)
        out->rgba[i * 4 + 3] = 255;
    if (!legend)
        return OIT_OK;
    /* the bar: column x shows the colour of the value at position x / (width - 1) */
    int bar_top = height + 2, bar_rows = 6;
    for (int x = 0; x < width; ++x) {
        double t = width > 1 ? (double)x / (width - 1) : 1.0;
        uint8_t rgb[3];
        if (flip)
            oit_flip_map_colour(t, rgb);
        else
            heat(t, rgb);
        for (int y = bar_top; y < bar_top + bar_rows; ++y)
            memcpy(out->rgba + ((size_t)y * width + x) * 4, rgb, 3);
    }
    static const int abs_ticks[] = {1, 2, 8, 32, OIT_ERROR_MAP_SATURATION};
    static const char *const flip_labels[] = {"0", ".25", ".5", ".75", "1"};
    /* right to left, so that the last tick (64+, 1) always shows; a label that would touch the one
     * to its right is left out (narrow maps) */
    int labelled_from = width + 2;
    for (size_t k = 5; k-- > 0;) {
        double position = flip ? 0.25 * (double)k : oit_error_map_position(abs_ticks[k]);
        int x = (int)lround(position * (width - 1));
        char label[8];
        if (flip)
            snprintf(label, sizeof label, "%s", flip_labels[k]);
        else
            snprintf(label, sizeof label, "%d%s", abs_ticks[k], abs_ticks[k] == OIT_ERROR_MAP_SATURATION ? "+" : "");
        int text_width = 4 * (int)strlen(label) - 1;
        int left = x - text_width / 2;
        if (left + text_width > width)
            left = width - text_width;
        if (left < 0)
            left = 0;
        for (int y = bar_top + bar_rows; y < bar_top + bar_rows + 2 && y < out->height; ++y) {
            uint8_t *p = out->rgba + ((size_t)y * width + x) * 4;
            p[0] = p[1] = p[2] = 255;
        }
        if (left + text_width < labelled_from - 1) {
            put_text(out, left, bar_top + bar_rows + 3, label);
            labelled_from = left;
        }
    }
    return OIT_OK;
}
