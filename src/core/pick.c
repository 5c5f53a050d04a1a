/*
 * pick.c: what one pixel shows, part by part (oit_pick_pixel in oit.h;
 * docs/algorithms.md, "Pick"). The reference's pipeline narrowed to one
 * pixel: the same vertex stage, coverage rule, canonical depth and tie
 * order (reference_raster.c, oit_reference_sort_fragments), then the
 * front-to-back weights alpha * T of its compose, summed per part. A click
 * through a faint shell thus picks what the eye sees behind it, not the
 * nearest surface, and the answer runs headless and exactly.
 */
#include <stdlib.h>
#include <string.h>

#include "reference_internal.h"

void oit_pick_release(oit_pick *pick)
{
    if (!pick)
        return;
    free(pick->parts);
    memset(pick, 0, sizeof *pick);
}

static int compare_parts(const void *pa, const void *pb)
{
    const oit_pick_part *a = pa, *b = pb;
    if (a->contribution != b->contribution)
        return a->contribution > b->contribution ? -1 : 1;
    if (a->depth != b->depth)
        return a->depth < b->depth ? -1 : 1;
    return (a->component > b->component) - (a->component < b->component);
}

/* The file-coordinate point at canonical depth s on pixel (x, gl_y)'s ray. */
static void fragment_point(const raster_context *ctx, const oit_model *model, int x, int gl_y, double s,
                           double out[3])
{
    double near_point[3], far_point[3], eye[3];
    oit_reference_pixel_ray(ctx->inverse_projection, ctx->width, ctx->height, x, gl_y, near_point, far_point);
    for (int k = 0; k < 3; ++k)
        eye[k] = near_point[k] + s * (far_point[k] - near_point[k]);
    const double *m = ctx->inverse_modelview; /* of the relative modelview: eye to relative */
    for (int row = 0; row < 3; ++row)
        out[row] = m[row] * eye[0] + m[4 + row] * eye[1] + m[8 + row] * eye[2] + m[12 + row] +
                   model->origin[row];
}

/* Weights of the sorted list, summed per part into out->parts (unsorted). */
static oit_status rank_parts(const raster_context *ctx, const oit_model *model, int x, int gl_y,
                             const reference_fragment *list, uint32_t count, oit_pick *out, oit_error *err)
{
    uint32_t *slot = malloc((size_t)model->component_count * sizeof *slot);
    out->parts = count ? calloc(count, sizeof *out->parts) : NULL;
    if (!slot || (count && !out->parts)) {
        free(slot);
        return oit_fail(err, OIT_E_RUNTIME, "pick: out of memory for %u fragments", count);
    }
    for (uint32_t c = 0; c < model->component_count; ++c)
        slot[c] = UINT32_MAX;
    double transmittance = 1.0;
    for (uint32_t i = 0; i < count; ++i) {
        const reference_fragment *f = &list[i];
        /* flat inputs, the component included, come from the provoking (last) vertex */
        uint32_t component = model->vertex_component[model->indices[3 * (size_t)f->triangle + 2]];
        double a = f->alpha;
        double weight = transmittance * a;
        transmittance *= 1.0 - a;
        if (slot[component] == UINT32_MAX) {
            /* the list is sorted, so a part's first fragment is its nearest */
            oit_pick_part *part = &out->parts[out->part_count];
            slot[component] = out->part_count++;
            part->component = component;
            part->depth = f->depth;
            part->triangle = f->triangle;
            fragment_point(ctx, model, x, gl_y, f->depth, part->point);
        }
        out->parts[slot[component]].contribution += weight;
    }
    free(slot);
    out->fragment_count = count;
    out->background = transmittance;
    if (out->part_count > 1)
        qsort(out->parts, out->part_count, sizeof *out->parts, compare_parts);
    return OIT_OK;
}

/* Margin of the candidate test, in pixels: far more than the 1/512 pixel
 * snapping can move a vertex. */
#define CANDIDATE_MARGIN_PIXELS 2.0

/* The triangles that may cover pixel (x, gl_y), ascending: all but those whose
 * three vertices lie in front of the eye (w > 0) and beyond the pixel on one
 * side, which cannot cover it (the projected triangle, clipped or not, lies in
 * its vertices' hull). Rasterizing only these is the pick's speed: on 491,520
 * triangles the vertex stage and this test instead of two full passes. */
static uint32_t candidate_triangles(const oit_model *model, const clip_vertex *vertices, int width, int height,
                                    int x, int gl_y, uint32_t *out)
{
    const double centre_x = ((double)x + 0.5) * 2.0 / width - 1.0;
    const double centre_y = ((double)gl_y + 0.5) * 2.0 / height - 1.0;
    const double margin_x = CANDIDATE_MARGIN_PIXELS * 2.0 / width;
    const double margin_y = CANDIDATE_MARGIN_PIXELS * 2.0 / height;
    uint32_t count = 0;
    for (uint32_t t = 0; t < model->triangle_count; ++t) {
        const uint32_t *index = &model->indices[3 * (size_t)t];
        unsigned left = 0, right = 0, below = 0, above = 0, in_front = 0;
        for (int k = 0; k < 3; ++k) {
            const double *c = vertices[index[k]].clip;
            in_front += c[3] > 0.0;
            left += c[0] < (centre_x - margin_x) * c[3];
            right += c[0] > (centre_x + margin_x) * c[3];
            below += c[1] < (centre_y - margin_y) * c[3];
            above += c[1] > (centre_y + margin_y) * c[3];
        }
        if (in_front == 3 && (left == 3 || right == 3 || below == 3 || above == 3))
            continue;
        out[count++] = t;
    }
    return count;
}

oit_status oit_pick_pixel(const oit_model *model, const oit_frame_settings *frame, int x, int y,
                          oit_pick *out, oit_error *err)
{
    if (!out)
        return oit_fail(err, OIT_E_INPUT, "pick: no result to fill");
    memset(out, 0, sizeof *out);
    out->background = 1.0;
    if (!model || !frame)
        return oit_fail(err, OIT_E_INPUT, "pick: no model or frame settings");
    if (frame->width < 1 || frame->height < 1)
        return oit_fail(err, OIT_E_INPUT, "pick: bad size %dx%d", frame->width, frame->height);
    if (x < 0 || y < 0 || x >= frame->width || y >= frame->height)
        return oit_fail(err, OIT_E_INPUT, "pick: pixel %d,%d is outside the %dx%d image (0..%d, 0..%d)", x, y,
                        frame->width, frame->height, frame->width - 1, frame->height - 1);
    oit_status status = oit_matrices_validate(frame->modelview, frame->projection, err);
    if (status == OIT_OK)
        status = oit_reference_check_model(model, err);
    oit_frame_settings relative;
    if (status == OIT_OK)
        status = oit_frame_relative(model, frame, &relative, err);
    if (status != OIT_OK || model->triangle_count == 0)
        return status;

    clip_vertex *vertices = malloc((size_t)model->vertex_count * sizeof *vertices);
    uint32_t *candidates = malloc((size_t)model->triangle_count * sizeof *candidates);
    if (!vertices || !candidates) {
        free(vertices);
        free(candidates);
        return oit_fail(err, OIT_E_RUNTIME, "pick: out of memory for %u vertices", model->vertex_count);
    }
    oit_reference_vertex_stage(model, &relative, vertices);

    /* the one pixel, in GL's rows (bottom up) */
    const int gl_y = frame->height - 1 - y;
    uint32_t candidate_count = candidate_triangles(model, vertices, frame->width, frame->height, x, gl_y, candidates);
    uint32_t count = 0;
    uint64_t offsets[2] = {0, 0};
    raster_context ctx;
    status = oit_reference_raster_begin(&ctx, &relative, frame->width, frame->height, &count, offsets, err);
    reference_fragment *fragments = NULL;
    if (status == OIT_OK) {
        ctx.region_x = x;
        ctx.region_y = gl_y;
        ctx.region_width = ctx.region_height = 1;
        oit_reference_rasterize_some(&ctx, model, vertices, candidates, candidate_count); /* count */
        offsets[1] = count;
        if (count > 0) {
            fragments = malloc((size_t)count * sizeof *fragments);
            if (!fragments)
                status = oit_fail(err, OIT_E_RUNTIME, "pick: out of memory for %u fragments", count);
        }
    }
    if (status == OIT_OK && count > 0) {
        uint32_t counted = count;
        count = 0;
        ctx.fill = true;
        ctx.fragments = fragments;
        oit_reference_rasterize_some(&ctx, model, vertices, candidates, candidate_count); /* store */
        count = count < counted ? count : counted;
        oit_reference_sort_fragments(fragments, count);
        status = rank_parts(&ctx, model, x, gl_y, fragments, count, out, err);
    }
    free(fragments);
    free(candidates);
    free(vertices);
    if (status != OIT_OK)
        oit_pick_release(out);
    return status;
}
