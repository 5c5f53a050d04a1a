/* reference_internal.h: what the reference's files share, and nothing else
 * does: alg_reference.c (the operations table, the fragment store, sort and
 * compose), reference_raster.c (the oracle's own maths, the vertex stage and
 * the rasterizer) and pick.c (one pixel's fragments, ranked by what they
 * add to its colour). Internal to the oracle, which shares no computation
 * with what it checks (alg_reference.c, the header comment). */
#ifndef OIT_REFERENCE_INTERNAL_H
#define OIT_REFERENCE_INTERNAL_H

#include <stdbool.h>
#include <stdint.h>

#include "oit.h"

typedef struct reference_fragment {
    float depth;       /* canonical depth along the pixel's ray, as oit_canonical_depth() */
    uint32_t triangle; /* gl_PrimitiveID: ties in depth sort by it */
    float rgb[3];      /* shaded colour */
    float alpha;
    float local;       /* the local modulation's factor (component opacity x focus) */
} reference_fragment;

/* Every fragment list sorted as the reference composites it: by depth as
 * float, then triangle index. */
void oit_reference_sort_fragments(reference_fragment *list, size_t count);

/* OIT_E_INPUT if an index or component id is out of range (the rasterizer
 * trusts them). */
oit_status oit_reference_check_model(const oit_model *model, oit_error *err);

/* A vertex after the vertex stage, in double. */
typedef struct clip_vertex {
    double clip[4];   /* projection * modelview * position */
    double eye[3];    /* (modelview * position).xyz */
    double normal[3]; /* normal matrix * normal, not normalized */
} clip_vertex;

/* Everything the rasterizer needs for one frame. */
typedef struct raster_context {
    int width, height;
    /* the pixels rasterized, in GL's rows: the whole image unless a pick
     * narrows it to one pixel; pixel_counts and pixel_offsets index them
     * row by row from (region_x, region_y) */
    int region_x, region_y, region_width, region_height;
    bool fill; /* false: count fragments per pixel; true: store shaded fragments */
    uint32_t *pixel_counts;
    const uint64_t *pixel_offsets;
    reference_fragment *fragments;
    const oit_frame_settings *frame;
    double guard_band_x, guard_band_y; /* |x| <= g * w, |y| <= g * w in clip space */
    /* the current triangle's flat inputs */
    uint32_t triangle;
    uint32_t component;
    const float *colour;  /* the material's, or tinted_colour for a highlighted part */
    float tinted_colour[3];
    float material_alpha; /* clamp(frame alpha * material opacity, 0, 1) */
    double part_alpha;    /* times the component's local opacity */
    float alpha;          /* part_alpha as the fragment's float opacity */
    /* local modulation: a focus shape makes alpha per fragment, and fragments
     * whose alpha is 0 are not stored (so the counting pass evaluates it too) */
    bool per_fragment_alpha;
    double focus_region;  /* the focus shapes' fall-off length R (model units) */
    double inverse_modelview[16];
    /* canonical depth (common/canonical_depth.glsl): the current triangle's
     * coplanar plane in eye space (through plane_to_eye, the inverse modelview,
     * or the identity where it has none, as the GPU set-up), and the inverse
     * projection for each pixel's ray */
    double plane_to_eye[16];
    double inverse_projection[16];
    double eye_plane[4];
    bool use_plane;
    /* section planes (docs/sections.md): the eye-space planes the GPU gets
     * (section_eye_planes), the current triangle's cap section (0, or 1 + the
     * section its provoking vertex caps) and whether they cut its part */
    float section_planes[OIT_SECTION_PLANES_MAX][4];
    uint32_t section_count;
    uint32_t section_cap;
    bool section_cut;
} raster_context;

/* The inverse of a column-major 4x4, in double, by Gauss-Jordan elimination
 * with partial pivoting on [m | I]; false (and zeros) if a pivot is 0 or not
 * finite. (The GPU set-up inverts by cofactors in local_modulation.c.) */
bool oit_reference_invert4(const double m[16], double out[16]);

/* The eye-space points of pixel (x, y)'s centre at NDC depth -1 and +1: the
 * ray along which the canonical depth runs from 0 to 1. */
void oit_reference_pixel_ray(const double inverse_projection[16], int width, int height, int64_t x,
                             int64_t y, double near_point[3], double far_point[3]);

/* The vertex stage, in double: clip position, eye position, eye normal. */
void oit_reference_vertex_stage(const oit_model *model, const oit_frame_settings *frame,
                                clip_vertex *out);

/* The frame's rasterizer state for a width x height image counting into
 * pixel_counts (ctx->fill false; to store, set fill, pixel_offsets and
 * fragments). OIT_E_INPUT when a focus shape needs a singular modelview. */
oit_status oit_reference_raster_begin(raster_context *ctx, const oit_frame_settings *frame, int width,
                                      int height, uint32_t *pixel_counts,
                                      const uint64_t *pixel_offsets, oit_error *err);

/* Every triangle of the model: counts its fragments per pixel, or (ctx->fill)
 * stores them shaded at their pixel's offset. */
void oit_reference_rasterize(raster_context *ctx, const oit_model *model, const clip_vertex *vertices);
/* The same for these triangles only, in the order given (ascending, for the
 * reference's tie order): a pick's candidates. */
void oit_reference_rasterize_some(raster_context *ctx, const oit_model *model, const clip_vertex *vertices,
                                  const uint32_t *triangles, uint32_t count);

#endif
