/* render_session.h: what the oit commands share: argument parsing, the render
 * options, a session (one model, one GL context made on first use, the
 * model's GPU buffers) and rendering N frames with medians. render, demo,
 * bench and measure all render through render_frames / render_frame_settings. */
#ifndef OIT_CLI_RENDER_SESSION_H
#define OIT_CLI_RENDER_SESSION_H

#include <stdbool.h>
#include <stdio.h>

#include "oit.h"

enum { EXIT_OK = 0, EXIT_MISMATCH = 1, EXIT_USAGE = 2, EXIT_RUNTIME = 3 };

#define MAX_IMAGE_SIDE 16384
#define MAX_FRAMES 10000

extern const char *program_path; /* argv[0], to find the shaders next to the executable */

int exit_code(oit_status status);
/* Prints err as "oit: error: ..." when status is not OK; returns the exit status. */
int report(oit_status status, const oit_error *err);
/* Prints "oit: error: <fmt with detail> (see oit --help)"; returns EXIT_USAGE. */
int usage_error(const char *fmt, const char *detail);

/* ------------------------------------------------------------- parsing */

bool parse_double(const char *text, double *out);
bool parse_int(const char *text, long minimum, long maximum, long *out);
/* Comma-separated finite numbers; returns the count parsed or -1 on a bad token. */
int parse_number_list(const char *text, double *values, int capacity);
/* 16 numbers row by row (as the source's measuring command line) into column-major. */
oit_status parse_matrix(const char *flag, const char *text, double out[16], oit_error *err);
/* Checks and converts 16 row-by-row numbers (already parsed) into column-major. */
oit_status matrix_from_rows(const char *what, const double rows[16], double out[16], oit_error *err);
oit_status parse_size(const char *text, int *width, int *height, oit_error *err);

/* ----------------------------------------------------- render options */

typedef struct render_options {
    const char *model_path;
    const char *out_path;
    const oit_algorithm_ops *algorithm;
    int width, height;
    bool has_modelview, has_projection;
    float orbit[2]; /* default camera: azimuth, elevation in degrees */
    double modelview[16], projection[16];
    float alpha;
    oit_shading_mode shading;
    float background[3];
    oit_modulation modulation;
    oit_backend backend;
    oit_algorithm_config config;
    int frames;
    bool json;
    oit_import_options import; /* --tessellation (STEP, IGES) */
    double explode;            /* --explode F, 0..OIT_EXPLODE_MAX (0: the assembly as built) */
    oit_overlay_options overlay; /* --axes[=CORNER], --scale-bar: drawn on the image render_frames returns */
    int samples;               /* --samples N: 1, 4, 8 or 16 (oit_frame_settings.samples); 0: not given */
} render_options;

void render_options_defaults(render_options *o);
/* Parses one render option at argv[*i]; returns 1 if consumed, 0 if unknown, -1 on error. */
int parse_render_option(int argc, char **argv, int *i, render_options *o, oit_error *err,
                        oit_status *status);

/* ------------------------------------------------------- render session */

/* Everything one process needs to render: the model, a GL context made on
 * first use, and the scene's GPU buffers. */
typedef struct session {
    oit_model model;
    bool model_loaded;
    oit_gl_context *gl;
    oit_backend backend;
    bool debug;
    oit_scene gpu_scene;
    bool gpu_scene_uploaded;
    oit_scene cpu_scene;
    char shader_dir[4096];
    oit_import_options import; /* how session_set_model imports */
    /* The model as drawn (session_prepare_model): with --explode or section
     * caps, model is oit_model_derive's and source_model the model as loaded;
     * otherwise model is the model as loaded and source_model unused. */
    oit_model source_model;
    bool derived;
    bool prepared;
    double prepared_explode;
    float *offsets;    /* 3 per part (--explode), NULL when 0 */
    uint8_t *open_cut; /* 1 per part a section cuts that is open (no cap), NULL when none */
    bool has_sections; /* the frame had sections: --json lists open_cut_parts */
} session;

oit_status session_open(session *s, const char *model_path, oit_backend backend, bool debug,
                        oit_error *err);
/* The same with import options (NULL: the defaults). */
oit_status session_open_import(session *s, const char *model_path, oit_backend backend, bool debug,
                               const oit_import_options *import, oit_error *err);
/* Replaces the model, keeping the GL context (bench: one context per process,
 * each model uploaded once). */
oit_status session_set_model(session *s, const char *model_path, oit_error *err);
oit_status session_need_gl(session *s, oit_error *err);
/* Makes s->model the model as drawn for o (--explode's offsets, then the
 * sections' caps through oit_model_derive, when oit_model_derive_needed says
 * so; the model as loaded otherwise, byte for byte), before the GPU gets it.
 * Prints one warning naming the open parts a section cuts (no cap). Called
 * by render_setup_create and render_frames; again with another --explode,
 * it starts from the model as loaded. */
oit_status session_prepare_model(session *s, const render_options *o, oit_error *err);
void session_close(session *s);

double median(double *values, int count); /* sorts values */

typedef struct render_result {
    oit_image image;
    oit_stats stats; /* medians */
    /* --json only, GL algorithms: the bytes of every GL buffer and texture
     * that exist after the last frame and did not before the algorithm was
     * created, counted by enumerating GL objects (oit_gl_enumerate_allocated_bytes,
     * which knows nothing of the algorithms' own accounting); -1 otherwise */
    int64_t gl_allocated_bytes;
    oit_overlay_info overlay; /* what --axes and --scale-bar drew (render_frames_overlay) */
} render_result;

/* The frame settings o asks for on s's model (default camera unless matrices
 * are given); validates the matrices. */
oit_status render_frame_settings(const session *s, const render_options *o, oit_frame_settings *frame,
                                 oit_error *err);
/* What a run of frames needs: the algorithm o names, created and sized, its
 * frame settings and the scene it draws (GPU or CPU). On failure *alg is NULL
 * or must still be destroyed by the caller (it is non-NULL once created). */
typedef struct render_setup {
    oit_algorithm *alg;
    oit_frame_settings frame;
    const oit_scene *scene;
} render_setup;
oit_status render_setup_create(session *s, const render_options *o, render_setup *setup,
                               oit_error *err);
/* The orientation aids o asks for (--axes, --scale-bar) onto image, a frame
 * of s's model rendered with frame's matrices: the one place the command
 * line draws them (render_frames calls it on its final image; a command
 * that makes frames another way calls it before writing each). The scale
 * bar takes the model as loaded (its centre and units), not the exploded one. */
oit_status render_overlay(const session *s, const render_options *o, const oit_frame_settings *frame,
                          oit_image *image, oit_overlay_info *info, oit_error *err);
/* Renders o->frames frames; figures are medians over frames 2..N. The
 * image has o's orientation aids on it (render_overlay). */
oit_status render_frames(session *s, const render_options *o, render_result *result, oit_error *err);

/* --------------------------------------------------------------- output */

/* Checks, before any work, that the file flag names can be written: a
 * regular file or a new name in a writable directory, its name within
 * NAME_MAX, or /dev/null or the standard output (oit_check_output_file). */
oit_status check_output_path(const char *flag, const char *path, oit_error *err);
/* "oit: warning: WHAT: ..." on stderr when a frame left fragments out (stats.truncated). */
void warn_if_truncated(const char *what, const oit_algorithm_config *config, const oit_stats *stats);
/* Each import warning as "oit: warning: ..." on stderr. */
void print_model_warnings(const oit_model *model);
double stages_total(const oit_stats *stats);

/* The frame of o (the reference, say) rendered at the pixel centre (--samples off). */
oit_status render_centre_reference(session *s, const render_options *o, oit_image *out, oit_error *err);

#endif
