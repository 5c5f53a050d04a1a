/* bench_output.h: what `oit bench` writes: one row per run as CSV and/or
 * JSON, each as soon as it is measured, into files replaced whole when the
 * run ends (oit_atomic_file), and the progress lines on stderr. */
#ifndef OIT_CLI_BENCH_OUTPUT_H
#define OIT_CLI_BENCH_OUTPUT_H

#include <stdbool.h>
#include <stdio.h>

#include "bench.h"
#include "bench_run.h"
#include "bench_scenes.h"

typedef struct bench_output {
    FILE *csv; /* stdout, or the stream of csv_file */
    FILE *json;
    oit_atomic_file *csv_file, *json_file; /* NULL for stdout */
    int json_rows;
    int tolerance;
} bench_output;

/* The files a bundle holds for one row (empty strings: none). */
typedef struct row_files {
    char image[512], reference[512], error_map[512];
} row_files;

/* Opens --csv and --json (stdout for '-'; the CSV on stdout when neither
 * --json nor --bundle is given). */
oit_status bench_output_open(const bench_settings *b, bench_output *out, oit_error *err);
/* The CSV header, and the JSON's opening: date, renderer, machine, command. */
void bench_output_begin(bench_output *out, const bench_settings *b, bool has_gl, int argc, char **argv);
/* One run's row in the CSV and the JSON (and a warning if its frames were truncated). */
void write_row(bench_output *out, const bench_scene *scene, const session *s, const bench_algorithm *algorithm,
               int width, int height, const run_result *r);
/* One row as a JSON object (--json's results, and the bundle's), with the
 * bundle's file names where files is not NULL. */
void write_json_row(FILE *f, const bench_scene *scene, const session *s, const bench_algorithm *algorithm,
                    int width, int height, const run_result *r, int tolerance, const row_files *files);
/* The JSON's closing: the failures and the peak resident memory. */
void bench_output_end(bench_output *out, int failures);
/* True once a write to an output failed: the run stops rather than measure
 * what cannot be written. */
bool bench_output_failed(const bench_output *out);
/* Closes the outputs: renamed over their targets, both or neither, when keep
 * and both were written whole; else dropped. A failed write is an error
 * naming the file. */
oit_status bench_output_close(bench_output *out, bool keep, oit_error *err);

/* The current time as 2024-01-31T12:00:00Z. */
void iso_time(char *out, size_t size);

/* The progress lines on stderr: a frame counter on a terminal, then one line per run. */
typedef struct progress_state {
    bool tty;
    int index, total;
    const char *scene, *algorithm;
    int width, height;
} progress_state;

void progress_frame(void *data, int frame, int frames); /* run_algorithm's progress (data: a progress_state) */
void progress_done(const progress_state *p, const run_result *r);

#endif
