/*
 * alg_reference.c: the exact CPU renderer, the test oracle for every GPU algorithm.
 *
 * It rasterizes the model the way GL does (clip in homogeneous space, perspective
 * divide, viewport transform, sample at pixel centres with a fill rule, no culling),
 * keeps every fragment, sorts each pixel's fragments by (depth as float,
 * triangle index) and composites them front to back in double precision. The
 * depth is the canonical one of every exact algorithm: where the triangle's
 * coplanar plane (oit_model.planes) meets the pixel centre's ray, as a fraction
 * of the ray from the near to the far plane, computed here in double
 * (common/canonical_depth.glsl does it in float), so coincident faces tie
 * exactly and order by triangle index.
 *
 * The coverage rule is the GL's as Mesa's llvmpipe implements it (GL leaves the
 * subpixel precision and the tie rule to the implementation), so "exact" means
 * the same set of fragments:
 * - window positions are snapped to the nearest 1/256 pixel (GL_SUBPIXEL_BITS is
 *   8 on both back ends), ties to even: llvmpipe converts (x - 1/2) * 256 with
 *   SSE's float-to-int conversion, which rounds half-way values to even (see
 *   round_half_even; rounding them away from zero covered other pixels);
 * - a pixel is covered when its centre is inside the snapped triangle, decided by
 *   edge functions evaluated exactly in 64-bit integers, so two triangles sharing
 *   an edge cover each pixel centre on it exactly once; a triangle whose snapped
 *   area is 0 covers nothing;
 * - ties (a pixel centre exactly on an edge) follow Gallium's rule for GL
 *   framebuffer objects: in GL window coordinates (y up) a centre on a left edge or
 *   on a horizontal edge with the triangle above it is inside (see edge_is_inclusive);
 * - the precision it assumes: the reference computes window positions in double,
 *   llvmpipe's are float results of its float vertex stage. Where the GL's
 *   positions are exact (tests/coverage_rule.sh:
 *   sub-pixel triangles, snap ties and edges through pixel centres) both cover
 *   the same fragments; elsewhere a vertex within the GL's float error of a snap
 *   tie can snap one 1/256 step the other way (docs/algorithms.md, "reference");
 * - x/y are clipped only against a wide guard band, so ordinary triangles are never
 *   split and keep their exact edges; near/far (-w <= z <= w) are clipped as in GL.
 * - snapping decides coverage only: the perspective-correct eye position and
 *   eye normal are interpolated from the unsnapped window positions, as
 *   llvmpipe's attribute planes are. Coverage then matches llvmpipe pixel for
 *   pixel, ties included.
 *
 * The oracle shares no computation with what it checks. What the GPU path gets
 * from core helpers (gl_frame.c sets, for the shaders, the inverse modelview and
 * projection and the focus region through local_modulation.c, the plane-to-eye
 * matrix through matrix.c, the normal matrix through oit_mat4_normal_matrix)
 * and what the shaders compute per fragment (shade.glsl: headlight shading and
 * contrast; local_modulation.glsl: component opacity and the focus factor) is
 * computed here again, from the definitions (docs/modulation.md; `--shading`
 * in docs/cli.md), in "The oracle's own maths" (reference_raster.c): a 4x4
 * inverse by Gauss-Jordan elimination, the normal and plane matrices from it,
 * the focus region, distance and factor, contrast and shading. Shared by design, as
 * definitions rather than computations: the frame's settings and matrices (the
 * input; oit_matrices_validate checks them as the CLI does), the model's
 * coplanar planes (oit_model.planes from model_planes.c: which fragments tie
 * is defined by the planes, see canonical_depth), and oit_shared.h's constants
 * (OIT_EDGE_ON_PLANE_PPM, OIT_HEADLIGHT_AMBIENT_PERCENT).
 *
 * The files: this one has the operations table, the fragment store (a
 * counting sort per pixel), the distances, sort and compose;
 * reference_raster.c the oracle's own maths, the vertex stage and the
 * rasterizer (clipping, snapping, coverage, interpolation, canonical depth,
 * shading); pick.c the same pipeline narrowed to one pixel (oit_pick_pixel);
 * reference_internal.h is what they share, and nothing else includes it.
 */
#define _POSIX_C_SOURCE 200809L

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "capabilities.h"
#include "reference_internal.h"

/* Largest output size accepted (GL_MAX_RENDERBUFFER_SIZE of llvmpipe). */
#define REFERENCE_MAX_SIZE 16384

/* Lists this short are sorted by insertion; longer ones with qsort. */
#define INSERTION_SORT_LIMIT 24

struct oit_algorithm {
    oit_algorithm_config config;
    int width, height;
    uint8_t *rgba; /* output, top row first */
    uint16_t *sample_sum; /* anti-aliasing: the samples' per-pixel sum, 4 per pixel; NULL at 1 sample */

    /* Per-pixel fragment store in GL row order (row 0 = bottom): a counting sort. */
    uint32_t *pixel_counts;  /* width * height: fragments per pixel, then fill cursor */
    uint64_t *pixel_offsets; /* width * height + 1: prefix sum of the counts */
    reference_fragment *fragments;
    size_t fragment_capacity;

    clip_vertex *vertices;
    size_t vertex_capacity;

    oit_stats stats;
};

/* ------------------------------------------------------------------ timing */

/* Stage times are this thread's CPU time; the frame's cpu_ms is wall time. */
static double thread_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static void add_stage(oit_stats *stats, const char *name, double ms)
{
    if (stats->stage_count >= OIT_MAX_STAGES)
        return;
    oit_stage_time *stage = &stats->stages[stats->stage_count++];
    strncpy(stage->name, name, sizeof stage->name - 1);
    stage->name[sizeof stage->name - 1] = '\0';
    stage->gpu_ms = ms;
}

/* ------------------------------------------------------- sort and compose */

static int compare_fragments(const void *pa, const void *pb)
{
    const reference_fragment *a = pa, *b = pb;
    if (a->depth != b->depth)
        return a->depth < b->depth ? -1 : 1;
    return (a->triangle > b->triangle) - (a->triangle < b->triangle);
}

void oit_reference_sort_fragments(reference_fragment *list, size_t count)
{
    if (count > INSERTION_SORT_LIMIT) {
        qsort(list, count, sizeof *list, compare_fragments);
        return;
    }
    for (size_t i = 1; i < count; ++i) {
        reference_fragment key = list[i];
        size_t j = i;
        while (j > 0 && compare_fragments(&list[j - 1], &key) > 0) {
            list[j] = list[j - 1];
            --j;
        }
        list[j] = key;
    }
}

static uint8_t quantize(double value)
{
    value = value < 0.0 ? 0.0 : (value > 1.0 ? 1.0 : value);
    return (uint8_t)lround(value * 255.0);
}

/* Linear eye depth of window depth z at the pixel centre (x, y), through the
 * inverse projection, as the GPU algorithms compute it (ib_eye_depth). */
static double eye_depth(const double inverse_projection[16], int width, int height, int x, int y,
                        float s)
{
    double near_point[3], far_point[3];
    oit_reference_pixel_ray(inverse_projection, width, height, x, y, near_point, far_point);
    return -(near_point[2] + (double)s * (far_point[2] - near_point[2]));
}

/* The distance modulation (docs/modulation.md; the same definition as ib's
 * curvature_distance.comp): fragment i's distance along the ray, in linear eye
 * depth, to fragment i+1 (adjacent), i+k (skip, or the last) or the last (far
 * end); the last fragment's is 0. Sorts every list and leaves each fragment's
 * distance in .alpha; returns the frame's largest distance. */
static double distances(oit_algorithm *alg, const oit_frame_settings *frame,
                        const double inverse_projection[16])
{
    const oit_modulation *m = &frame->modulation;
    const size_t skip = m->distance_skip > 0 ? (size_t)m->distance_skip : 2;
    double largest = 0.0;
    for (int y = 0; y < alg->height; ++y)
        for (int x = 0; x < alg->width; ++x) {
            size_t pixel = (size_t)y * (size_t)alg->width + (size_t)x;
            size_t count = alg->pixel_offsets[pixel + 1] - alg->pixel_offsets[pixel];
            if (count == 0)
                continue;
            reference_fragment *list = alg->fragments + alg->pixel_offsets[pixel];
            if (count > 1)
                oit_reference_sort_fragments(list, count);
            for (size_t i = 0; i < count; ++i) {
                size_t target = count - 1;
                if (m->distance == OIT_DISTANCE_ADJACENT)
                    target = i + 1 < count ? i + 1 : count - 1;
                else if (m->distance == OIT_DISTANCE_SKIP)
                    target = i + skip < count ? i + skip : count - 1;
                double d = 0.0;
                if (target != i)
                    d = fabs(eye_depth(inverse_projection, alg->width, alg->height, x, y,
                                       list[target].depth) -
                             eye_depth(inverse_projection, alg->width, alg->height, x, y,
                                       list[i].depth));
                list[i].alpha = (float)d; /* only depths are read across fragments */
                largest = d > largest ? d : largest;
            }
        }
    return largest;
}

static void sort_and_compose(oit_algorithm *alg, const oit_frame_settings *frame,
                             bool distance_mode, double distance_norm)
{
    const int width = alg->width, height = alg->height;
    const oit_view view = frame->modulation.view;
    const size_t view_parameter =
        frame->modulation.view_parameter > 0 ? (size_t)frame->modulation.view_parameter : 0;
    for (int y = 0; y < height; ++y) {
        /* GL row y (bottom up) is image row height - 1 - y (top down) */
        uint8_t *out_row = alg->rgba + (size_t)(height - 1 - y) * (size_t)width * 4;
        for (int x = 0; x < width; ++x) {
            size_t pixel = (size_t)y * (size_t)width + (size_t)x;
            size_t count = alg->pixel_offsets[pixel + 1] - alg->pixel_offsets[pixel];
            double colour[3] = {0.0, 0.0, 0.0};
            double transmittance = 1.0;
            reference_fragment *list = count ? alg->fragments + alg->pixel_offsets[pixel] : NULL;
            if (count > 1 && !distance_mode) /* distances() sorted them already */
                oit_reference_sort_fragments(list, count);
            size_t first = 0, end = count; /* the fragments this view composites */
            if (view == OIT_VIEW_PEEL_LIMIT) {
                end = count < view_parameter ? count : view_parameter;
            } else if (view == OIT_VIEW_LAYER) {
                first = view_parameter < count ? view_parameter : count;
                end = first < count ? first + 1 : count;
            }
            for (size_t i = first; i < end; ++i) {
                double a = list[i].alpha;
                if (distance_mode) {
                    /* alpha = saturate(distance / region), then the local modulation */
                    a = list[i].alpha / distance_norm;
                    a = (a < 0.0 ? 0.0 : (a > 1.0 ? 1.0 : a)) * list[i].local;
                }
                for (int k = 0; k < 3; ++k)
                    colour[k] += transmittance * a * list[i].rgb[k];
                transmittance *= 1.0 - a;
            }
            uint8_t *out = out_row + (size_t)x * 4;
            for (int k = 0; k < 3; ++k)
                out[k] = quantize(colour[k] + transmittance * frame->background[k]);
            out[3] = 255;
        }
    }
}

/* --------------------------------------------------------------- memory */

/* The sizes of the arrays as allocated (capacities, not this frame's counts):
 * per pixel the output, the counts and the offsets (one more than pixels);
 * the fragment store; the transformed vertices. */
static uint64_t pixel_bytes_held(const oit_algorithm *alg)
{
    uint64_t pixels = (uint64_t)alg->width * (uint64_t)alg->height;
    uint64_t bytes = 0;
    if (alg->rgba)
        bytes += pixels * 4;
    if (alg->pixel_counts)
        bytes += pixels * sizeof *alg->pixel_counts;
    if (alg->pixel_offsets)
        bytes += (pixels + 1) * sizeof *alg->pixel_offsets;
    if (alg->sample_sum)
        bytes += pixels * 4 * sizeof *alg->sample_sum;
    return bytes;
}

static uint64_t bytes_held(const oit_algorithm *alg)
{
    return pixel_bytes_held(alg) + (uint64_t)alg->fragment_capacity * sizeof *alg->fragments +
           (uint64_t)alg->vertex_capacity * sizeof *alg->vertices;
}

static oit_status reserve_fragments(oit_algorithm *alg, uint64_t count, oit_error *err)
{
    if (count > UINT64_MAX / sizeof(reference_fragment))
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for %llu fragments",
                        (unsigned long long)count);
    uint64_t bytes = count * sizeof(reference_fragment);
    /* the fragment store is the buffer that grows with the scene, as the GPU
     * algorithms' fragment pools; a budget of 0 means no limit */
    uint64_t budget = alg->config.max_memory_bytes;
    if (budget != 0 && bytes > budget)
        return oit_fail(err, OIT_E_RUNTIME,
                        "reference: %llu fragments need %llu bytes (%.1f MiB), over the memory "
                        "budget of %llu bytes (%.1f MiB)",
                        (unsigned long long)count, (unsigned long long)bytes, bytes / 1048576.0,
                        (unsigned long long)budget, budget / 1048576.0);
    /* keep the store between frames; give back a large one that is mostly unused */
    bool mostly_unused = alg->fragment_capacity / 4 > count &&
                         alg->fragment_capacity * sizeof(reference_fragment) > (64u << 20);
    if (count <= alg->fragment_capacity && !mostly_unused)
        return OIT_OK;
    if (count > SIZE_MAX / sizeof(reference_fragment))
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for %llu fragments",
                        (unsigned long long)count);
    free(alg->fragments);
    alg->fragment_capacity = 0;
    alg->fragments = malloc((size_t)count * sizeof(reference_fragment));
    if (!alg->fragments)
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for %llu fragments",
                        (unsigned long long)count);
    alg->fragment_capacity = (size_t)count;
    return OIT_OK;
}

static oit_status reserve_vertices(oit_algorithm *alg, uint32_t count, oit_error *err)
{
    if (count <= alg->vertex_capacity)
        return OIT_OK;
    free(alg->vertices);
    alg->vertex_capacity = 0;
    alg->vertices = malloc((size_t)count * sizeof *alg->vertices);
    if (!alg->vertices)
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for %u vertices", count);
    alg->vertex_capacity = count;
    return OIT_OK;
}

/* ------------------------------------------------------------ the table */

/* The arrays whose size is the image's. */
static void free_pixel_arrays(oit_algorithm *alg)
{
    free(alg->rgba);
    free(alg->pixel_counts);
    free(alg->pixel_offsets);
    free(alg->sample_sum);
    alg->sample_sum = NULL;
    alg->rgba = NULL;
    alg->pixel_counts = NULL;
    alg->pixel_offsets = NULL;
}

static void reference_destroy(oit_algorithm *alg)
{
    if (!alg)
        return;
    free_pixel_arrays(alg);
    free(alg->fragments);
    free(alg->vertices);
    free(alg);
}

static oit_status reference_create(const oit_algorithm_config *config, oit_algorithm **out,
                                   oit_error *err)
{
    *out = NULL;
    oit_algorithm *alg = calloc(1, sizeof *alg);
    if (!alg)
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory");
    if (config)
        alg->config = *config;
    else
        oit_algorithm_config_defaults(&alg->config);
    oit_stats_reset(&alg->stats);
    *out = alg;
    return OIT_OK;
}

static oit_status reference_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    if (width < 1 || height < 1 || width > REFERENCE_MAX_SIZE || height > REFERENCE_MAX_SIZE)
        return oit_fail(err, OIT_E_INPUT, "reference: image size %dx%d is outside 1..%d", width,
                        height, REFERENCE_MAX_SIZE);
    if (width == alg->width && height == alg->height && alg->rgba)
        return OIT_OK;
    free_pixel_arrays(alg);
    alg->width = alg->height = 0;
    size_t pixels = (size_t)width * (size_t)height;
    alg->rgba = calloc(pixels, 4);
    alg->pixel_counts = calloc(pixels, sizeof *alg->pixel_counts);
    alg->pixel_offsets = calloc(pixels + 1, sizeof *alg->pixel_offsets);
    if (!alg->rgba || !alg->pixel_counts || !alg->pixel_offsets) {
        free_pixel_arrays(alg);
        return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for a %dx%d image", width,
                        height);
    }
    alg->width = width;
    alg->height = height;
    return OIT_OK;
}

/* Indices and component ids are trusted by the rasterizer; check them once. */
oit_status oit_reference_check_model(const oit_model *model, oit_error *err)
{
    if (model->triangle_count == 0)
        return OIT_OK;
    if (!model->positions || !model->indices || !model->vertex_component || !model->components ||
        model->component_count == 0)
        return oit_fail(err, OIT_E_INPUT, "reference: the model lacks positions, indices or components");
    for (size_t i = 0; i < 3 * (size_t)model->triangle_count; ++i)
        if (model->indices[i] >= model->vertex_count)
            return oit_fail(err, OIT_E_INPUT,
                            "reference: triangle %zu uses vertex %u of %u", i / 3,
                            model->indices[i], model->vertex_count);
    for (uint32_t v = 0; v < model->vertex_count; ++v)
        if (model->vertex_component[v] >= model->component_count)
            return oit_fail(err, OIT_E_INPUT, "reference: vertex %u has component %u of %u", v,
                            model->vertex_component[v], model->component_count);
    return OIT_OK;
}

/* mean list length over non-empty pixels and psi, the share of non-empty pixels
 * whose list is longer than 2/3 of the longest */
static void list_statistics(const uint32_t *counts, size_t pixels, uint64_t total,
                            uint64_t max_list, oit_stats *stats)
{
    uint64_t non_empty = 0, long_lists = 0;
    for (size_t p = 0; p < pixels; ++p) {
        if (counts[p] == 0)
            continue;
        ++non_empty;
        if (3 * (uint64_t)counts[p] > 2 * max_list)
            ++long_lists;
    }
    stats->mean_list = non_empty ? (double)total / (double)non_empty : 0.0;
    stats->psi = non_empty ? (double)long_lists / (double)non_empty : 0.0;
}

static bool reference_continue(const oit_frame_settings *frame, const char *pass, int *passes_done);
static oit_status reference_cancelled(const char *pass, int passes_done, oit_error *err);

static oit_status reference_render(oit_algorithm *alg, const oit_scene *scene,
                                   const oit_frame_settings *frame, oit_error *err)
{
    double frame_start = wall_ms();
    oit_stats_reset(&alg->stats);
    if (!scene || !scene->model || !frame)
        return oit_fail(err, OIT_E_INPUT, "reference: no scene or frame settings");
    const oit_model *model = scene->model;

    oit_status status = reference_resize(alg, frame->width, frame->height, err);
    if (status != OIT_OK)
        return status;
    status = oit_matrices_validate(frame->modelview, frame->projection, err);
    if (status != OIT_OK)
        return status;
    status = oit_reference_check_model(model, err);
    if (status != OIT_OK)
        return status;

    double stage_start = thread_cpu_ms();
    if (model->triangle_count > 0) {
        status = reserve_vertices(alg, model->vertex_count, err);
        if (status != OIT_OK)
            return status;
        oit_reference_vertex_stage(model, frame, alg->vertices);
    }

    const size_t pixels = (size_t)alg->width * (size_t)alg->height;
    raster_context ctx;
    status = oit_reference_raster_begin(&ctx, frame, alg->width, alg->height, alg->pixel_counts,
                                        alg->pixel_offsets, err);
    if (status != OIT_OK)
        return status;

    /* pass 1: count fragments per pixel */
    memset(alg->pixel_counts, 0, pixels * sizeof *alg->pixel_counts);
    if (model->triangle_count > 0)
        oit_reference_rasterize(&ctx, model, alg->vertices);
    int passes_done = 0;
    if (!reference_continue(frame, "count", &passes_done))
        return reference_cancelled("count", passes_done, err);

    uint64_t total = 0, max_list = 0;
    oit_stats *stats = &alg->stats;
    stats->histogram_bins = OIT_HISTOGRAM_BINS;
    for (size_t p = 0; p < pixels; ++p) {
        uint32_t count = alg->pixel_counts[p];
        alg->pixel_offsets[p] = total;
        total += count;
        if (count > max_list)
            max_list = count;
        stats->list_histogram[count < OIT_HISTOGRAM_BINS - 1 ? count : OIT_HISTOGRAM_BINS - 1]++;
    }
    alg->pixel_offsets[pixels] = total;
    list_statistics(alg->pixel_counts, pixels, total, max_list, stats);

    /* pass 2: store the shaded fragments, each pixel's at its offset */
    status = reserve_fragments(alg, total, err);
    if (status != OIT_OK)
        return status;
    if (total > 0) {
        memset(alg->pixel_counts, 0, pixels * sizeof *alg->pixel_counts);
        ctx.fill = true;
        ctx.fragments = alg->fragments;
        oit_reference_rasterize(&ctx, model, alg->vertices);
    }
    add_stage(&alg->stats, "rasterize", thread_cpu_ms() - stage_start);
    if (!reference_continue(frame, "rasterize", &passes_done))
        return reference_cancelled("rasterize", passes_done, err);

    stage_start = thread_cpu_ms();
    bool distance_mode = frame->modulation.mode == OIT_MODULATE_DISTANCE;
    double distance_norm = 1.0;
    if (distance_mode) {
        double inverse_projection[16];
        if (!oit_reference_invert4(frame->projection, inverse_projection))
            return oit_fail(err, OIT_E_INPUT, "reference: the projection matrix is singular");
        double largest = distances(alg, frame, inverse_projection);
        /* focus region 0: normalise by the frame's largest distance (as ib) */
        distance_norm = frame->modulation.focus_region > 0.0f ? frame->modulation.focus_region
                        : largest > 0.0                        ? (double)(float)largest
                                                               : 1.0;
    }
    sort_and_compose(alg, frame, distance_mode, distance_norm);
    add_stage(&alg->stats, "sort_compose", thread_cpu_ms() - stage_start);

    alg->stats.fragments = (int64_t)total;
    alg->stats.max_list = (int64_t)max_list;
    /* the figures of what is allocated (oit_stats in oit.h defines them) */
    alg->stats.memory_bytes = bytes_held(alg);
    alg->stats.bytes_per_fragment = sizeof(reference_fragment); /* the store's bytes / capacity */
    /* per pixel: list count, list offset (one more than pixels), output colour */
    alg->stats.bytes_per_pixel = (double)pixel_bytes_held(alg) / (double)pixels;
    alg->stats.cpu_ms = wall_ms() - frame_start;
    return OIT_OK;
}

/* The frame's progress callback (oit_progress) after each pass: the GPU
 * algorithms ask it from their stage timer, the reference here. */
static bool reference_continue(const oit_frame_settings *frame, const char *pass, int *passes_done)
{
    ++*passes_done;
    return !frame->progress.report || frame->progress.report(frame->progress.user, pass, *passes_done);
}

static oit_status reference_cancelled(const char *pass, int passes_done, oit_error *err)
{
    return oit_fail(err, OIT_CANCELLED, "the frame was cancelled after stage %s (%d stages done)", pass,
                    passes_done);
}

static oit_status reference_read_image(oit_algorithm *alg, oit_image *out, oit_error *err)
{
    if (!alg->rgba)
        return oit_fail(err, OIT_E_RUNTIME, "reference: nothing rendered yet");
    oit_status status = oit_image_alloc(out, alg->width, alg->height, err);
    if (status != OIT_OK)
        return status;
    memcpy(out->rgba, alg->rgba, (size_t)alg->width * (size_t)alg->height * 4);
    return OIT_OK;
}

static void reference_stats(const oit_algorithm *alg, oit_stats *out)
{
    *out = alg->stats;
}

/* Anti-aliasing (oit_algorithm_ops.accumulate): the same sum and rounded
 * average as common/samples_accumulate.comp, in 16-bit integers. */
static oit_status reference_accumulate(oit_algorithm *alg, int sample, int samples, oit_stats *frame,
                                       oit_error *err)
{
    size_t values = (size_t)alg->width * (size_t)alg->height * 4;
    if (samples <= 1) {
        free(alg->sample_sum);
        alg->sample_sum = NULL;
        return OIT_OK;
    }
    if (sample < 0 || sample >= samples || samples > OIT_SAMPLES_MAX || !frame || !alg->rgba)
        return oit_fail(err, OIT_E_RUNTIME, "reference: sample %d of %d cannot be accumulated", sample, samples);
    double start = thread_cpu_ms(), wall_start = wall_ms();
    if (!alg->sample_sum) {
        alg->sample_sum = malloc(values * sizeof *alg->sample_sum);
        if (!alg->sample_sum)
            return oit_fail(err, OIT_E_RUNTIME, "reference: out of memory for the samples' sum");
    }
    if (sample == 0) {
        for (size_t i = 0; i < values; ++i)
            alg->sample_sum[i] = alg->rgba[i];
    } else if (sample + 1 < samples) {
        for (size_t i = 0; i < values; ++i)
            alg->sample_sum[i] = (uint16_t)(alg->sample_sum[i] + alg->rgba[i]);
    } else {
        unsigned n = (unsigned)samples;
        for (size_t i = 0; i < values; ++i)
            alg->rgba[i] = (uint8_t)((alg->sample_sum[i] + alg->rgba[i] + n / 2) / n);
    }
    oit_stats_add_stage(frame, "samples_accumulate", thread_cpu_ms() - start);
    frame->cpu_ms += wall_ms() - wall_start;
    uint64_t held = bytes_held(alg);
    frame->memory_bytes = held > frame->memory_bytes ? held : frame->memory_bytes;
    frame->bytes_per_pixel = (double)pixel_bytes_held(alg) / ((double)alg->width * (double)alg->height);
    if (sample + 1 == samples)
        alg->stats = *frame;
    return OIT_OK;
}

/* The reference shows the composited image and the views that select
 * fragments by depth order, with the local modulations and the distance; list
 * heat maps and the Illustration Buffer's modulation are the GPU algorithms'
 * business. */
#define REFERENCE_VIEW_REASON "view '%s' is not supported (only colour, peel limit and layer)"
#define REFERENCE_MODULATION_REASON "opacity modulation '%s' is not supported (only distance; the non-local ones are ib's)"
static const oit_capabilities reference_capabilities = {
    .views = {[OIT_VIEW_HEATMAP] = REFERENCE_VIEW_REASON, [OIT_VIEW_NEIGHBOURS] = REFERENCE_VIEW_REASON,
              [OIT_VIEW_CURVATURE] = REFERENCE_VIEW_REASON, [OIT_VIEW_DISTANCE] = REFERENCE_VIEW_REASON,
              [OIT_VIEW_FIELDS] = REFERENCE_VIEW_REASON},
    .modulations = {[OIT_MODULATE_CURVATURE] = REFERENCE_MODULATION_REASON,
                    [OIT_MODULATE_DIST_CURV] = REFERENCE_MODULATION_REASON,
                    [OIT_MODULATE_FIELDS] = REFERENCE_MODULATION_REASON,
                    [OIT_MODULATE_EDGES] = REFERENCE_MODULATION_REASON},
    .options = OIT_OPTION_MAX_MEMORY,
};

const oit_algorithm_ops oit_algorithm_reference = {
    .name = "reference",
    .summary = "exact CPU rasterizer: every fragment sorted per pixel (the test oracle)",
    .uses_gl = false,
    .exact = true,
    .capabilities = &reference_capabilities,
    .create = reference_create,
    .resize = reference_resize,
    .render = reference_render,
    .read_image = reference_read_image,
    .stats = reference_stats,
    .accumulate = reference_accumulate,
    .destroy = reference_destroy,
};
