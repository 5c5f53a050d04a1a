/*
 * render_session.c: argument parsing, render options, the render session and
 * N-frame rendering shared by the oit commands (render_session.h).
 */
#define _XOPEN_SOURCE 700 /* strtok_r */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "local_options.h"
#include "modulation_options.h"
#include "render_session.h"

const char *program_path = "oit";

int exit_code(oit_status status)
{
    return status == OIT_OK ? EXIT_OK : status == OIT_E_INPUT ? EXIT_USAGE : EXIT_RUNTIME;
}

int report(oit_status status, const oit_error *err)
{
    if (status != OIT_OK)
        fprintf(stderr, "oit: error: %s\n", err->message);
    return exit_code(status);
}

int usage_error(const char *fmt, const char *detail)
{
    fprintf(stderr, "oit: error: ");
    fprintf(stderr, fmt, detail);
    fprintf(stderr, " (see oit --help)\n");
    return EXIT_USAGE;
}

/* ------------------------------------------------------------- parsing */

bool parse_double(const char *text, double *out)
{
    char *end = NULL;
    errno = 0;
    double value = strtod(text, &end);
    if (end == text || *end != '\0' || errno == ERANGE)
        return false;
    *out = value;
    return true;
}

bool parse_int(const char *text, long minimum, long maximum, long *out)
{
    char *end = NULL;
    errno = 0;
    long value = strtol(text, &end, 10);
    if (end == text || *end != '\0' || errno == ERANGE || value < minimum || value > maximum)
        return false;
    *out = value;
    return true;
}

/* Comma-separated finite numbers; returns the count parsed or -1 on a bad token. */
int parse_number_list(const char *text, double *values, int capacity)
{
    char buffer[2048];
    if (strlen(text) >= sizeof buffer)
        return -1;
    strcpy(buffer, text);
    int count = 0;
    char *save = NULL;
    for (char *token = strtok_r(buffer, ", ", &save); token; token = strtok_r(NULL, ", ", &save)) {
        double value;
        if (!parse_double(token, &value))
            return -1;
        if (count < capacity)
            values[count] = value;
        ++count;
    }
    return count;
}

/* 16 numbers row by row (as the source's measuring command line) into column-major. */
oit_status matrix_from_rows(const char *what, const double values[16], double out[16], oit_error *err)
{
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            double value = values[row * 4 + col];
            if (!isfinite(value) || fabs(value) > 3.0e38)
                return oit_fail(err, OIT_E_INPUT, "%s: element at row %d, column %d is not a finite number",
                                what, row, col);
            out[col * 4 + row] = value;
        }
    return OIT_OK;
}

oit_status parse_matrix(const char *flag, const char *text, double out[16], oit_error *err)
{
    double values[16];
    int count = parse_number_list(text, values, 16);
    if (count < 0)
        return oit_fail(err, OIT_E_INPUT, "%s: '%s' is not a list of numbers", flag, text);
    if (count != 16)
        return oit_fail(err, OIT_E_INPUT, "%s needs 16 comma-separated numbers (row by row), got %d",
                        flag, count);
    return matrix_from_rows(flag, values, out, err);
}

oit_status parse_size(const char *text, int *width, int *height, oit_error *err)
{
    char buffer[64];
    if (strlen(text) >= sizeof buffer)
        return oit_fail(err, OIT_E_INPUT, "--size: '%.40s...' is not WxH", text);
    strcpy(buffer, text);
    char *x = strchr(buffer, 'x');
    if (!x)
        return oit_fail(err, OIT_E_INPUT, "--size: '%s' is not WxH (for example 256x256)", text);
    *x = '\0';
    long w, h;
    if (!parse_int(buffer, 0, 1000000000L, &w) || !parse_int(x + 1, 0, 1000000000L, &h))
        return oit_fail(err, OIT_E_INPUT, "--size: '%s' is not WxH (for example 256x256)", text);
    if (w < 1 || h < 1)
        return oit_fail(err, OIT_E_INPUT, "--size %s: width and height must be at least 1", text);
    if (w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE)
        return oit_fail(err, OIT_E_INPUT, "--size %s is too large: at most %d pixels per side", text,
                        MAX_IMAGE_SIDE);
    *width = (int)w;
    *height = (int)h;
    return OIT_OK;
}

static oit_status parse_colour(const char *flag, const char *text, float out[3], oit_error *err)
{
    double values[3];
    int count = parse_number_list(text, values, 3);
    if (count != 3)
        return oit_fail(err, OIT_E_INPUT, "%s needs R,G,B with each in [0, 1], got '%s'", flag, text);
    for (int i = 0; i < 3; ++i) {
        if (!(values[i] >= 0.0 && values[i] <= 1.0))
            return oit_fail(err, OIT_E_INPUT, "%s: component %d (%g) is outside [0, 1]", flag, i,
                            values[i]);
        out[i] = (float)values[i];
    }
    return OIT_OK;
}

/* ----------------------------------------------------- render options */

void render_options_defaults(render_options *o)
{
    memset(o, 0, sizeof *o);
    o->algorithm = oit_algorithm_find("ll");
    o->width = o->height = 256;
    o->alpha = 0.5f;
    o->shading = OIT_SHADE_HEADLIGHT;
    o->background[0] = o->background[1] = o->background[2] = 1.0f;
    o->backend = OIT_BACKEND_EGL;
    oit_algorithm_config_defaults(&o->config);
    o->frames = 1;
    oit_overlay_options_defaults(&o->overlay);
    o->samples = 0; /* not given: 1 (anti-aliasing off), or the algorithm's own default (OIT_OPTION_SAMPLES) */
}

/* Parses one render option at argv[*i]; returns 1 if consumed, 0 if unknown, -1 on error. */
int parse_render_option(int argc, char **argv, int *i, render_options *o, oit_error *err,
                               oit_status *status)
{
    const char *flag = argv[*i];
    const char *value = NULL;
#define NEED_VALUE()                                                                      \
    do {                                                                                  \
        if (*i + 1 >= argc) {                                                             \
            *status = oit_fail(err, OIT_E_INPUT, "%s needs a value", flag);              \
            return -1;                                                                    \
        }                                                                                 \
        value = argv[++*i];                                                               \
    } while (0)
#define CHECK(call)                                                                       \
    do {                                                                                  \
        if ((*status = (call)) != OIT_OK)                                                 \
            return -1;                                                                    \
    } while (0)

    if (strcmp(flag, "--model") == 0) {
        NEED_VALUE();
        o->model_path = value;
    } else if (strcmp(flag, "--tessellation") == 0) {
        NEED_VALUE();
        CHECK(oit_import_options_parse_tessellation(value, &o->import, err));
    } else if (strcmp(flag, "--out") == 0) {
        NEED_VALUE();
        o->out_path = value;
    } else if (strcmp(flag, "--algorithm") == 0) {
        NEED_VALUE();
        o->algorithm = oit_algorithm_find(value);
        if (!o->algorithm) {
            *status = oit_fail(err, OIT_E_INPUT, "unknown algorithm '%s' (oit algorithms lists them)",
                               value);
            return -1;
        }
    } else if (strcmp(flag, "--size") == 0) {
        NEED_VALUE();
        CHECK(parse_size(value, &o->width, &o->height, err));
    } else if (strcmp(flag, "--modelview") == 0) {
        NEED_VALUE();
        CHECK(parse_matrix("--modelview", value, o->modelview, err));
        o->has_modelview = true;
    } else if (strcmp(flag, "--projection") == 0) {
        NEED_VALUE();
        CHECK(parse_matrix("--projection", value, o->projection, err));
        o->has_projection = true;
    } else if (strcmp(flag, "--orbit") == 0) {
        NEED_VALUE();
        double angles[2];
        if (parse_number_list(value, angles, 2) != 2 || !(fabs(angles[0]) <= 360.0) ||
            !(fabs(angles[1]) <= 90.0)) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--orbit needs AZIMUTH,ELEVATION in degrees (|azimuth| <= 360, |elevation| <= 90), got '%s'",
                               value);
            return -1;
        }
        o->orbit[0] = (float)angles[0];
        o->orbit[1] = (float)angles[1];
    } else if (strcmp(flag, "--alpha") == 0) {
        NEED_VALUE();
        double a;
        if (!parse_double(value, &a) || !(a >= 0.0 && a <= 1.0)) {
            *status = oit_fail(err, OIT_E_INPUT, "--alpha must be a number in [0, 1], got '%s'", value);
            return -1;
        }
        o->alpha = (float)a;
    } else if (strcmp(flag, "--shading") == 0) {
        NEED_VALUE();
        int shading;
        CHECK(oit_setting_parse(OIT_SETTING_SHADING, value, &shading, err));
        o->shading = (oit_shading_mode)shading;
    } else if (strcmp(flag, "--background") == 0) {
        NEED_VALUE();
        CHECK(parse_colour("--background", value, o->background, err));
    } else if (strcmp(flag, "--samples") == 0) {
        NEED_VALUE();
        long n;
        /* the core's table of sample counts (oit_sample_positions) is the one rule */
        if (!parse_int(value, 1, OIT_SAMPLES_MAX, &n) || oit_sample_positions((int)n, NULL) == 0) {
            *status = oit_fail(err, OIT_E_INPUT, "--samples must be 1, 4, 8 or 16, got '%s'", value);
            return -1;
        }
        o->samples = (int)n;
    } else if (strcmp(flag, "--seed") == 0) {
        NEED_VALUE();
        long seed;
        if (!parse_int(value, 0, 4294967295L, &seed)) {
            *status = oit_fail(err, OIT_E_INPUT, "--seed must be a whole number from 0 to 4294967295, got '%s'",
                               value);
            return -1;
        }
        o->config.seed = (uint32_t)seed;
    } else if (strcmp(flag, "--stochastic-masks") == 0) {
        NEED_VALUE();
        if (strcmp(value, "stratified") == 0)
            o->config.stochastic_masks = OIT_STOCHASTIC_STRATIFIED;
        else if (strcmp(value, "independent") == 0)
            o->config.stochastic_masks = OIT_STOCHASTIC_INDEPENDENT;
        else {
            *status = oit_fail(err, OIT_E_INPUT, "--stochastic-masks must be stratified or independent, got '%s'",
                               value);
            return -1;
        }
    } else if (strcmp(flag, "--backend") == 0) {
        NEED_VALUE();
        int backend;
        CHECK(oit_setting_parse(OIT_SETTING_BACKEND, value, &backend, err));
        o->backend = (oit_backend)backend;
    } else if (strcmp(flag, "--max-memory") == 0) {
        NEED_VALUE();
        long mb;
        if (!parse_int(value, 1, 1L << 22, &mb)) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--max-memory must be a whole number of MB in [1, 4194304], got '%s'", value);
            return -1;
        }
        o->config.max_memory_bytes = (uint64_t)mb * 1024 * 1024;
    } else if (strcmp(flag, "--sort") == 0) {
        NEED_VALUE();
        int sort;
        CHECK(oit_setting_parse(OIT_SETTING_SORT, value, &sort, err));
        o->config.ll_sort = (oit_ll_sort)sort;
    } else if (strcmp(flag, "--max-layers") == 0) {
        NEED_VALUE();
        long layers;
        if (!parse_int(value, 1, OIT_PEEL_LAYER_CAP_MAX, &layers)) {
            *status = oit_fail(err, OIT_E_INPUT, "--max-layers must be a whole number from 1 to %d, got '%s'",
                               OIT_PEEL_LAYER_CAP_MAX, value);
            return -1;
        }
        o->config.max_layers = (int)layers;
    } else if (strcmp(flag, "--layers") == 0) {
        NEED_VALUE();
        long layers;
        if (!parse_int(value, 1, OIT_LAYERS_MAX, &layers)) {
            *status = oit_fail(err, OIT_E_INPUT, "--layers must be a whole number from 1 to %d, got '%s'",
                               OIT_LAYERS_MAX, value);
            return -1;
        }
        o->config.layers = (int)layers;
    } else if (strcmp(flag, "--moments") == 0) {
        NEED_VALUE();
        int moments;
        CHECK(oit_setting_parse(OIT_SETTING_MOMENTS, value, &moments, err));
        o->config.moments = (oit_moments)moments;
    } else if (strcmp(flag, "--wavelet-rank") == 0) {
        NEED_VALUE();
        long rank;
        if (!parse_int(value, 1, OIT_WAVELET_RANK_MAX, &rank)) {
            *status = oit_fail(err, OIT_E_INPUT, "--wavelet-rank must be a whole number from 1 to %d, got '%s'",
                               OIT_WAVELET_RANK_MAX, value);
            return -1;
        }
        o->config.wavelet_rank = (int)rank;
    } else if (strcmp(flag, "--fragment-pool") == 0) {
        NEED_VALUE();
        long capacity;
        if (!parse_int(value, 1, 1L << 30, &capacity)) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--fragment-pool must be a whole number of fragments in [1, 2^30], got '%s'", value);
            return -1;
        }
        o->config.initial_fragment_capacity = (uint64_t)capacity;
    } else if (strcmp(flag, "--fragment-counter-start") == 0) {
        NEED_VALUE();
        long start;
        if (!parse_int(value, 0, 4294967295L, &start)) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--fragment-counter-start must be a whole number in [0, 4294967295], got '%s'",
                               value);
            return -1;
        }
        o->config.fragment_counter_start = (uint32_t)start;
    } else if (strcmp(flag, "--buffer-fragment-limit") == 0) {
        NEED_VALUE();
        long limit;
        if (!parse_int(value, 1, 1L << 30, &limit)) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--buffer-fragment-limit must be a whole number of fragments in [1, 2^30], got '%s'",
                               value);
            return -1;
        }
        o->config.buffer_fragment_limit = (uint64_t)limit;
    } else if (strcmp(flag, "--locks-held") == 0) {
        o->config.locks_held = true;
    } else if (strcmp(flag, "--frames") == 0) {
        NEED_VALUE();
        long frames;
        if (!parse_int(value, 1, MAX_FRAMES, &frames)) {
            *status = oit_fail(err, OIT_E_INPUT, "--frames must be a whole number in [1, %d], got '%s'",
                               MAX_FRAMES, value);
            return -1;
        }
        o->frames = (int)frames;
    } else if (strcmp(flag, "--explode") == 0) {
        NEED_VALUE();
        double factor;
        if (!parse_double(value, &factor) || !(factor >= 0.0 && factor <= OIT_EXPLODE_MAX)) {
            *status = oit_fail(err, OIT_E_INPUT, "--explode must be a number in [0, %g], got '%s'",
                               OIT_EXPLODE_MAX, value);
            return -1;
        }
        o->explode = factor;
    } else if (strcmp(flag, "--axes") == 0) {
        o->overlay.axes = true;
        o->overlay.axes_corner = OIT_CORNER_BOTTOM_LEFT;
    } else if (strncmp(flag, "--axes=", 7) == 0) {
        if (oit_corner_parse(flag + 7, &o->overlay.axes_corner, err) != OIT_OK) {
            *status = oit_fail(err, OIT_E_INPUT,
                               "--axes=%.60s: no such corner (bottom-left, bottom-right, top-left or top-right)",
                               flag + 7);
            return -1;
        }
        o->overlay.axes = true;
    } else if (strcmp(flag, "--scale-bar") == 0) {
        o->overlay.scale_bar = true;
    } else if (strcmp(flag, "--json") == 0) {
        o->json = true;
    } else if (strcmp(flag, "--debug") == 0) {
        o->config.debug = true;
    } else {
        int parsed = oit_cli_parse_local_option(argc, argv, i, err, status);
        if (parsed != 0)
            return parsed;
        return oit_cli_parse_modulation_option(argc, argv, i, &o->modulation, &o->config, err, status);
    }
    return 1;
#undef NEED_VALUE
#undef CHECK
}

/* ------------------------------------------------------- render session */

oit_status session_open(session *s, const char *model_path, oit_backend backend, bool debug,
                        oit_error *err)
{
    return session_open_import(s, model_path, backend, debug, NULL, err);
}

oit_status session_open_import(session *s, const char *model_path, oit_backend backend, bool debug,
                               const oit_import_options *import, oit_error *err)
{
    memset(s, 0, sizeof *s);
    if (import)
        s->import = *import;
    s->backend = backend;
    s->debug = debug;
    return session_set_model(s, model_path, err);
}

oit_status session_need_gl(session *s, oit_error *err)
{
    if (s->gl && s->gpu_scene_uploaded)
        return OIT_OK;
    oit_status status = s->shader_dir[0] ? OIT_OK
                                         : oit_find_shader_dir(program_path, s->shader_dir, sizeof s->shader_dir, err);
    if (status != OIT_OK)
        return status;
    if (!s->gl) {
        status = oit_gl_context_create(s->backend, s->debug, &s->gl, err);
        if (status != OIT_OK)
            return status;
    }
    if (s->gpu_scene_uploaded)
        return OIT_OK;
    status = oit_scene_upload(&s->gpu_scene, &s->model, err);
    s->gpu_scene_uploaded = status == OIT_OK;
    return status;
}

/* Back to the model as loaded: the derived model, offsets and open parts go. */
static void session_drop_derived(session *s)
{
    if (s->derived) {
        if (s->gpu_scene_uploaded) {
            oit_scene_release(&s->gpu_scene);
            s->gpu_scene_uploaded = false;
        }
        oit_model_free(&s->model);
        s->model = s->source_model;
        memset(&s->source_model, 0, sizeof s->source_model);
        s->derived = false;
        oit_scene_cpu(&s->cpu_scene, &s->model);
    }
    free(s->offsets);
    s->offsets = NULL;
    free(s->open_cut);
    s->open_cut = NULL;
    s->has_sections = false;
    s->prepared = false;
}

oit_status session_prepare_model(session *s, const render_options *o, oit_error *err)
{
    if (s->prepared && s->prepared_explode == o->explode)
        return OIT_OK;
    session_drop_derived(s);
    const oit_model *model = &s->model;
    uint32_t parts = model->component_count;
    oit_status status = OIT_OK;
    if (o->explode != 0.0 && parts) {
        s->offsets = malloc((size_t)parts * 3 * sizeof *s->offsets);
        if (!s->offsets)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory for %u parts' offsets", parts);
        status = oit_explode_offsets(model, o->explode, s->offsets, err);
    }
    /* the sections and caps, as the frame will have them (names resolve the
     * same on the derived model: it keeps the parts) */
    oit_local_modulation local;
    if (status == OIT_OK)
        status = oit_cli_resolve_local_options(model, &local, err);
    if (status != OIT_OK) {
        session_drop_derived(s);
        return status;
    }
    s->has_sections = local.section_count > 0;
    bool needed = oit_model_derive_needed(model, s->offsets, s->offsets ? parts : 0, &local);
    /* open parts a section cuts are named even when no cap is made */
    bool open_part = false;
    for (uint32_t c = 0; local.section_count > 0 && !local.no_caps && c < parts; ++c)
        open_part = open_part || !model->components[c].closed;
    if (needed || open_part) {
        oit_model derived;
        s->open_cut = calloc(parts ? parts : 1, 1);
        status = s->open_cut ? oit_model_derive(model, s->offsets, s->offsets ? parts : 0, &local, &derived,
                                                s->open_cut, err)
                             : oit_fail(err, OIT_E_RUNTIME, "out of memory for %u parts", parts);
        if (status != OIT_OK) {
            session_drop_derived(s);
            return status;
        }
        if (needed) {
            if (s->gpu_scene_uploaded) {
                oit_scene_release(&s->gpu_scene);
                s->gpu_scene_uploaded = false;
            }
            s->source_model = s->model;
            s->model = derived;
            s->derived = true;
            oit_scene_cpu(&s->cpu_scene, &s->model);
        } else
            oit_model_free(&derived);
        /* one line naming the open parts a section cuts */
        bool named = false;
        for (uint32_t c = 0; c < parts; ++c) {
            if (!s->open_cut[c])
                continue;
            fprintf(stderr, "%s%s", named ? ", " : "oit: warning: section cuts open parts (no cap): ",
                    s->model.components[c].name);
            named = true;
        }
        if (named)
            fputc('\n', stderr);
    }
    s->prepared = true;
    s->prepared_explode = o->explode;
    return OIT_OK;
}

oit_status session_set_model(session *s, const char *model_path, oit_error *err)
{
    session_drop_derived(s);
    if (s->gpu_scene_uploaded) {
        oit_scene_release(&s->gpu_scene);
        s->gpu_scene_uploaded = false;
    }
    if (s->model_loaded) {
        oit_model_free(&s->model);
        s->model_loaded = false;
    }
    /* a FIFO, /dev/zero or a directory is refused before the importer sees it */
    oit_status status = oit_check_regular_file(model_path, "model", err);
    if (status == OIT_OK)
        status = oit_model_load_contained_with(model_path, NULL, &s->import, &s->model, err);
    if (status != OIT_OK)
        return status;
    print_model_warnings(&s->model);
    s->model_loaded = true;
    oit_scene_cpu(&s->cpu_scene, &s->model);
    return OIT_OK;
}

void session_close(session *s)
{
    if (s->gpu_scene_uploaded)
        oit_scene_release(&s->gpu_scene);
    if (s->gl)
        oit_gl_context_destroy(s->gl);
    if (s->model_loaded)
        oit_model_free(&s->model);
    if (s->derived)
        oit_model_free(&s->source_model);
    free(s->offsets);
    free(s->open_cut);
    memset(s, 0, sizeof *s);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double median(double *values, int count)
{
    if (count <= 0)
        return 0.0;
    qsort(values, (size_t)count, sizeof values[0], compare_double);
    return count % 2 ? values[count / 2] : 0.5 * (values[count / 2 - 1] + values[count / 2]);
}

/* Median of every figure over the measured frames (frame 1 pays for shader
 * compilation and is left out when there is more than one frame). */
static void median_stats(const oit_stats *frames, int frame_count, oit_stats *out)
{
    int first = frame_count > 1 ? 1 : 0;
    int measured = frame_count - first;
    double *values = malloc(sizeof(double) * (size_t)measured);
    *out = frames[frame_count - 1];
    if (!values)
        return;
    for (int f = 0; f < measured; ++f)
        values[f] = frames[first + f].cpu_ms;
    out->cpu_ms = median(values, measured);
    for (int stage = 0; stage < out->stage_count; ++stage) {
        int n = 0;
        for (int f = 0; f < measured; ++f) {
            const oit_stats *s = &frames[first + f];
            if (stage < s->stage_count && strcmp(s->stages[stage].name, out->stages[stage].name) == 0)
                values[n++] = s->stages[stage].gpu_ms;
        }
        out->stages[stage].gpu_ms = median(values, n);
    }
    free(values);
}

oit_status render_frame_settings(const session *s, const render_options *o, oit_frame_settings *frame,
                                 oit_error *err)
{
    memset(frame, 0, sizeof *frame);
    frame->width = o->width;
    frame->height = o->height;
    double default_modelview[16], default_projection[16];
    if (!o->has_modelview || !o->has_projection) {
        oit_status status = oit_default_camera(&s->model, o->width, o->height, o->orbit[0], o->orbit[1],
                                               default_modelview, default_projection, err);
        if (status != OIT_OK)
            return status;
    }
    memcpy(frame->modelview, o->has_modelview ? o->modelview : default_modelview, sizeof frame->modelview);
    memcpy(frame->projection, o->has_projection ? o->projection : default_projection,
           sizeof frame->projection);
    frame->alpha = o->alpha;
    frame->shading = o->shading;
    frame->samples = o->samples;
    memcpy(frame->background, o->background, sizeof frame->background);
    frame->modulation = o->modulation;
    oit_status status = oit_cli_resolve_local_options(&s->model, &frame->local, err);
    if (status != OIT_OK)
        return status;
    return oit_matrices_validate(frame->modelview, frame->projection, err);
}

oit_status render_setup_create(session *s, const render_options *o, render_setup *setup,
                               oit_error *err)
{
    const oit_algorithm_ops *ops = o->algorithm;
    memset(setup, 0, sizeof *setup);
    oit_status status = session_prepare_model(s, o, err);
    if (status != OIT_OK)
        return status;
    if (ops->uses_gl) {
        status = session_need_gl(s, err);
        if (status != OIT_OK)
            return status;
    }
    oit_algorithm_config config = o->config;
    config.shader_dir = s->shader_dir;
    status = render_frame_settings(s, o, &setup->frame, err);
    if (status == OIT_OK)
        status = oit_algorithm_create(ops, &config, &setup->alg, err);
    if (status == OIT_OK)
        status = oit_algorithm_resize(ops, setup->alg, o->width, o->height, err);
    setup->scene = ops->uses_gl ? &s->gpu_scene : &s->cpu_scene;
    return status;
}

oit_status render_overlay(const session *s, const render_options *o, const oit_frame_settings *frame,
                          oit_image *image, oit_overlay_info *info, oit_error *err)
{
    memset(info, 0, sizeof *info);
    if (!o->overlay.axes && !o->overlay.scale_bar)
        return OIT_OK; /* the image as rendered, byte for byte */
    const oit_model *loaded = s->derived ? &s->source_model : &s->model;
    oit_status status = oit_overlay_draw(image, &o->overlay, frame->modelview, frame->projection, loaded, info, err);
    if (status == OIT_OK && o->overlay.scale_bar && !info->scale_bar)
        fprintf(stderr, "oit: warning: --scale-bar: %s\n", info->scale_problem);
    return status;
}

oit_status render_frames(session *s, const render_options *o, render_result *result, oit_error *err)
{
    memset(result, 0, sizeof *result);
    result->gl_allocated_bytes = -1;
    const oit_algorithm_ops *ops = o->algorithm;
    oit_stats *per_frame = calloc((size_t)o->frames, sizeof *per_frame);
    if (!per_frame)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory for %d frames of statistics", o->frames);
    /* --json: what GL holds before the algorithm exists (the scene), to
     * count what the algorithm allocated independently of its figures */
    int64_t gl_bytes_before = -1;
    oit_status status = session_prepare_model(s, o, err);
    if (status == OIT_OK && o->json && ops->uses_gl) {
        status = session_need_gl(s, err);
        if (status == OIT_OK)
            gl_bytes_before = oit_gl_enumerate_allocated_bytes();
    }
    render_setup setup;
    memset(&setup, 0, sizeof setup);
    if (status == OIT_OK)
        status = render_setup_create(s, o, &setup, err);
    for (int f = 0; status == OIT_OK && f < o->frames; ++f) {
        status = oit_algorithm_render(ops, setup.alg, setup.scene, &setup.frame, err);
        if (status == OIT_OK)
            ops->stats(setup.alg, &per_frame[f]);
    }
    if (status == OIT_OK && gl_bytes_before >= 0) {
        int64_t after = oit_gl_enumerate_allocated_bytes();
        if (after >= 0)
            result->gl_allocated_bytes = after - gl_bytes_before;
    }
    if (status == OIT_OK)
        status = ops->read_image(setup.alg, &result->image, err);
    if (status == OIT_OK)
        status = render_overlay(s, o, &setup.frame, &result->image, &result->overlay, err);
    if (status == OIT_OK)
        median_stats(per_frame, o->frames, &result->stats);
    if (setup.alg)
        ops->destroy(setup.alg);
    free(per_frame);
    return status;
}

/* ------------------------------------------------------------- output */

oit_status check_output_path(const char *flag, const char *path, oit_error *err)
{
    /* a FIFO, a device, a directory, a name too long or a missing directory
     * is refused now, not after the work (oit.h, "files") */
    return oit_check_output_file(path, flag, err);
}

void warn_if_truncated(const char *what, const oit_algorithm_config *config, const oit_stats *stats)
{
    if (stats->truncated)
        fprintf(stderr,
                "oit: warning: %s: --max-layers %d cut the frame short: pixels with more layers "
                "lost their farther fragments (\"truncated\": true)\n",
                what, config->max_layers);
}

void print_model_warnings(const oit_model *model)
{
    for (uint32_t i = 0; i < model->warning_count; ++i)
        fprintf(stderr, "oit: warning: %s\n", model->warnings[i]);
}

double stages_total(const oit_stats *stats)
{
    double total = 0.0;
    for (int i = 0; i < stats->stage_count; ++i)
        total += stats->stages[i].gpu_ms;
    return total;
}

oit_status render_centre_reference(session *s, const render_options *o, oit_image *out, oit_error *err)
{
    render_options centre = *o;
    centre.samples = 0;
    render_result result;
    oit_status status = render_frames(s, &centre, &result, err);
    if (status == OIT_OK)
        *out = result.image;
    return status;
}
