/* bench_bundle.h: `oit bench --bundle DIR`: the images of every run (the
 * algorithm's, the reference's, the error map) and bundle.json (command,
 * commit, machine, driver, parameters, scenes with their cameras, the rows
 * of --json), replacing DIR whole when the run ends. */
#ifndef OIT_CLI_BENCH_BUNDLE_H
#define OIT_CLI_BENCH_BUNDLE_H

#include <stdbool.h>
#include <stdio.h>

#include "bench.h"
#include "bench_output.h"
#include "bench_run.h"
#include "bench_scenes.h"

/* --bundle DIR: the images of every run and bundle.json, written into
 * DIR.tmp.XXXXXX beside DIR (oit_temporary_create: removed if the run fails
 * or is interrupted, or by the next run if it was killed) and swapped with
 * DIR when the run ends, so that a run that stops half-way leaves a previous
 * bundle at DIR whole. DIR may be new, an empty directory or a previous
 * bundle (a directory with bundle.json and regular files only), or a link to
 * one (the link stays); anything else is refused before any work. */
typedef struct bench_bundle {
    char given[4096];    /* DIR as given, without trailing slashes: for messages */
    char path[4096];     /* DIR with its links followed: what is replaced */
    bool replaces;       /* DIR exists (a bundle or an empty directory) */
    unsigned mode;       /* its permissions, which the new bundle keeps */
    oit_temporary temp;  /* DIR.tmp.XXXXXX: where it is written */
    FILE *rows, *scenes; /* open_memstream: the rows and scenes of bundle.json */
    char *rows_text, *scenes_text;
    size_t rows_size, scenes_size;
    int row_count, scene_count, camera_count;
    char renderer[256], gl_version[256], gl_vendor[256];
    oit_status status; /* a file that could not be written stops the run */
    oit_error err;
} bench_bundle;

/* Checks DIR and every file name it will hold (unique, within NAME_MAX and
 * PATH_MAX) before any work, then makes its temporary folder. */
oit_status bundle_open(const bench_settings *b, const scene_list *scenes, bench_bundle *bundle, oit_error *err);
/* The driver (GL_RENDERER, GL_VERSION, GL_VENDOR), while the context is current. */
void bundle_driver(bench_bundle *bundle, bool has_gl);
/* A scene's entry: its model (path, bytes, checksum) and render options;
 * the cameras follow, one per size (bundle_camera), then bundle_scene_end. */
void bundle_scene_begin(bench_bundle *bundle, const bench_scene *scene);
void bundle_camera(bench_bundle *bundle, const oit_frame_settings *frame);
void bundle_scene_end(bench_bundle *bundle, oit_status load, const oit_error *load_err);
/* The reference image of a scene at a size, SCENE_WxH.reference.png; its name in files. */
void bundle_reference(bench_bundle *bundle, const bench_scene *scene, int width, int height,
                      const oit_image *reference, row_files *files);
/* A run's image, SCENE_ALGORITHM_WxH.png, and where there is a reference its
 * error map, SCENE_ALGORITHM_WxH.error.png; their names in files. A file that
 * cannot be written sets bundle->status, which stops the run. */
void bundle_run_images(bench_bundle *bundle, const bench_scene *scene, const bench_algorithm *algorithm,
                       int width, int height, const oit_image *image, const oit_image *reference,
                       row_files *files);
/* One row, as --json writes it, with the bundle's file names where files is not NULL. */
void bundle_row(bench_bundle *bundle, const bench_scene *scene, const session *s,
                const bench_algorithm *algorithm, int width, int height, const run_result *r, int tolerance,
                const row_files *files);
/* bundle.json, then DIR.tmp.XXXXXX renamed to DIR (a previous bundle at DIR
 * is moved aside first and removed after). */
oit_status bundle_commit(bench_bundle *bundle, const bench_settings *b, bool has_gl, int argc, char **argv,
                         int failures, oit_error *err);
/* Drops what bundle_commit did not rename (a run that failed). */
void bundle_close(bench_bundle *bundle);

#endif
