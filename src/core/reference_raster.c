/*
 * reference_raster.c: the reference's own pipeline up to the fragments it
 * stores: the oracle's own maths (a 4x4 inverse, the focus shapes, shading and
 * contrast), the vertex stage in double, clipping, snapping, coverage by
 * exact edge functions with llvmpipe's tie rule, perspective-correct
 * interpolation and the canonical depth. What it reproduces of the GL and
 * why, and what it shares by design: alg_reference.c's header comment.
 */
#include <math.h>
#include <string.h>

#include "oit_shared.h" /* constants shared with the shaders: definitions */
#include "reference_internal.h"

/* llvmpipe's subpixel precision: 8 bits. */
#define SUBPIXEL_BITS 8
#define SUBPIXEL_ONE (1 << SUBPIXEL_BITS)
#define SUBPIXEL_HALF (SUBPIXEL_ONE / 2)

/* Window coordinates stay within +-2^20 pixels after guard-band clipping, so
 * snapped coordinates need 29 bits and edge functions fit easily in int64. */
#define GUARD_BAND_PIXELS 1048576.0

/* The smallest clip w kept: guards the perspective divide for odd projections. */
#define CLIP_W_EPSILON 1e-12

/* Clipping adds at most one vertex per plane: 3 + 7. */
#define CLIP_PLANE_COUNT 7
#define CLIP_MAX_VERTICES (3 + CLIP_PLANE_COUNT)

/* ------------------------------------------------- the oracle's own maths */

bool oit_reference_invert4(const double m[16], double out[16])
{
    double a[4][8]; /* a[row][col] */
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            a[row][col] = m[col * 4 + row];
            a[row][4 + col] = row == col ? 1.0 : 0.0;
        }
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int row = col + 1; row < 4; ++row)
            if (fabs(a[row][col]) > fabs(a[pivot][col]))
                pivot = row;
        double p = a[pivot][col];
        if (!(fabs(p) > 0.0) || !isfinite(p)) {
            memset(out, 0, 16 * sizeof out[0]);
            return false;
        }
        if (pivot != col)
            for (int k = 0; k < 8; ++k) {
                double t = a[col][k];
                a[col][k] = a[pivot][k];
                a[pivot][k] = t;
            }
        for (int k = 0; k < 8; ++k)
            a[col][k] /= p;
        for (int row = 0; row < 4; ++row) {
            double factor = a[row][col];
            if (row == col || factor == 0.0)
                continue;
            for (int k = 0; k < 8; ++k)
                a[row][k] -= factor * a[col][k];
        }
    }
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            out[col * 4 + row] = a[row][4 + col];
            if (!isfinite(out[col * 4 + row])) {
                memset(out, 0, 16 * sizeof out[0]);
                return false;
            }
        }
    return true;
}

/* The focus shapes' fall-off length R (docs/modulation.md): --focus-region, or
 * when that is auto (0) the default the caller set (the CLI: a quarter of the
 * bounding radius), or when neither is set 1 (oit.h, oit_local_modulation). */
static double focus_region(const oit_frame_settings *frame)
{
    if (frame->modulation.focus_region > 0.0f)
        return frame->modulation.focus_region;
    return frame->local.focus_default_region > 0.0f ? frame->local.focus_default_region : 1.0;
}

/* The distance from model position p to the focus shape (docs/modulation.md):
 * to the point; to the plane A x + B y + C z + D = 0, |A x + B y + C z + D| /
 * |(A, B, C)|; to the box, the Euclidean distance to its nearest point (0
 * inside). */
static double focus_distance(const oit_local_modulation *local, const double p[3])
{
    const double *f = local->focus;
    double sum = 0.0;
    switch (local->focus_shape) {
    case OIT_FOCUS_POINT:
        for (int k = 0; k < 3; ++k)
            sum += (p[k] - f[k]) * (p[k] - f[k]);
        return sqrt(sum);
    case OIT_FOCUS_PLANE: {
        double normal = sqrt((double)f[0] * f[0] + (double)f[1] * f[1] + (double)f[2] * f[2]);
        double height = (double)f[0] * p[0] + (double)f[1] * p[1] + (double)f[2] * p[2] + f[3];
        return normal > 0.0 ? fabs(height) / normal : 0.0; /* a 0 normal is refused on parsing */
    }
    case OIT_FOCUS_BOX:
        for (int k = 0; k < 3; ++k) {
            double gap = fmax(fmax(f[k] - p[k], p[k] - f[3 + k]), 0.0); /* min f[k], max f[3+k] */
            sum += gap * gap;
        }
        return sqrt(sum);
    case OIT_FOCUS_NONE:
    default: return 0.0;
    }
}

/* The fragment's opacity with a focus shape: the part's alpha times
 * saturate(distance / R). */
static double focus_alpha(const raster_context *ctx, const double model_position[3])
{
    double x = focus_distance(&ctx->frame->local, model_position) / ctx->focus_region;
    return ctx->part_alpha * (x > 1.0 ? 1.0 : (x > 0.0 ? x : 0.0));
}

/* The sections as eye-space planes q (fragment at eye position e removed
 * where q . (e, 1) > 0): q = (n, -d) times the inverse modelview, with the
 * oracle's own inverse, in double, rounded to float once as the GPU's are
 * (docs/sections.md). frame is relative: its sections were moved to the
 * model's origin and checked by oit_frame_relative. */
static oit_status section_eye_planes(const oit_frame_settings *frame, bool modelview_regular,
                                     raster_context *ctx, oit_error *err)
{
    const oit_local_modulation *local = &frame->local;
    ctx->section_count = 0;
    if (local->section_count == 0)
        return OIT_OK;
    if (!modelview_regular)
        return oit_fail(err, OIT_E_INPUT,
                        "reference: the modelview is singular, so section planes (model "
                        "coordinates) cannot be placed");
    uint32_t count = local->section_count < OIT_SECTION_PLANES_MAX ? local->section_count
                                                                   : OIT_SECTION_PLANES_MAX;
    for (uint32_t i = 0; i < count; ++i) {
        const double *s = local->sections[i];
        const double row[4] = {s[0], s[1], s[2], -s[3]};
        for (int col = 0; col < 4; ++col) {
            double q = 0.0;
            for (int k = 0; k < 4; ++k)
                q += row[k] * ctx->inverse_modelview[col * 4 + k];
            ctx->section_planes[i][col] = (float)q;
            if (!isfinite(ctx->section_planes[i][col]))
                return oit_fail(err, OIT_E_INPUT,
                                "reference: section plane %u is too large for single precision in eye space",
                                i + 1);
        }
    }
    ctx->section_count = count;
    return OIT_OK;
}

/* Whether the sections cut part component (section_parts; NULL: every part). */
static bool section_cuts_part(const oit_local_modulation *local, uint32_t component)
{
    if (!local->section_parts)
        return true;
    return component < local->section_parts_count && local->section_parts[component] != 0;
}

/* The shaded, contrasted colour (docs/cli.md, --shading; docs/modulation.md,
 * --contrast): flat is the material colour; headlight is colour * (ambient +
 * (1 - ambient) |n . v|) with n the normalised eye normal and v the unit vector
 * towards the eye (two-sided); a fragment at the eye looks along +z, one without
 * a normal is unlit (factor 1). Then rgb = saturate((rgb - 0.5) C + 0.5) unless
 * C is 0 (unset) or 1. */
static void shade(const oit_frame_settings *frame, const float colour[3], const float normal[3],
                  const float eye[3], float out[3])
{
    double factor = 1.0;
    if (frame->shading == OIT_SHADE_HEADLIGHT) {
        double n[3] = {normal[0], normal[1], normal[2]}, e[3] = {eye[0], eye[1], eye[2]};
        double n_length = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        double e_length = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
        if (n_length > 0.0) {
            double cosine = e_length > 0.0 ? -(n[0] * e[0] + n[1] * e[1] + n[2] * e[2]) / e_length
                                           : n[2];
            double ambient = OIT_HEADLIGHT_AMBIENT_PERCENT / 100.0;
            factor = ambient + (1.0 - ambient) * fabs(cosine / n_length);
        }
    }
    double contrast = frame->local.contrast;
    bool contrasted = contrast != 0.0 && contrast != 1.0;
    for (int k = 0; k < 3; ++k) {
        double c = colour[k] * factor;
        if (contrasted) {
            c = (c - 0.5) * contrast + 0.5;
            c = c < 0.0 ? 0.0 : (c > 1.0 ? 1.0 : c);
        }
        out[k] = (float)c;
    }
}

/* ------------------------------------------ the vertex stage, the set-up */

void oit_reference_vertex_stage(const oit_model *model, const oit_frame_settings *frame,
                                clip_vertex *out)
{
    /* normals take the inverse transpose of the modelview's 3x3: invert it as a
     * 4x4 with (0, 0, 0, 1) for the rest; n_eye[row] = sum_k inverse(k, row) n[k] */
    double upper[16] = {0.0}, inverse[16];
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            upper[col * 4 + row] = frame->modelview[col * 4 + row];
    upper[15] = 1.0;
    double normal_matrix[9]; /* column-major 3x3 */
    bool regular = oit_reference_invert4(upper, inverse); /* always, after oit_matrices_validate */
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            normal_matrix[col * 3 + row] = regular ? inverse[row * 4 + col] : 0.0;
    const double *mv = frame->modelview, *pr = frame->projection;
    for (uint32_t v = 0; v < model->vertex_count; ++v) {
        const float *p = &model->positions[3 * (size_t)v];
        double eye[4];
        for (int row = 0; row < 4; ++row)
            eye[row] = mv[row] * p[0] + mv[4 + row] * p[1] + mv[8 + row] * p[2] + mv[12 + row];
        clip_vertex *o = &out[v];
        for (int row = 0; row < 4; ++row)
            o->clip[row] = pr[row] * eye[0] + pr[4 + row] * eye[1] + pr[8 + row] * eye[2] +
                           pr[12 + row] * eye[3];
        for (int i = 0; i < 3; ++i)
            o->eye[i] = eye[i];
        if (model->normals) {
            const float *n = &model->normals[3 * (size_t)v];
            for (int row = 0; row < 3; ++row)
                o->normal[row] = normal_matrix[row] * n[0] + normal_matrix[3 + row] * n[1] +
                                 normal_matrix[6 + row] * n[2];
        } else {
            o->normal[0] = o->normal[1] = o->normal[2] = 0.0;
        }
    }
}

oit_status oit_reference_raster_begin(raster_context *ctx, const oit_frame_settings *frame, int width,
                                      int height, uint32_t *pixel_counts,
                                      const uint64_t *pixel_offsets, oit_error *err)
{
    *ctx = (raster_context){
        .width = width,
        .height = height,
        .region_width = width,
        .region_height = height,
        .pixel_counts = pixel_counts,
        .pixel_offsets = pixel_offsets,
        .frame = frame,
        .guard_band_x = GUARD_BAND_PIXELS / width,
        .guard_band_y = GUARD_BAND_PIXELS / height,
        .per_fragment_alpha = frame->local.focus_shape != OIT_FOCUS_NONE,
    };
    oit_reference_invert4(frame->projection, ctx->inverse_projection); /* validated regular */
    ctx->focus_region = focus_region(frame);
    bool modelview_regular = oit_reference_invert4(frame->modelview, ctx->inverse_modelview);
    if (ctx->per_fragment_alpha && !modelview_regular)
        return oit_fail(err, OIT_E_INPUT,
                        "reference: the modelview is singular, so focus shapes (model coordinates) "
                        "cannot be placed");
    oit_status status = section_eye_planes(frame, modelview_regular, ctx, err);
    if (status != OIT_OK)
        return status;
    /* sections make the opacity per fragment too: the counting pass must skip
     * what they remove, as the storing pass does */
    ctx->per_fragment_alpha |= ctx->section_count > 0;
    if (modelview_regular)
        memcpy(ctx->plane_to_eye, ctx->inverse_modelview, sizeof ctx->plane_to_eye);
    else
        for (int i = 0; i < 16; ++i)
            ctx->plane_to_eye[i] = i % 5 == 0 ? 1.0 : 0.0;
    return OIT_OK;
}

/* ----------------------------------------------------------- rasterizing */

/* Floor division for possibly negative fixed-point values. */
static int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0)))
        --q;
    return q;
}

/*
 * The tie rule for a pixel centre exactly on an edge. The triangle is oriented
 * counter-clockwise in GL window coordinates (y up), so its interior lies left of
 * each edge a->b. Gallium rasterizes GL framebuffer objects with its "top-left"
 * rule in memory rows, where row 0 is GL's y = 0; in GL's y-up coordinates that
 * includes left edges (heading down, dy < 0) and horizontal edges with the
 * interior above them (heading right, dx > 0). Opposite edges of two triangles
 * sharing an edge get opposite answers, so shared edges are covered once.
 * (Checked against llvmpipe with triangles on a half-pixel grid: identical; the
 * top-left rule in y-up coordinates differs on about 2% of such triangles.)
 */
static bool edge_is_inclusive(int64_t dx, int64_t dy)
{
    return dy < 0 || (dy == 0 && dx > 0);
}

typedef struct window_vertex {
    double window_x, window_y; /* window position before snapping */
    int64_t x, y;              /* snapped window position, 1/256 pixel: coverage */
    double inv_w;              /* 1 / clip w, for perspective-correct interpolation */
    const clip_vertex *attributes;
} window_vertex;

/* The nearest integer, ties to even: llvmpipe snaps with SSE's float-to-int
 * conversion in its default rounding mode. A vertex exactly half-way between
 * two 1/256 steps goes to the even one. (floor(value + 0.5), or llround's ties
 * away from zero, differ from it there.) value - floor(value) is exact. */
static int64_t round_half_even(double value)
{
    double below = floor(value);
    double fraction = value - below;
    if (fraction > 0.5 || (fraction == 0.5 && fmod(below, 2.0) != 0.0))
        below += 1.0;
    return (int64_t)below;
}

static void to_window(const raster_context *ctx, const clip_vertex *v, window_vertex *out)
{
    double inv_w = 1.0 / v->clip[3];
    double ndc_x = v->clip[0] * inv_w, ndc_y = v->clip[1] * inv_w;
    out->window_x = (ndc_x * 0.5 + 0.5) * ctx->width;
    out->window_y = (ndc_y * 0.5 + 0.5) * ctx->height;
    out->x = round_half_even(out->window_x * SUBPIXEL_ONE);
    out->y = round_half_even(out->window_y * SUBPIXEL_ONE);
    out->inv_w = inv_w;
    out->attributes = v;
}

/*
 * Snapping decides coverage only. Inputs are interpolated from the unsnapped
 * window positions, as llvmpipe's attribute planes are: a triangle's
 * screen-space barycentrics are b_i = (a_i x + b_i y + c_i) / area.
 */
typedef struct interpolation_plane {
    double step_x[3], step_y[3], offset[3]; /* per vertex, already divided by the area */
    bool use_snapped; /* unsnapped area is zero: fall back to the exact edge values */
    double inv_snapped_area;
} interpolation_plane;

static void interpolation_setup(const window_vertex v[3], int64_t snapped_area2,
                                interpolation_plane *plane)
{
    double area = (v[1].window_x - v[0].window_x) * (v[2].window_y - v[0].window_y) -
                  (v[1].window_y - v[0].window_y) * (v[2].window_x - v[0].window_x);
    plane->use_snapped = !(area != 0.0 && isfinite(area));
    plane->inv_snapped_area = 1.0 / (double)snapped_area2;
    if (plane->use_snapped)
        return;
    double inv_area = 1.0 / area;
    for (int i = 0; i < 3; ++i) {
        /* the edge opposite vertex i, from vertex i+1 to vertex i+2 */
        const window_vertex *a = &v[(i + 1) % 3], *b = &v[(i + 2) % 3];
        double dx = b->window_x - a->window_x, dy = b->window_y - a->window_y;
        plane->step_x[i] = -dy * inv_area;
        plane->step_y[i] = dx * inv_area;
        plane->offset[i] = (dy * a->window_x - dx * a->window_y) * inv_area;
    }
}

/* Whether a section plane removes the current triangle's fragment at eye
 * position eye (float, as the shaders interpolate it): the planes cut its
 * part and q . (eye, 1) > 0 for a plane q that is not the triangle's own cap
 * section (common/local_modulation.glsl, oit_section_removed; evaluated here
 * in double). */
static bool section_removes(const raster_context *ctx, const float eye[3])
{
    if (!ctx->section_cut)
        return false;
    for (uint32_t i = 0; i < ctx->section_count; ++i) {
        const float *q = ctx->section_planes[i];
        double side = (double)q[0] * eye[0] + (double)q[1] * eye[1] + (double)q[2] * eye[2] + (double)q[3];
        if (i + 1 != ctx->section_cap && side > 0.0)
            return true;
    }
    return false;
}

/* Interpolates the eye position and eye normal at pixel (x, y); returns the
 * fragment's opacity after local modulation, 0 where a section plane removes
 * it. (Its depth is canonical_depth's.) */
static float fragment_inputs(const raster_context *ctx, int64_t x, int64_t y,
                             const window_vertex v[3], const interpolation_plane *plane,
                             const int64_t edge[3], float eye[3], float normal[3])
{
    double b[3];
    if (plane->use_snapped) {
        for (int i = 0; i < 3; ++i)
            b[i] = (double)edge[i] * plane->inv_snapped_area;
    } else {
        double centre_x = (double)x + 0.5, centre_y = (double)y + 0.5;
        for (int i = 0; i < 3; ++i)
            b[i] = plane->step_x[i] * centre_x + plane->step_y[i] * centre_y + plane->offset[i];
    }
    /* perspective-correct weights */
    double p0 = b[0] * v[0].inv_w, p1 = b[1] * v[1].inv_w, p2 = b[2] * v[2].inv_w;
    double sum = p0 + p1 + p2;
    if (sum != 0.0) {
        p0 /= sum;
        p1 /= sum;
        p2 /= sum;
    }
    const clip_vertex *a0 = v[0].attributes, *a1 = v[1].attributes, *a2 = v[2].attributes;
    for (int i = 0; i < 3; ++i) {
        eye[i] = (float)(p0 * a0->eye[i] + p1 * a1->eye[i] + p2 * a2->eye[i]);
        normal[i] = (float)(p0 * a0->normal[i] + p1 * a1->normal[i] + p2 * a2->normal[i]);
    }
    if (section_removes(ctx, eye))
        return 0.0f;
    if (ctx->frame->local.focus_shape == OIT_FOCUS_NONE)
        return ctx->alpha;
    /* the model position from the (float) eye position, as the shaders do */
    const double *m = ctx->inverse_modelview;
    double model[3];
    for (int row = 0; row < 3; ++row)
        model[row] = m[row] * eye[0] + m[4 + row] * eye[1] + m[8 + row] * eye[2] + m[12 + row];
    return (float)focus_alpha(ctx, model);
}

/* (oit_pixel_ray in common/local_modulation.glsl computes it in float.) */
void oit_reference_pixel_ray(const double inverse_projection[16], int width, int height, int64_t x,
                             int64_t y, double near_point[3], double far_point[3])
{
    double ndc_x = ((double)x + 0.5) * 2.0 / width - 1.0, ndc_y = ((double)y + 0.5) * 2.0 / height - 1.0;
    for (int end = 0; end < 2; ++end) {
        double ndc[4] = {ndc_x, ndc_y, end ? 1.0 : -1.0, 1.0}, h[4] = {0.0, 0.0, 0.0, 0.0};
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col)
                h[row] += inverse_projection[col * 4 + row] * ndc[col];
        double *out = end ? far_point : near_point;
        for (int k = 0; k < 3; ++k)
            out[k] = h[k] / h[3];
    }
}

/* The canonical depth of the current triangle at pixel (x, y), as
 * oit_canonical_depth() (common/canonical_depth.glsl) computes it in float:
 * where its coplanar plane meets the pixel's ray, as a fraction of the ray
 * from the near-plane point to the far-plane point. A plane seen edge-on
 * takes the interpolated eye position's projection on the ray instead. */
static double canonical_depth(const raster_context *ctx, int64_t x, int64_t y, const float eye[3])
{
    double near_point[3], far_point[3], along[3];
    oit_reference_pixel_ray(ctx->inverse_projection, ctx->width, ctx->height, x, y, near_point, far_point);
    for (int k = 0; k < 3; ++k)
        along[k] = far_point[k] - near_point[k];
    const double *q = ctx->eye_plane;
    double slope = q[0] * along[0] + q[1] * along[1] + q[2] * along[2];
    double normal_length = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    double along_length2 = along[0] * along[0] + along[1] * along[1] + along[2] * along[2];
    double s;
    if (ctx->use_plane &&
        fabs(slope) > OIT_EDGE_ON_PLANE_PPM * 1e-6 * normal_length * sqrt(along_length2)) {
        s = -(q[0] * near_point[0] + q[1] * near_point[1] + q[2] * near_point[2] + q[3]) / slope;
    } else {
        s = 0.0;
        for (int k = 0; k < 3; ++k)
            s += ((double)eye[k] - near_point[k]) * along[k];
        s /= along_length2;
    }
    return s < 0.0 ? 0.0 : (s > OIT_CANONICAL_DEPTH_MAX ? OIT_CANONICAL_DEPTH_MAX : s);
}

/* Counting pass: would this fragment be stored (alpha > 0)? */
static bool fragment_kept(const raster_context *ctx, int64_t x, int64_t y,
                          const window_vertex v[3], const interpolation_plane *plane,
                          const int64_t edge[3])
{
    float eye[3], normal[3];
    return fragment_inputs(ctx, x, y, v, plane, edge, eye, normal) > 0.0f;
}

static void store_fragment(const raster_context *ctx, size_t pixel, int64_t x, int64_t y,
                           const window_vertex v[3], const interpolation_plane *plane,
                           const int64_t edge[3])
{
    float eye[3], normal[3];
    float alpha = fragment_inputs(ctx, x, y, v, plane, edge, eye, normal);
    if (!(alpha > 0.0f))
        return; /* alpha 0 is never stored (the counting pass skipped it too) */
    reference_fragment *f = &ctx->fragments[ctx->pixel_offsets[pixel] + ctx->pixel_counts[pixel]++];
    f->depth = (float)canonical_depth(ctx, x, y, eye);
    f->triangle = ctx->triangle;
    shade(ctx->frame, ctx->colour, normal, eye, f->rgb);
    f->alpha = alpha;
    f->local = ctx->material_alpha > 0.0f ? alpha / ctx->material_alpha : 0.0f;
}

/* Rasterize one triangle whose vertices are inside the clip volume (guard band). */
static void rasterize_clipped(raster_context *ctx, const clip_vertex *c0, const clip_vertex *c1,
                              const clip_vertex *c2)
{
    window_vertex v[3];
    to_window(ctx, c0, &v[0]);
    to_window(ctx, c1, &v[1]);
    to_window(ctx, c2, &v[2]);

    int64_t area2 = (v[1].x - v[0].x) * (v[2].y - v[0].y) - (v[1].y - v[0].y) * (v[2].x - v[0].x);
    if (area2 == 0)
        return; /* zero area after snapping: GL draws nothing */
    if (area2 < 0) {
        /* make it counter-clockwise; faces are not culled */
        window_vertex t = v[1];
        v[1] = v[2];
        v[2] = t;
        area2 = -area2;
    }

    int64_t min_x = v[0].x, max_x = v[0].x, min_y = v[0].y, max_y = v[0].y;
    for (int i = 1; i < 3; ++i) {
        min_x = v[i].x < min_x ? v[i].x : min_x;
        max_x = v[i].x > max_x ? v[i].x : max_x;
        min_y = v[i].y < min_y ? v[i].y : min_y;
        max_y = v[i].y > max_y ? v[i].y : max_y;
    }
    /* pixels whose centres (256 * p + 128) lie in the bounding box */
    int64_t x0 = -floor_div(-(min_x - SUBPIXEL_HALF), SUBPIXEL_ONE);
    int64_t x1 = floor_div(max_x - SUBPIXEL_HALF, SUBPIXEL_ONE);
    int64_t y0 = -floor_div(-(min_y - SUBPIXEL_HALF), SUBPIXEL_ONE);
    int64_t y1 = floor_div(max_y - SUBPIXEL_HALF, SUBPIXEL_ONE);
    if (x0 < ctx->region_x)
        x0 = ctx->region_x;
    if (y0 < ctx->region_y)
        y0 = ctx->region_y;
    if (x1 > ctx->region_x + ctx->region_width - 1)
        x1 = ctx->region_x + ctx->region_width - 1;
    if (y1 > ctx->region_y + ctx->region_height - 1)
        y1 = ctx->region_y + ctx->region_height - 1;
    if (x0 > x1 || y0 > y1)
        return;

    /* Edge i runs from vertex i+1 to vertex i+2 and is positive inside. The bias
     * makes "> 0, or == 0 on an inclusive edge" a single ">= 0" test. */
    int64_t step_x[3], step_y[3], row_start[3], bias[3];
    const int64_t start_x = x0 * SUBPIXEL_ONE + SUBPIXEL_HALF;
    const int64_t start_y = y0 * SUBPIXEL_ONE + SUBPIXEL_HALF;
    for (int i = 0; i < 3; ++i) {
        const window_vertex *a = &v[(i + 1) % 3], *b = &v[(i + 2) % 3];
        int64_t dx = b->x - a->x, dy = b->y - a->y;
        bias[i] = edge_is_inclusive(dx, dy) ? 0 : -1;
        row_start[i] = dx * (start_y - a->y) - dy * (start_x - a->x) + bias[i];
        step_x[i] = -dy * SUBPIXEL_ONE;
        step_y[i] = dx * SUBPIXEL_ONE;
    }

    interpolation_plane plane = {.use_snapped = true};
    if (ctx->fill || ctx->per_fragment_alpha)
        interpolation_setup(v, area2, &plane);

    const int region_width = ctx->region_width;
    for (int64_t y = y0; y <= y1; ++y) {
        int64_t e0 = row_start[0], e1 = row_start[1], e2 = row_start[2];
        size_t pixel = (size_t)(y - ctx->region_y) * (size_t)region_width + (size_t)(x0 - ctx->region_x);
        for (int64_t x = x0; x <= x1; ++x, ++pixel) {
            if ((e0 | e1 | e2) >= 0) {
                const int64_t edge[3] = {e0 - bias[0], e1 - bias[1], e2 - bias[2]};
                if (ctx->fill)
                    store_fragment(ctx, pixel, x, y, v, &plane, edge);
                else if (!ctx->per_fragment_alpha || fragment_kept(ctx, x, y, v, &plane, edge))
                    ctx->pixel_counts[pixel]++;
            }
            e0 += step_x[0];
            e1 += step_x[1];
            e2 += step_x[2];
        }
        row_start[0] += step_y[0];
        row_start[1] += step_y[1];
        row_start[2] += step_y[2];
    }
}

/* Signed distance to clip plane `plane`; inside when >= 0. */
static double plane_distance(const raster_context *ctx, const clip_vertex *v, int plane)
{
    const double *c = v->clip;
    switch (plane) {
    case 0: return c[3] - CLIP_W_EPSILON;       /* w > epsilon */
    case 1: return c[3] + c[2];                 /* near: z >= -w */
    case 2: return c[3] - c[2];                 /* far: z <= w */
    case 3: return ctx->guard_band_x * c[3] + c[0];
    case 4: return ctx->guard_band_x * c[3] - c[0];
    case 5: return ctx->guard_band_y * c[3] + c[1];
    default: return ctx->guard_band_y * c[3] - c[1];
    }
}

/* The intersection of edge (inside, outside) with a plane. Always computed from
 * the inside vertex, so triangles sharing the edge get the identical vertex. */
static void clip_intersect(const clip_vertex *inside, double d_inside, const clip_vertex *outside,
                           double d_outside, clip_vertex *out)
{
    double t = d_inside / (d_inside - d_outside);
    for (int i = 0; i < 4; ++i)
        out->clip[i] = inside->clip[i] + t * (outside->clip[i] - inside->clip[i]);
    for (int i = 0; i < 3; ++i) {
        out->eye[i] = inside->eye[i] + t * (outside->eye[i] - inside->eye[i]);
        out->normal[i] = inside->normal[i] + t * (outside->normal[i] - inside->normal[i]);
    }
}

static void rasterize_triangle(raster_context *ctx, const clip_vertex *a, const clip_vertex *b,
                               const clip_vertex *c)
{
    const clip_vertex *corner[3] = {a, b, c};
    unsigned outside_any = 0, outside_all = (1u << CLIP_PLANE_COUNT) - 1;
    for (int i = 0; i < 3; ++i) {
        unsigned outside = 0;
        for (int p = 0; p < CLIP_PLANE_COUNT; ++p)
            if (!(plane_distance(ctx, corner[i], p) >= 0.0))
                outside |= 1u << p;
        outside_any |= outside;
        outside_all &= outside;
    }
    if (outside_all)
        return; /* all three vertices outside one plane */
    if (!outside_any) {
        rasterize_clipped(ctx, a, b, c);
        return;
    }

    /* Sutherland-Hodgman against the planes the triangle crosses. */
    clip_vertex buffers[2][CLIP_MAX_VERTICES];
    clip_vertex *polygon = buffers[0], *next = buffers[1];
    int count = 3;
    polygon[0] = *a;
    polygon[1] = *b;
    polygon[2] = *c;
    for (int p = 0; p < CLIP_PLANE_COUNT && count >= 3; ++p) {
        if (!(outside_any & (1u << p)))
            continue;
        int next_count = 0;
        for (int i = 0; i < count; ++i) {
            const clip_vertex *cur = &polygon[i], *following = &polygon[(i + 1) % count];
            double d_cur = plane_distance(ctx, cur, p);
            double d_following = plane_distance(ctx, following, p);
            bool cur_in = d_cur >= 0.0, following_in = d_following >= 0.0;
            if (cur_in)
                next[next_count++] = *cur;
            if (cur_in != following_in) {
                if (cur_in)
                    clip_intersect(cur, d_cur, following, d_following, &next[next_count++]);
                else
                    clip_intersect(following, d_following, cur, d_cur, &next[next_count++]);
            }
        }
        clip_vertex *swap = polygon;
        polygon = next;
        next = swap;
        count = next_count;
    }
    for (int i = 1; i + 1 < count; ++i)
        rasterize_clipped(ctx, &polygon[0], &polygon[i], &polygon[i + 1]);
}

/* One triangle: its flat inputs, then clipping and coverage. */
static void rasterize_model_triangle(raster_context *ctx, const oit_model *model, const clip_vertex *vertices,
                                     uint32_t t)
{
    const uint32_t *index = &model->indices[3 * (size_t)t];
    ctx->triangle = t;
    /* flat inputs come from the provoking (last) vertex, as in GL */
    ctx->component = model->vertex_component[index[2]];
    const oit_component *component = &model->components[ctx->component];
    float alpha = ctx->frame->alpha * component->opacity;
    alpha = alpha < 0.0f ? 0.0f : (alpha > 1.0f ? 1.0f : alpha);
    ctx->material_alpha = alpha;
    /* the per-component opacity here; the focus factor comes per fragment */
    const oit_local_modulation *local = &ctx->frame->local;
    ctx->part_alpha = alpha;
    if (local->component_alpha && ctx->component < local->component_count)
        ctx->part_alpha *= local->component_alpha[ctx->component];
    ctx->alpha = (float)ctx->part_alpha;
    /* section planes: whether they cut the part, and the cap exemption of
     * the provoking vertex (oit_model.vertex_section_cap, the GPU's attribute bits) */
    ctx->section_cut = ctx->section_count > 0 && section_cuts_part(local, ctx->component);
    ctx->section_cap = model->vertex_section_cap ? model->vertex_section_cap[index[2]] : 0;
    ctx->colour = component->colour;
    /* selection highlight: the material colour mixed towards the highlight
     * colour before shading, as oit_local_tint (common/local_modulation.glsl) */
    float highlight[3];
    const float weight = oit_local_highlight(local, ctx->component, highlight);
    if (weight > 0.0f) {
        for (int c = 0; c < 3; ++c)
            ctx->tinted_colour[c] = component->colour[c] * (1.0f - weight) + highlight[c] * weight;
        ctx->colour = ctx->tinted_colour;
    }
    if (!(ctx->alpha > 0.0f))
        return; /* hidden parts and opacity 0: never stored */
    ctx->use_plane = ctx->fill && model->triangle_plane && model->planes;
    if (ctx->use_plane) {
        /* a plane q with q . (p, 1) = 0 in model space is q M^-1 in eye space
         * (eye = M p): row vector times the inverse modelview */
        const float *plane = model->planes + (size_t)model->triangle_plane[t] * 4;
        const double *inverse = ctx->plane_to_eye;
        for (int col = 0; col < 4; ++col)
            ctx->eye_plane[col] = plane[0] * inverse[col * 4] + plane[1] * inverse[col * 4 + 1] +
                                  plane[2] * inverse[col * 4 + 2] + plane[3] * inverse[col * 4 + 3];
    }
    rasterize_triangle(ctx, &vertices[index[0]], &vertices[index[1]], &vertices[index[2]]);
}

void oit_reference_rasterize(raster_context *ctx, const oit_model *model, const clip_vertex *vertices)
{
    for (uint32_t t = 0; t < model->triangle_count; ++t)
        rasterize_model_triangle(ctx, model, vertices, t);
}

void oit_reference_rasterize_some(raster_context *ctx, const oit_model *model, const clip_vertex *vertices,
                                  const uint32_t *triangles, uint32_t count)
{
    for (uint32_t i = 0; i < count; ++i)
        rasterize_model_triangle(ctx, model, vertices, triangles[i]);
}
