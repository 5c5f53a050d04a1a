/* bench_run.h: one measured run of one algorithm, as `oit bench` and
 * `oit measure` make it: warm-up frames, then measured frames whose figures
 * are kept as median, minimum and maximum; and bench's --orbit-sequence. */
#ifndef OIT_CLI_BENCH_RUN_H
#define OIT_CLI_BENCH_RUN_H

#include <stdbool.h>
#include <stdint.h>

#include "render_session.h"

#define BENCH_DEFAULT_FRAMES 10
#define BENCH_DEFAULT_WARMUP 2
#define BENCH_DEFAULT_SIZE 600 /* the thesis measured at 600x600 */

typedef struct spread {
    double median, min, max;
} spread;

/* The stages of the measured frames, by name in first-seen order. */
typedef struct stage_series {
    char name[OIT_STAGE_NAME_SIZE];
    spread ms;
} stage_series;

typedef struct run_result {
    bool ok;
    char error[OIT_ERROR_MESSAGE_SIZE];
    int warmup, frames;
    spread cpu_ms, gpu_ms;
    int stage_count;
    stage_series stages[OIT_MAX_STAGES];
    oit_stats last; /* the last measured frame: memory, fragments, lists */
    uint64_t memory_max;
    bool has_reference_diff;
    oit_image_diff diff;
    bool has_error; /* the oit_image_error figures against the same reference */
    oit_image_error error_figures;
    /* the scene's depth complexity at this size: the list-length histogram of
     * the CPU reference's frame (oit_stats.list_histogram), 0 bins when bench
     * rendered no reference (width x height over --reference-max-pixels) */
    int scene_histogram_bins;
    uint64_t scene_histogram[OIT_HISTOGRAM_BINS];
    /* --orbit-sequence: the temporal stability of the error (run_orbit) */
    int orbit_frames; /* 0: not measured */
    double flicker, flicker_max, orbit_rmse_mean;
} run_result;

/* Runs warm-up + measured frames of one algorithm on the session's model;
 * keeps the last image in *image when image is not NULL. budget_ms > 0:
 * stop measuring once the measured frames took that long, after at least
 * BENCH_MIN_FRAMES of them (heavy scenes on llvmpipe). progress, when not
 * NULL, is told of every frame (1-based) before it renders. */
oit_status run_algorithm(session *s, const render_options *o, int warmup, int frames, double budget_ms,
                         run_result *r, oit_image *image, void (*progress)(void *, int, int), void *progress_data,
                         oit_error *err);
/* Sum of the medians of the stages whose names start with any of the prefixes. */
double stages_sum(const run_result *r, const char *const *prefixes, int prefix_count);
/* --orbit-sequence: count frames of a slow orbit (step_degrees of azimuth a
 * frame) with the algorithm, and the CPU reference of each. e = image -
 * reference per RGB channel (0..255); flicker is the mean over consecutive
 * frame pairs of mean |e(i) - e(i-1)| over pixels and channels, flicker_max
 * the largest pair, orbit_rmse_mean the mean of the frames' error rmse.
 * reference_frames: count images kept between the algorithms of one scene
 * and size (NULL: render the reference every time). */
oit_status run_orbit(session *s, const render_options *o, int count, double step_degrees,
                     oit_image *reference_frames, run_result *r, oit_error *err);

#endif
