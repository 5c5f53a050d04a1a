/*
 * bench_run.c: one measured run of one algorithm (bench_run.h), and the
 * orbit sequence's flicker against the reference.
 */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_run.h"

#define BENCH_MIN_FRAMES 3 /* what --time-budget leaves at the least */

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1000.0 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

static spread spread_of(double *values, int count)
{
    spread s = {0.0, 0.0, 0.0};
    if (count <= 0)
        return s;
    s.median = median(values, count); /* sorts */
    s.min = values[0];
    s.max = values[count - 1];
    return s;
}

oit_status run_algorithm(session *s, const render_options *o, int warmup, int frames, double budget_ms,
                         run_result *r, oit_image *image, void (*progress)(void *, int, int),
                         void *progress_data, oit_error *err)
{
    const oit_algorithm_ops *ops = o->algorithm;
    oit_stats *per_frame = calloc((size_t)frames, sizeof *per_frame);
    double *values = malloc(sizeof(double) * (size_t)frames);
    if (!per_frame || !values) {
        free(per_frame);
        free(values);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %d frames of statistics", frames);
    }
    /* timed frames are the image's work only: ib's neighbour-quality pass is a diagnostic */
    render_options timed = *o;
    timed.config.neighbour_quality = false;
    render_setup setup;
    oit_status status = render_setup_create(s, &timed, &setup, err);
    oit_algorithm *alg = setup.alg;
    int measured = 0;
    double measure_start_ms = 0.0;
    for (int f = 0; status == OIT_OK && f < warmup + frames; ++f) {
        if (progress)
            progress(progress_data, f + 1, warmup + frames);
        if (f == warmup)
            measure_start_ms = now_ms();
        status = oit_algorithm_render(ops, alg, setup.scene, &setup.frame, err);
        if (status == OIT_OK && f >= warmup) {
            ops->stats(alg, &per_frame[measured++]);
            if (budget_ms > 0.0 && measured >= BENCH_MIN_FRAMES && now_ms() - measure_start_ms > budget_ms)
                break;
        }
    }
    frames = measured;
    if (status == OIT_OK && image)
        status = ops->read_image(alg, image, err);
    if (status == OIT_OK && frames == 0)
        status = oit_fail(err, OIT_E_RUNTIME, "no frame was measured");
    if (status == OIT_OK) {
        r->warmup = warmup;
        r->frames = frames;
        r->last = per_frame[frames - 1];
        r->memory_max = 0;
        for (int f = 0; f < frames; ++f) {
            values[f] = per_frame[f].cpu_ms;
            if (per_frame[f].memory_bytes > r->memory_max)
                r->memory_max = per_frame[f].memory_bytes;
        }
        r->cpu_ms = spread_of(values, frames);
        for (int f = 0; f < frames; ++f)
            values[f] = stages_total(&per_frame[f]);
        r->gpu_ms = spread_of(values, frames);
        /* stages by name, in the order they first appear (peel counts may differ between frames) */
        r->stage_count = 0;
        for (int f = 0; f < frames; ++f)
            for (int k = 0; k < per_frame[f].stage_count; ++k) {
                const char *name = per_frame[f].stages[k].name;
                int found = -1;
                for (int j = 0; j < r->stage_count && found < 0; ++j)
                    if (strcmp(r->stages[j].name, name) == 0)
                        found = j;
                if (found < 0 && r->stage_count < OIT_MAX_STAGES)
                    snprintf(r->stages[r->stage_count++].name, OIT_STAGE_NAME_SIZE, "%s", name);
            }
        for (int j = 0; j < r->stage_count; ++j) {
            int n = 0;
            for (int f = 0; f < frames; ++f) {
                double sum = 0.0; /* a frame without the stage (fill_retry) counts 0 */
                for (int k = 0; k < per_frame[f].stage_count; ++k)
                    if (strcmp(per_frame[f].stages[k].name, r->stages[j].name) == 0)
                        sum += per_frame[f].stages[k].gpu_ms;
                values[n++] = sum;
            }
            r->stages[j].ms = spread_of(values, n);
        }
        r->ok = true;
    }
    if (alg)
        ops->destroy(alg);
    free(per_frame);
    free(values);
    return status;
}

/* Sum of the medians of the stages whose names start with any of the prefixes. */
double stages_sum(const run_result *r, const char *const *prefixes, int prefix_count)
{
    double sum = 0.0;
    for (int j = 0; j < r->stage_count; ++j)
        for (int p = 0; p < prefix_count; ++p)
            if (strncmp(r->stages[j].name, prefixes[p], strlen(prefixes[p])) == 0) {
                sum += r->stages[j].ms.median;
                break;
            }
    return sum;
}

/* modelview * T(centre) * Ry(-degrees) * T(-centre): the camera orbited about
 * the model's vertical axis through its bounding sphere's centre (the model's
 * origin). For the default camera this is the camera of azimuth + degrees
 * (oit_default_camera builds translate * rotate_x(el) * rotate_y(-az) *
 * translate(-centre)). */
static void orbit_modelview(const double modelview[16], const double centre[3], double degrees, double out[16])
{
    double angle = -degrees * 3.14159265358979323846 / 180.0;
    double c = cos(angle), sn = sin(angle);
    /* M = T(centre) * Ry * T(-centre), column-major, in double */
    double m[16] = {c, 0.0, -sn, 0.0, 0.0, 1.0, 0.0, 0.0, sn, 0.0, c, 0.0, 0.0, 0.0, 0.0, 1.0};
    double t[3];
    for (int row = 0; row < 3; ++row)
        t[row] = centre[row] - (m[row] * centre[0] + m[4 + row] * centre[1] + m[8 + row] * centre[2]);
    m[12] = t[0];
    m[13] = t[1];
    m[14] = t[2];
    oit_mat4_multiply(modelview, m, out);
}

/* The reference's image of one frame: from the cache when it is there, else
 * rendered (and kept in the cache when there is one, else in *scratch). */
static oit_status orbit_reference(session *s, const render_options *o, const oit_frame_settings *frame,
                                  render_setup *reference, oit_image *cached, oit_image *scratch,
                                  const oit_image **out, oit_error *err)
{
    if (cached && cached->rgba) {
        *out = cached;
        return OIT_OK;
    }
    oit_status status = OIT_OK;
    if (!reference->alg) {
        render_options ro = *o;
        ro.algorithm = &oit_algorithm_reference;
        status = render_setup_create(s, &ro, reference, err);
    }
    reference->frame = *frame;
    if (oit_algorithm_reads(o->algorithm, OIT_OPTION_SAMPLES))
        reference->frame.samples = 0; /* stochastic's samples are depth slots at the pixel centre */
    if (status == OIT_OK)
        status = oit_algorithm_render(&oit_algorithm_reference, reference->alg, reference->scene, &reference->frame, err);
    oit_image *target = cached ? cached : scratch;
    oit_image_free(target);
    if (status == OIT_OK)
        status = oit_algorithm_reference.read_image(reference->alg, target, err);
    *out = target;
    return status;
}

oit_status run_orbit(session *s, const render_options *o, int count, double step_degrees,
                     oit_image *reference_frames, run_result *r, oit_error *err)
{
    const oit_algorithm_ops *ops = o->algorithm;
    render_options timed = *o;
    timed.config.neighbour_quality = false;
    render_setup setup, reference;
    memset(&reference, 0, sizeof reference);
    oit_status status = render_setup_create(s, &timed, &setup, err);
    size_t values = (size_t)o->width * (size_t)o->height * 3;
    int16_t *previous = malloc(values * sizeof *previous), *current = malloc(values * sizeof *current);
    if (status == OIT_OK && (!previous || !current))
        status = oit_fail(err, OIT_E_RUNTIME, "--orbit-sequence: out of memory for %dx%d error images",
                          o->width, o->height);
    double base[16];
    memcpy(base, setup.frame.modelview, sizeof base);
    oit_image image = {0}, scratch = {0};
    double pair_sum = 0.0, pair_max = 0.0, rmse_sum = 0.0;
    for (int i = 0; status == OIT_OK && i < count; ++i) {
        orbit_modelview(base, s->model.origin, step_degrees * i, setup.frame.modelview);
        status = oit_algorithm_render(ops, setup.alg, setup.scene, &setup.frame, err);
        if (status == OIT_OK) {
            oit_image_free(&image);
            status = ops->read_image(setup.alg, &image, err);
        }
        const oit_image *ref = NULL;
        if (status == OIT_OK) {
            status = orbit_reference(s, o, &setup.frame, &reference,
                                     reference_frames ? &reference_frames[i] : NULL, &scratch, &ref, err);
            if (status != OIT_OK) {
                char reason[OIT_ERROR_MESSAGE_SIZE];
                snprintf(reason, sizeof reason, "%s", err->message);
                status =
                    oit_fail(err, status, "--orbit-sequence: the reference of frame %d: %s", i + 1, reason);
            }
        }
        oit_image_error figures;
        if (status == OIT_OK)
            status = oit_image_error_compute(&image, ref, &figures, err);
        if (status != OIT_OK)
            break;
        rmse_sum += figures.rmse;
        size_t n = 0;
        for (size_t p = 0; p < (size_t)o->width * (size_t)o->height; ++p)
            for (int c = 0; c < 3; ++c, ++n)
                current[n] = (int16_t)((int)image.rgba[4 * p + c] - (int)ref->rgba[4 * p + c]);
        if (i > 0) {
            double sum = 0.0;
            for (size_t k = 0; k < values; ++k)
                sum += abs((int)current[k] - (int)previous[k]);
            double pair = sum / (double)values;
            pair_sum += pair;
            if (pair > pair_max)
                pair_max = pair;
        }
        int16_t *swap = previous;
        previous = current;
        current = swap;
    }
    if (status == OIT_OK) {
        r->orbit_frames = count;
        r->flicker = pair_sum / (count - 1);
        r->flicker_max = pair_max;
        r->orbit_rmse_mean = rmse_sum / count;
    }
    oit_image_free(&image);
    oit_image_free(&scratch);
    free(previous);
    free(current);
    if (setup.alg)
        ops->destroy(setup.alg);
    if (reference.alg)
        oit_algorithm_reference.destroy(reference.alg);
    return status;
}
