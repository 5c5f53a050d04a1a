/* bench.h: `oit bench` (scenes x algorithms x sizes, CSV, JSON and a result
 * bundle; docs/cli.md, docs/benchmarks.md) and what its command line asks
 * for, which its output (bench_output.h) and bundle (bench_bundle.h) read. */
#ifndef OIT_CLI_BENCH_H
#define OIT_CLI_BENCH_H

#include <stdbool.h>

#include "render_session.h"

#define BENCH_MAX_SIZES 32
#define BENCH_MAX_ALGORITHMS 32 /* the quality map sweeps every algorithm and parameter in one run */

/* One algorithm variant: a registry name, optionally with the ll sort
 * ("ll-array" is ll --sort array, as the thesis's table 5.3 compares; also
 * ll-insertion, ll-bma, ll-merge) or a
 * parameter after a colon: NAME:K sets the layers of an algorithm that reads
 * them (kbuffer:16), NAME:MOMENTS its moments (mboit:power6), NAME:N the
 * samples of one that reads them (stochastic:16), NAME:R the rank of one
 * that reads --wavelet-rank (wavelet:2). The label is
 * the text as given. */
typedef struct bench_algorithm {
    char label[48];
    const oit_algorithm_ops *ops;
    int sort;            /* -1: the scene's --sort; else oit_ll_sort (ll-insertion, ll-array, ...) */
    int layers;          /* 0: the scene's --layers */
    oit_moments moments; /* OIT_MOMENTS_DEFAULT: the scene's --moments */
    int samples;         /* 0: the scene's --samples (NAME:N of an algorithm reading OIT_OPTION_SAMPLES) */
    int wavelet_rank;    /* 0: the scene's --wavelet-rank */
} bench_algorithm;

/* What the bench's command line asks for. */
typedef struct bench_settings {
    render_options base; /* render options for every scene */
    const char *scene_list_path, *single_model, *single_name, *scene_patterns;
    const char *csv_path, *json_path, *bundle_path;
    bench_algorithm algorithms[BENCH_MAX_ALGORITHMS];
    int algorithm_count;
    int widths[BENCH_MAX_SIZES], heights[BENCH_MAX_SIZES], size_count;
    long frames, warmup, reference_pixels, tolerance;
    double budget_ms;
    long orbit_frames; /* --orbit-sequence; 0: none */
    double orbit_step; /* degrees of azimuth per frame */
    bool orbit_step_given;
    bool quiet;
} bench_settings;

int command_bench(int argc, char **argv);

/* WxH, or N alone for NxN (--sizes' items, measure's VIEWPORT); parse_size's messages. */
oit_status parse_size_or_side(const char *text, int *width, int *height, oit_error *err);

#endif
