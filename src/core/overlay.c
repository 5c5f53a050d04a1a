/*
 * overlay.c: the orientation aids (issue 29) drawn onto a finished frame: an
 * axes triad in a corner and a scale bar (oit.h, "orientation aids").
 *
 * Everything is drawn on the CPU onto the RGBA8 image after it was read
 * back, with double arithmetic in a fixed order, so the same settings give
 * the same bytes whatever rendered the frame (EGL, OSMesa, the reference,
 * the workbench). Each item (one axis with its letter, the bar, its label)
 * is first rasterized into a coverage mask (the largest coverage of its
 * primitives per pixel, so strokes that meet are not blended twice), then
 * blended once in its colour. Coverage: the pixel-centre distance to a
 * stroke or a triangle's edges, a one-pixel ramp (anti-aliased edges); the
 * bar is an axis-aligned rectangle whose coverage is the pixel's exact area
 * inside it, so its drawn length is its stated length in pixels.
 *
 * The glyphs (digits, '.', 'm', X, Y, Z) are this file's own stroke font:
 * polylines on a 4 x 6 grid (half-unit steps), drawn as round-capped strokes.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

/* ----------------------------------------------------------- corners */

static const char *const corner_names[] = {"bottom-left", "bottom-right", "top-left", "top-right"};

const char *oit_corner_name(oit_corner corner)
{
    return (unsigned)corner < 4 ? corner_names[corner] : "bottom-left";
}

oit_status oit_corner_parse(const char *text, oit_corner *out, oit_error *err)
{
    for (int i = 0; i < 4; ++i)
        if (text && strcmp(text, corner_names[i]) == 0) {
            *out = (oit_corner)i;
            return OIT_OK;
        }
    return oit_fail(err, OIT_E_INPUT,
                    "unknown corner '%.60s' (bottom-left, bottom-right, top-left or top-right)",
                    text ? text : "");
}

void oit_overlay_options_defaults(oit_overlay_options *options)
{
    memset(options, 0, sizeof *options);
    options->axes_corner = OIT_CORNER_BOTTOM_LEFT;
}

/* ------------------------------------------------------------- masks */

typedef struct mask {
    int x0, y0, w, h; /* the image's pixels it covers */
    double *c;        /* coverage 0..1, w * h */
} mask;

static oit_status mask_create(mask *m, const oit_image *image, double x0, double y0, double x1, double y1,
                              oit_error *err)
{
    memset(m, 0, sizeof *m);
    int ix0 = (int)floor(x0) - 1, iy0 = (int)floor(y0) - 1;
    int ix1 = (int)ceil(x1) + 1, iy1 = (int)ceil(y1) + 1;
    ix0 = ix0 < 0 ? 0 : ix0;
    iy0 = iy0 < 0 ? 0 : iy0;
    ix1 = ix1 > image->width ? image->width : ix1;
    iy1 = iy1 > image->height ? image->height : iy1;
    if (ix1 <= ix0 || iy1 <= iy0)
        return OIT_OK; /* nothing inside the image */
    m->x0 = ix0;
    m->y0 = iy0;
    m->w = ix1 - ix0;
    m->h = iy1 - iy0;
    m->c = calloc((size_t)m->w * (size_t)m->h, sizeof *m->c);
    if (!m->c)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for a %dx%d overlay mask", m->w, m->h);
    return OIT_OK;
}

static void mask_free(mask *m)
{
    free(m->c);
    m->c = NULL;
}

static double clamp01(double v)
{
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

static void mask_put(mask *m, int x, int y, double coverage)
{
    double *c = &m->c[(size_t)(y - m->y0) * (size_t)m->w + (size_t)(x - m->x0)];
    if (coverage > *c)
        *c = coverage;
}

/* The pixels of m within [x0, x1) x [y0, y1), as loop bounds. */
static void mask_range(const mask *m, double x0, double y0, double x1, double y1, int *ix0, int *iy0, int *ix1,
                       int *iy1)
{
    *ix0 = (int)floor(x0) - 1;
    *iy0 = (int)floor(y0) - 1;
    *ix1 = (int)ceil(x1) + 1;
    *iy1 = (int)ceil(y1) + 1;
    if (*ix0 < m->x0)
        *ix0 = m->x0;
    if (*iy0 < m->y0)
        *iy0 = m->y0;
    if (*ix1 > m->x0 + m->w)
        *ix1 = m->x0 + m->w;
    if (*iy1 > m->y0 + m->h)
        *iy1 = m->y0 + m->h;
}

/* A round-capped stroke from a to b, radius r (pixels; image coordinates, the
 * pixel (x, y) covering [x, x + 1) x [y, y + 1)). */
static void mask_stroke(mask *m, double ax, double ay, double bx, double by, double r)
{
    if (!m->c)
        return;
    int ix0, iy0, ix1, iy1;
    mask_range(m, fmin(ax, bx) - r, fmin(ay, by) - r, fmax(ax, bx) + r, fmax(ay, by) + r, &ix0, &iy0, &ix1, &iy1);
    double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    for (int y = iy0; y < iy1; ++y)
        for (int x = ix0; x < ix1; ++x) {
            double px = x + 0.5 - ax, py = y + 0.5 - ay;
            double t = len2 > 0.0 ? (px * dx + py * dy) / len2 : 0.0;
            t = clamp01(t);
            double ex = px - t * dx, ey = py - t * dy;
            double d = sqrt(ex * ex + ey * ey);
            double coverage = clamp01(r + 0.5 - d);
            if (coverage > 0.0)
                mask_put(m, x, y, coverage);
        }
}

/* A filled triangle; coverage from the largest signed distance to its edges. */
static void mask_triangle(mask *m, const double p[3][2])
{
    if (!m->c)
        return;
    double area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if (area == 0.0)
        return;
    double sign = area > 0.0 ? 1.0 : -1.0;
    double nx[3], ny[3], off[3];
    for (int e = 0; e < 3; ++e) {
        const double *a = p[e], *b = p[(e + 1) % 3];
        double ex = b[0] - a[0], ey = b[1] - a[1], len = sqrt(ex * ex + ey * ey);
        if (len == 0.0)
            return;
        /* outward normal */
        nx[e] = sign * ey / len;
        ny[e] = -sign * ex / len;
        off[e] = nx[e] * a[0] + ny[e] * a[1];
    }
    double minx = fmin(p[0][0], fmin(p[1][0], p[2][0])), maxx = fmax(p[0][0], fmax(p[1][0], p[2][0]));
    double miny = fmin(p[0][1], fmin(p[1][1], p[2][1])), maxy = fmax(p[0][1], fmax(p[1][1], p[2][1]));
    int ix0, iy0, ix1, iy1;
    mask_range(m, minx, miny, maxx, maxy, &ix0, &iy0, &ix1, &iy1);
    for (int y = iy0; y < iy1; ++y)
        for (int x = ix0; x < ix1; ++x) {
            double px = x + 0.5, py = y + 0.5, d = -1e300;
            for (int e = 0; e < 3; ++e)
                d = fmax(d, nx[e] * px + ny[e] * py - off[e]);
            double coverage = clamp01(0.5 - d);
            if (coverage > 0.0)
                mask_put(m, x, y, coverage);
        }
}

/* An axis-aligned rectangle: each pixel's exact area inside it. */
static void mask_rect(mask *m, double x0, double y0, double x1, double y1)
{
    if (!m->c)
        return;
    int ix0, iy0, ix1, iy1;
    mask_range(m, x0, y0, x1, y1, &ix0, &iy0, &ix1, &iy1);
    for (int y = iy0; y < iy1; ++y) {
        double cy = fmin(y + 1.0, y1) - fmax((double)y, y0);
        if (cy <= 0.0)
            continue;
        for (int x = ix0; x < ix1; ++x) {
            double cx = fmin(x + 1.0, x1) - fmax((double)x, x0);
            if (cx > 0.0)
                mask_put(m, x, y, clamp01(cx * cy));
        }
    }
}

/* Blends colour over the image where m covers it (one rounding per channel). */
static void mask_blend(const mask *m, oit_image *image, const uint8_t colour[3])
{
    if (!m->c)
        return;
    for (int y = 0; y < m->h; ++y)
        for (int x = 0; x < m->w; ++x) {
            double c = m->c[(size_t)y * (size_t)m->w + (size_t)x];
            if (c <= 0.0)
                continue;
            uint8_t *p = image->rgba + ((size_t)(m->y0 + y) * (size_t)image->width + (size_t)(m->x0 + x)) * 4;
            for (int k = 0; k < 3; ++k)
                p[k] = (uint8_t)floor(p[k] * (1.0 - c) + colour[k] * c + 0.5);
            p[3] = (uint8_t)floor(p[3] * (1.0 - c) + 255.0 * c + 0.5);
        }
}

/* -------------------------------------------------------------- font */

/* Polylines on a grid of half units, x 0..8 (4 units wide), y 0..12 (6
 * units high, 0 the baseline, up): "xy" pairs, '0'-'9' then 'a'-'c' for
 * 10-12, ' ' between points, '|' lifts the pen. */
typedef struct glyph {
    char c;
    const char *strokes;
} glyph;

static const glyph font[] = {
    {'0', "20 60 82 8a 6c 2c 0a 02 20"},
    {'1', "2a 4c 40|20 60"},
    {'2', "0a 2c 6c 8a 88 00 80"},
    {'3', "0a 2c 6c 8a 88 66 26|66 84 82 60 20 02"},
    {'4', "60 6c 04 84"},
    {'5', "8c 0c 06 66 84 82 60 20 02"},
    {'6', "8a 6c 2c 0a 02 20 60 82 84 66 06"},
    {'7', "0c 8c 20"},
    {'8', "26 08 0a 2c 6c 8a 88 66 26 04 02 20 60 82 84 66"},
    {'9', "86 26 08 0a 2c 6c 8a 82 60 20 02"},
    {'.', "40 40"},
    {'m', "00 08|06 28 46 40|46 68 86 80"},
    {'X', "00 8c|0c 80"},
    {'Y', "0c 46 8c|46 40"},
    {'Z', "0c 8c 00 80"},
};

#define GLYPH_ADVANCE 6.0 /* units: 4 wide, 2 apart */
#define SPACE_ADVANCE 4.0

static double coordinate(char c)
{
    return (c >= 'a' ? c - 'a' + 10 : c - '0') * 0.5;
}

static double text_width_units(const char *text)
{
    double w = 0.0;
    for (const char *c = text; *c; ++c)
        w += *c == ' ' ? SPACE_ADVANCE : GLYPH_ADVANCE;
    return w > 0.0 ? w - (GLYPH_ADVANCE - 4.0) : 0.0;
}

/* The text centred on (cx, cy), its capitals h pixels high. */
static void mask_text(mask *m, const char *text, double cx, double cy, double h, double radius)
{
    double unit = h / 6.0;
    double x = cx - 0.5 * text_width_units(text) * unit;
    double base = cy + 0.5 * h;
    for (const char *c = text; *c; ++c) {
        if (*c == ' ') {
            x += SPACE_ADVANCE * unit;
            continue;
        }
        for (size_t g = 0; g < sizeof font / sizeof font[0]; ++g) {
            if (font[g].c != *c)
                continue;
            const char *s = font[g].strokes;
            double px = 0.0, py = 0.0;
            bool pen = false;
            while (*s) {
                if (*s == '|') {
                    pen = false;
                    ++s;
                    continue;
                }
                if (*s == ' ') {
                    ++s;
                    continue;
                }
                double qx = x + coordinate(s[0]) * unit, qy = base - coordinate(s[1]) * unit;
                if (pen)
                    mask_stroke(m, px, py, qx, qy, radius);
                else if (s[2] != ' ') /* a lone point: a dot */
                    mask_stroke(m, qx, qy, qx, qy, radius);
                px = qx;
                py = qy;
                pen = true;
                s += 2;
            }
        }
        x += GLYPH_ADVANCE * unit;
    }
}

/* ------------------------------------------------------------ layout */

/* The aids' size unit in pixels for an image whose shorter side is m: 1 up to
 * 128 px, m / 128 to 256 px, then slower (2 + (m - 256) / 256: 9.4 at 2160). */
static double size_unit(int width, int height)
{
    double m = width < height ? width : height;
    if (m <= 128.0)
        return 1.0;
    if (m <= 256.0)
        return m / 128.0;
    return 2.0 + (m - 256.0) / 256.0;
}

#define AXIS_LENGTH 14.0   /* units */
#define AXIS_RADIUS 0.6    /* the shaft's half width */
#define HEAD_LENGTH 4.5
#define HEAD_HALF 2.0
#define LABEL_HEIGHT 6.0
#define LABEL_RADIUS 0.55
#define LABEL_GAP 4.5      /* from the tip to the label's centre */
#define MARGIN 3.0
#define TRIAD_REACH (AXIS_LENGTH + LABEL_GAP + 3.5)

static const uint8_t axis_colours[3][3] = {{214, 39, 40}, {30, 150, 40}, {31, 90, 220}};

/* The triad: the model's axes turned by the modelview's rotation. */
static oit_status draw_axes(oit_image *image, oit_corner corner, const double mv[16], oit_overlay_info *info,
                            oit_error *err)
{
    double u = size_unit(image->width, image->height);
    double reach = (TRIAD_REACH + MARGIN) * u;
    bool right = corner == OIT_CORNER_BOTTOM_RIGHT || corner == OIT_CORNER_TOP_RIGHT;
    bool top = corner == OIT_CORNER_TOP_LEFT || corner == OIT_CORNER_TOP_RIGHT;
    double ox = right ? image->width - reach : reach;
    double oy = top ? reach : image->height - reach;
    /* each model axis in eye space: the modelview's columns, normalized (a
     * scaled modelview turns the same) */
    double dir[3][3];
    for (int a = 0; a < 3; ++a) {
        double x = mv[a * 4 + 0], y = mv[a * 4 + 1], z = mv[a * 4 + 2];
        double len = sqrt(x * x + y * y + z * z);
        if (!(len > 0.0) || !isfinite(len))
            return oit_fail(err, OIT_E_INPUT, "axes: the modelview's rotation has a zero or non-finite column");
        dir[a][0] = x / len;
        dir[a][1] = y / len;
        dir[a][2] = z / len;
    }
    /* farthest first: an axis pointing away is drawn under one pointing at the eye */
    int order[3] = {0, 1, 2};
    for (int i = 1; i < 3; ++i)
        for (int j = i; j > 0 && dir[order[j]][2] < dir[order[j - 1]][2]; --j) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    static const char *const letters[3] = {"X", "Y", "Z"};
    double L = AXIS_LENGTH * u;
    for (int i = 0; i < 3; ++i) {
        int a = order[i];
        double sx = dir[a][0], sy = -dir[a][1]; /* image y runs down */
        double planar = sqrt(sx * sx + sy * sy);
        double tx = ox + sx * L, ty = oy + sy * L;
        mask m;
        oit_status status = mask_create(&m, image, ox - reach, oy - reach, ox + reach, oy + reach, err);
        if (status != OIT_OK)
            return status;
        double shown = planar * L;
        if (shown < HEAD_LENGTH * u * 0.8) {
            /* nearly along the line of sight: a dot */
            mask_stroke(&m, tx, ty, tx, ty, HEAD_HALF * u * 0.8);
        } else {
            double ux = sx / planar, uy = sy / planar;
            double head = HEAD_LENGTH * u;
            double bx = tx - ux * head, by = ty - uy * head;
            mask_stroke(&m, ox, oy, bx, by, AXIS_RADIUS * u);
            double tri[3][2] = {{tx + ux * 0.5 * u, ty + uy * 0.5 * u},
                                {bx - uy * HEAD_HALF * u, by + ux * HEAD_HALF * u},
                                {bx + uy * HEAD_HALF * u, by - ux * HEAD_HALF * u}};
            mask_triangle(&m, tri);
        }
        /* the letter beyond the tip (up and right of a dot) */
        double lx, ly;
        if (planar > 1e-6) {
            double gap = LABEL_GAP * u;
            lx = tx + sx / planar * gap;
            ly = ty + sy / planar * gap;
        } else {
            lx = tx + 0.7 * LABEL_GAP * u;
            ly = ty - 0.7 * LABEL_GAP * u;
        }
        mask_text(&m, letters[a], lx, ly, LABEL_HEIGHT * u, fmax(LABEL_RADIUS * u, 0.55));
        mask_blend(&m, image, axis_colours[a]);
        mask_free(&m);
        if (info)
            for (int k = 0; k < 2; ++k)
                info->axes_directions[a][k] = k ? sy : sx;
    }
    if (info) {
        info->axes = true;
        info->axes_origin[0] = ox;
        info->axes_origin[1] = oy;
        info->axes_length = L;
    }
    return OIT_OK;
}

/* Clip coordinates of an eye-space point. */
static void to_clip(const double p[16], const double e[3], double clip[4])
{
    for (int r = 0; r < 4; ++r)
        clip[r] = p[0 * 4 + r] * e[0] + p[1 * 4 + r] * e[1] + p[2 * 4 + r] * e[2] + p[3 * 4 + r];
}

/* 10^k exactly for the integers a double holds, by multiplication. */
static double power_of_ten(int k)
{
    double v = 1.0;
    for (int i = 0; i < (k < 0 ? -k : k); ++i)
        v *= 10.0;
    return k < 0 ? 1.0 / v : v;
}

static oit_status draw_scale_bar(oit_image *image, const oit_overlay_options *options, const double mv[16],
                                 const double projection[16], const oit_model *model, oit_overlay_info *info,
                                 oit_error *err)
{
    /* the model's centre (the default camera's orbit centre) in eye space */
    double centre[3];
    for (int r = 0; r < 3; ++r)
        centre[r] = mv[0 * 4 + r] * model->origin[0] + mv[1 * 4 + r] * model->origin[1] +
                    mv[2 * 4 + r] * model->origin[2] + mv[3 * 4 + r];
    /* model units per eye unit: the modelview's scale (the mean of its columns' lengths) */
    double scale = 0.0;
    for (int a = 0; a < 3; ++a)
        scale += sqrt(mv[a * 4] * mv[a * 4] + mv[a * 4 + 1] * mv[a * 4 + 1] + mv[a * 4 + 2] * mv[a * 4 + 2]) / 3.0;
    double moved[3] = {centre[0] + 1.0, centre[1], centre[2]};
    double c0[4], c1[4];
    to_clip(projection, centre, c0);
    to_clip(projection, moved, c1);
    if (!(c0[3] > 0.0) || !(c1[3] > 0.0) || !(scale > 0.0)) {
        if (info)
            snprintf(info->scale_problem, sizeof info->scale_problem,
                     "the model's centre is behind the camera: no scale bar");
        return OIT_OK;
    }
    /* pixels per eye unit along x at the centre's depth, then per model unit */
    double per_eye = fabs(c1[0] / c1[3] - c0[0] / c0[3]) * 0.5 * image->width;
    double ppu = per_eye * scale;
    if (!(ppu > 0.0) || !isfinite(ppu)) {
        if (info)
            snprintf(info->scale_problem, sizeof info->scale_problem, "the projection gives no length: no scale bar");
        return OIT_OK;
    }
    double u = size_unit(image->width, image->height);
    /* the longest 1, 2 or 5 x 10^k that fits a quarter of the width */
    double target = 0.25 * image->width / ppu;
    double magnitude = floor(log10(target)); /* +-inf or NaN for a scale out of range */
    if (!(magnitude >= -30.0 && magnitude <= 30.0)) {
        if (info)
            snprintf(info->scale_problem, sizeof info->scale_problem,
                     "the scale (%g pixels per unit) is out of range: no scale bar", ppu);
        return OIT_OK;
    }
    int k = (int)magnitude;
    double value = 0.0;
    for (int step = k - 1; step <= k + 1; ++step)
        for (int i = 0; i < 3; ++i) {
            static const int nice[3] = {1, 2, 5};
            double v = nice[i] * power_of_ten(step);
            if (v <= target * (1.0 + 1e-12) && v > value) {
                value = v;
                k = step;
            }
        }
    double pixels = value * ppu;
    /* units: B-rep imports (STEP, IGES) hold millimetres */
    bool mm = model->unit_name[0] || model->unit_to_mm > 0.0 || model->tessellation_linear_mm > 0.0;
    char number[32], label[48];
    snprintf(number, sizeof number, "%.*f", k < 0 ? -k : 0, value);
    snprintf(label, sizeof label, "%s%s", number, mm ? " mm" : "");

    /* placement: the bottom-right corner, or bottom-left when the triad is there */
    bool left = options->axes && options->axes_corner == OIT_CORNER_BOTTOM_RIGHT;
    double margin = 4.0 * u, thickness = 1.5 * u, tick = 4.0 * u, label_h = 6.0 * u;
    double x0 = left ? margin : image->width - margin - pixels;
    double x1 = x0 + pixels;
    double y1 = image->height - margin, y0 = y1 - thickness;
    double label_cy = y0 - 2.0 * u - 0.5 * label_h - 0.5 * tick;
    double label_w = text_width_units(label) * label_h / 6.0;
    double label_cx = 0.5 * (x0 + x1);
    double bx0 = fmin(x0, label_cx - 0.5 * label_w) - u, bx1 = fmax(x1, label_cx + 0.5 * label_w) + u;
    double by0 = label_cy - 0.5 * label_h - u;
    /* dark on a light frame, light on a dark one: the mean luminance under it */
    double sum = 0.0;
    long count = 0;
    for (int y = (int)fmax(0.0, floor(by0)); y < (int)fmin(image->height, ceil(y1)); ++y)
        for (int x = (int)fmax(0.0, floor(bx0)); x < (int)fmin(image->width, ceil(bx1)); ++x) {
            const uint8_t *p = image->rgba + ((size_t)y * (size_t)image->width + (size_t)x) * 4;
            sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            ++count;
        }
    bool dark = count == 0 || sum / count >= 128.0;
    static const uint8_t ink_dark[3] = {20, 20, 20}, ink_light[3] = {240, 240, 240};
    mask m;
    oit_status status = mask_create(&m, image, bx0, by0, bx1, y1, err);
    if (status != OIT_OK)
        return status;
    mask_rect(&m, x0, y0, x1, y1);
    double tick_w = fmin(thickness, 0.5 * pixels);
    mask_rect(&m, x0, y1 - tick, x0 + tick_w, y1);
    mask_rect(&m, x1 - tick_w, y1 - tick, x1, y1);
    mask_text(&m, label, label_cx, label_cy, label_h, fmax(0.55 * u, 0.55));
    mask_blend(&m, image, dark ? ink_dark : ink_light);
    mask_free(&m);
    if (info) {
        info->scale_bar = true;
        info->scale_value = value;
        snprintf(info->scale_units, sizeof info->scale_units, "%s", mm ? "mm" : "");
        snprintf(info->scale_label, sizeof info->scale_label, "%s", label);
        info->scale_pixels = pixels;
        info->scale_pixels_per_unit = ppu;
        info->scale_start[0] = x0;
        info->scale_start[1] = y0;
        info->scale_thickness = thickness;
        info->scale_exact = projection[3] == 0.0 && projection[7] == 0.0 && projection[11] == 0.0;
    }
    return OIT_OK;
}

oit_status oit_overlay_draw(oit_image *image, const oit_overlay_options *options, const double modelview[16],
                            const double projection[16], const oit_model *model, oit_overlay_info *info,
                            oit_error *err)
{
    if (info)
        memset(info, 0, sizeof *info);
    if (!image || !image->rgba || image->width <= 0 || image->height <= 0)
        return oit_fail(err, OIT_E_INPUT, "overlay: no image to draw on");
    if ((unsigned)options->axes_corner >= 4)
        return oit_fail(err, OIT_E_INPUT, "overlay: corner %d is not one of the four", (int)options->axes_corner);
    for (int i = 0; i < 16; ++i)
        if (!isfinite(modelview[i]) || !isfinite(projection[i]))
            return oit_fail(err, OIT_E_INPUT, "overlay: the matrices hold a non-finite number");
    oit_status status = OIT_OK;
    /* the bar first: the triad stays on top where a tiny image makes them meet */
    if (options->scale_bar)
        status = draw_scale_bar(image, options, modelview, projection, model, info, err);
    if (status == OIT_OK && options->axes)
        status = draw_axes(image, options->axes_corner, modelview, info, err);
    return status;
}
