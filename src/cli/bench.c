/*
 * bench.c: `oit bench` and `oit measure`.
 *
 * oit bench runs scenes x algorithms x sizes in one process: one GL context,
 * each model loaded and uploaded once, each algorithm created once per scene
 * and size, warm-up frames, then N measured frames whose figures are reported
 * as median, minimum and maximum. One row per run goes to CSV and/or JSON as
 * soon as it is measured: into FILE.tmp.XXXXXX beside FILE, renamed over FILE
 * when the run ends (oit_atomic_file), so the previous FILE stays whole until
 * then; a run that fails or is interrupted removes the temporary.
 *
 * oit measure is the source's measuring command line (thesis appendix E.3):
 * TASK COUNTER NAME PATH m00..m33 p00..p33 [VIEWPORT], one result line
 * appended to a results file per run.
 */
#define _GNU_SOURCE /* renameat2 (RENAME_EXCHANGE), open_memstream, strtok_r, fnmatch */
#include <dirent.h>
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "json_output.h"
#include "render_session.h"

#define BENCH_DEFAULT_FRAMES 10
#define BENCH_DEFAULT_WARMUP 2
#define BENCH_DEFAULT_SIZE 600 /* the thesis measured at 600x600 */
#define BENCH_DEFAULT_REFERENCE_PIXELS (256 * 256)
#define BENCH_DEFAULT_TOLERANCE 2 /* the exact algorithms' tolerance in the tests */
#define BENCH_MAX_SIZES 32
#define BENCH_MAX_ALGORITHMS 16
#define BENCH_MAX_TOKENS 256
#define BENCH_MIN_FRAMES 3
#define BENCH_ORBIT_MIN 2
#define BENCH_ORBIT_MAX 3600
#define BENCH_DEFAULT_ORBIT_STEP 0.5 /* degrees of azimuth per frame of --orbit-sequence */
/* --orbit-sequence keeps the reference's frames of a scene and size for the
 * next algorithms when they fit in this many bytes (else renders them again) */
#define BENCH_ORBIT_CACHE_BYTES (256ull << 20)

/* ------------------------------------------------------------ helpers */

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return 1000.0 * (double)t.tv_sec + 1e-6 * (double)t.tv_nsec;
}

typedef struct spread {
    double median, min, max;
} spread;

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

/* A CSV field: quoted when it holds a separator, a quote or a line break. */
static void csv_field(FILE *out, const char *text)
{
    if (strpbrk(text, ",\"\n\r") == NULL) {
        fputs(text, out);
        return;
    }
    fputc('"', out);
    for (const char *c = text; *c; ++c) {
        if (*c == '"')
            fputc('"', out);
        fputc(*c, out);
    }
    fputc('"', out);
}

static void iso_time(char *out, size_t size)
{
    time_t now = time(NULL);
    struct tm utc;
    gmtime_r(&now, &utc);
    strftime(out, size, "%Y-%m-%dT%H:%M:%SZ", &utc);
}

/* ------------------------------------------------------------- scenes */

typedef struct bench_scene {
    char *name;
    render_options options; /* model path and camera; the bench's own options underneath */
    char *view;             /* the options as given, for the output */
} bench_scene;

typedef struct scene_list {
    bench_scene *items;
    int count, capacity;
    char **owned; /* strings the options point into */
    int owned_count, owned_capacity;
} scene_list;

static char *keep(scene_list *list, const char *text)
{
    if (list->owned_count == list->owned_capacity) {
        int capacity = list->owned_capacity ? 2 * list->owned_capacity : 64;
        char **grown = realloc(list->owned, (size_t)capacity * sizeof *grown);
        if (!grown)
            return NULL;
        list->owned = grown;
        list->owned_capacity = capacity;
    }
    char *copy = strdup(text);
    if (copy)
        list->owned[list->owned_count++] = copy;
    return copy;
}

static void scene_list_free(scene_list *list)
{
    for (int i = 0; i < list->owned_count; ++i)
        free(list->owned[i]);
    free(list->owned);
    free(list->items);
    memset(list, 0, sizeof *list);
}

/* Adds a scene NAME MODEL [render options...] on top of the base options. */
static oit_status scene_add(scene_list *list, const render_options *base, int token_count, char **tokens,
                            const char *where, oit_error *err)
{
    if (token_count < 2)
        return oit_fail(err, OIT_E_INPUT, "%s: a scene needs NAME MODEL [render options], got %d word(s)",
                        where, token_count);
    if (list->count == list->capacity) {
        int capacity = list->capacity ? 2 * list->capacity : 32;
        bench_scene *grown = realloc(list->items, (size_t)capacity * sizeof *grown);
        if (!grown)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory for %d scenes", capacity);
        list->items = grown;
        list->capacity = capacity;
    }
    for (int k = 0; k < list->count; ++k)
        if (strcmp(list->items[k].name, tokens[0]) == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s' is named twice", where, tokens[0]);
    bench_scene *scene = &list->items[list->count];
    memset(scene, 0, sizeof *scene);
    scene->options = *base;
    char view[2048] = "";
    size_t used = 0;
    for (int t = 0; t < token_count; ++t) {
        char *owned = keep(list, tokens[t]);
        if (!owned)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
        tokens[t] = owned;
        /* the options as a scene line would give them: a word with blanks or quotes quoted */
        bool plain = owned[0] && !strpbrk(owned, " \t\"'\\#");
        if (t >= 2 && used < sizeof view)
            used += (size_t)snprintf(view + used, sizeof view - used, "%s%s", t > 2 ? " " : "", plain ? owned : "\"");
        for (const char *c = owned; t >= 2 && !plain && *c && used + 2 < sizeof view; ++c) {
            if (*c == '"' || *c == '\\')
                view[used++] = '\\';
            view[used++] = *c;
            view[used] = '\0';
        }
        if (t >= 2 && !plain && used + 1 < sizeof view) {
            view[used++] = '"';
            view[used] = '\0';
        }
    }
    scene->name = tokens[0];
    scene->options.model_path = tokens[1];
    oit_status status = OIT_OK;
    for (int t = 2; t < token_count; ++t) {
        if (strcmp(tokens[t], "--model") == 0 || strcmp(tokens[t], "--out") == 0 ||
            strcmp(tokens[t], "--algorithm") == 0 || strcmp(tokens[t], "--size") == 0 ||
            strcmp(tokens[t], "--frames") == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': %s belongs on the bench's command line", where,
                            scene->name, tokens[t]);
        /* the local modulation flags keep process-wide state: they would pile up across scenes */
        static const char *const process_wide[] = {"--component-alpha", "--hide", "--focus-point",
                                                   "--focus-plane", "--focus-box", "--contrast"};
        for (size_t k = 0; k < sizeof process_wide / sizeof process_wide[0]; ++k)
            if (strcmp(tokens[t], process_wide[k]) == 0)
                return oit_fail(err, OIT_E_INPUT,
                                "%s: scene '%s': %s applies to every scene: give it on the bench's command line",
                                where, scene->name, tokens[t]);
        int parsed = parse_render_option(token_count, tokens, &t, &scene->options, err, &status);
        if (parsed < 0) {
            char message[OIT_ERROR_MESSAGE_SIZE];
            snprintf(message, sizeof message, "%s", err->message);
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': %s", where, scene->name, message);
        }
        if (parsed == 0)
            return oit_fail(err, OIT_E_INPUT, "%s: scene '%s': unknown option '%s'", where, scene->name,
                            tokens[t]);
    }
    scene->view = keep(list, view);
    if (!scene->view)
        return oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
    ++list->count;
    return OIT_OK;
}

/* Splits a scene-list line into words, in place: blanks separate words;
 * '...' keeps what it holds as it is, "..." too except that \" and \\ stand
 * for " and \ (a path with blanks: "my models/a b.obj"); a '#' that starts a
 * word starts a comment. The count, or -1 (too many words) or -2 (a quote
 * left open). */
static int split_words(char *line, char **words, int capacity)
{
    int count = 0;
    char *in = line, *out = line;
    for (;;) {
        while (*in == ' ' || *in == '\t' || *in == '\r' || *in == '\n')
            ++in;
        if (!*in || *in == '#')
            return count;
        if (count == capacity)
            return -1;
        words[count++] = out;
        while (*in && *in != ' ' && *in != '\t' && *in != '\r' && *in != '\n') {
            char quote = *in == '\'' || *in == '"' ? *in : 0;
            if (!quote) {
                *out++ = *in++;
                continue;
            }
            for (++in; *in != quote; ++in) {
                if (!*in)
                    return -2;
                if (quote == '"' && *in == '\\' && (in[1] == '"' || in[1] == '\\'))
                    ++in;
                *out++ = *in;
            }
            ++in; /* the closing quote */
        }
        char *end = out;
        if (*in)
            ++in; /* the blank after the word (out never passes in) */
        *end = '\0';
        out = end + 1;
    }
}

/* A scene list: one scene per line, NAME MODEL [render options], words
 * separated by blanks and quoted where they hold blanks (split_words); '#'
 * starts a comment. A model path that is not absolute is relative to the
 * list's folder; a UTF-8 byte order mark before the first line is skipped. */
static oit_status scene_list_read(scene_list *list, const render_options *base, const char *path,
                                  oit_error *err)
{
    FILE *file; /* a regular file: a FIFO or /dev/zero would never end */
    oit_status opened = oit_open_regular_file(path, "--scene-list", &file, err);
    if (opened != OIT_OK)
        return opened;
    /* getline: lines of any length, and their real length, so that a NUL
     * byte cannot cut a line short without a word */
    char *line = NULL;
    size_t line_capacity = 0;
    ssize_t length;
    int line_number = 0;
    oit_status status = OIT_OK;
    while (status == OIT_OK && (length = getline(&line, &line_capacity, file)) >= 0) {
        ++line_number;
        char where[4200];
        snprintf(where, sizeof where, "%s:%d", path, line_number);
        if (memchr(line, '\0', (size_t)length)) {
            status = oit_fail(err, OIT_E_INPUT, "%s: the line holds a NUL byte", where);
            break;
        }
        char *text = line;
        if (line_number == 1 && strncmp(text, "\xef\xbb\xbf", 3) == 0)
            text += 3; /* a byte order mark, as some editors write it */
        char *tokens[BENCH_MAX_TOKENS];
        int count = split_words(text, tokens, BENCH_MAX_TOKENS);
        if (count == -1)
            status = oit_fail(err, OIT_E_INPUT, "%s: more than %d words on the line", where, BENCH_MAX_TOKENS);
        else if (count == -2)
            status = oit_fail(err, OIT_E_INPUT, "%s: a quote is not closed", where);
        if (status != OIT_OK || count == 0)
            continue;
        /* a relative model path is the list's, not the working directory's */
        char *model = NULL;
        const char *slash = strrchr(path, '/');
        if (count >= 2 && tokens[1][0] != '/' && slash) {
            size_t folder = (size_t)(slash - path) + 1;
            model = malloc(folder + strlen(tokens[1]) + 1);
            if (!model) {
                status = oit_fail(err, OIT_E_RUNTIME, "out of memory reading scenes");
                break;
            }
            memcpy(model, path, folder);
            strcpy(model + folder, tokens[1]);
            tokens[1] = model;
        }
        status = scene_add(list, base, count, tokens, where, err); /* copies the words */
        free(model);
    }
    free(line);
    fclose(file);
    if (status == OIT_OK && list->count == 0)
        status = oit_fail(err, OIT_E_INPUT, "--scene-list %s holds no scenes", path);
    return status;
}

/* --scenes: comma-separated names or shell patterns (engine*). */
static bool scene_selected(const char *patterns, const char *name)
{
    if (!patterns)
        return true;
    char buffer[4096];
    snprintf(buffer, sizeof buffer, "%s", patterns);
    char *save = NULL;
    for (char *p = strtok_r(buffer, ",", &save); p; p = strtok_r(NULL, ",", &save))
        if (fnmatch(p, name, 0) == 0)
            return true;
    return false;
}

/* -------------------------------------------------------- one run */

/* One algorithm variant: a registry name, optionally with the ll sort
 * ("ll-array" is ll --sort array, as the thesis's table 5.3 compares) or a
 * parameter after a colon: NAME:K sets the layers of an algorithm that reads
 * them (kbuffer:16), NAME:MOMENTS its moments (mboit:power6). The label is
 * the text as given. */
typedef struct bench_algorithm {
    char label[48];
    const oit_algorithm_ops *ops;
    bool sort_array;
    int layers;          /* 0: the scene's --layers */
    oit_moments moments; /* OIT_MOMENTS_DEFAULT: the scene's --moments */
} bench_algorithm;

static const char *const moments_names[] = {"power4", "power6", "trig3"};
static const oit_moments moments_values[] = {OIT_MOMENTS_POWER4, OIT_MOMENTS_POWER6, OIT_MOMENTS_TRIG3};

/* What an algorithm's parameter may be, for messages. */
static const char *parameter_kind(const oit_algorithm_ops *ops)
{
    if (oit_algorithm_reads(ops, OIT_OPTION_LAYERS) && oit_algorithm_reads(ops, OIT_OPTION_MOMENTS))
        return "layers K or moments power4, power6 or trig3";
    return oit_algorithm_reads(ops, OIT_OPTION_LAYERS) ? "layers K" : "moments power4, power6 or trig3";
}

/* NAME[:PARAMETER] (item is modified). */
static oit_status parse_algorithm(char *item, bench_algorithm *a, oit_error *err)
{
    memset(a, 0, sizeof *a);
    if (strlen(item) >= sizeof a->label)
        return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s' is too long (at most %d characters)", item,
                        (int)sizeof a->label - 1);
    snprintf(a->label, sizeof a->label, "%s", item);
    char *colon = strchr(item, ':');
    const char *parameter = NULL;
    if (colon) {
        *colon = '\0';
        parameter = colon + 1;
    }
    const char *name = item;
    if (strcmp(name, "ll-array") == 0) {
        a->ops = oit_algorithm_find("ll");
        a->sort_array = true;
    } else {
        a->ops = oit_algorithm_find(name);
    }
    if (!a->ops)
        return oit_fail(err, OIT_E_INPUT,
                        "--algorithms: unknown algorithm '%s' (oit algorithms lists them; also ll-array)",
                        name);
    if (!parameter)
        return OIT_OK;
    if (!*parameter)
        return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': no parameter after the colon", a->label);
    bool numeric = strspn(parameter, "+-0123456789") == strlen(parameter);
    int moments = -1;
    for (int k = 0; k < 3; ++k)
        if (strcmp(parameter, moments_names[k]) == 0)
            moments = k;
    const oit_algorithm_ops *ops = a->ops;
    if (numeric && oit_algorithm_reads(ops, OIT_OPTION_LAYERS)) {
        long layers;
        if (!parse_int(parameter, 1, oit_approx_layers_max(), &layers))
            return oit_fail(err, OIT_E_INPUT,
                            "--algorithms: '%s': layers must be a whole number from 1 to %d", a->label,
                            oit_approx_layers_max());
        a->layers = (int)layers;
    } else if (moments >= 0 && oit_algorithm_reads(ops, OIT_OPTION_MOMENTS)) {
        a->moments = moments_values[moments];
    } else if (oit_algorithm_reads(ops, OIT_OPTION_LAYERS) || oit_algorithm_reads(ops, OIT_OPTION_MOMENTS)) {
        return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': %s takes %s, got '%s'", a->label, name,
                        parameter_kind(ops), parameter);
    } else {
        return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': %s takes no %s", a->label, name,
                        numeric        ? "layers"
                        : moments >= 0 ? "moments"
                                       : "parameter");
    }
    return OIT_OK;
}

static oit_status parse_algorithms(const char *text, bench_algorithm *out, int *count, oit_error *err)
{
    char buffer[1024];
    if (strlen(text) >= sizeof buffer)
        return oit_fail(err, OIT_E_INPUT, "--algorithms: list too long");
    strcpy(buffer, text);
    *count = 0;
    char *save = NULL;
    for (char *item = strtok_r(buffer, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
        if (*count == BENCH_MAX_ALGORITHMS)
            return oit_fail(err, OIT_E_INPUT, "--algorithms: at most %d", BENCH_MAX_ALGORITHMS);
        oit_status status = parse_algorithm(item, &out[*count], err);
        if (status != OIT_OK)
            return status;
        ++*count;
    }
    if (*count == 0)
        return oit_fail(err, OIT_E_INPUT, "--algorithms needs at least one name");
    return OIT_OK;
}

static oit_status parse_sizes(const char *text, int widths[], int heights[], int *count, oit_error *err)
{
    char buffer[1024];
    if (strlen(text) >= sizeof buffer)
        return oit_fail(err, OIT_E_INPUT, "--sizes: list too long");
    strcpy(buffer, text);
    *count = 0;
    char *save = NULL;
    for (char *item = strtok_r(buffer, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
        if (*count == BENCH_MAX_SIZES)
            return oit_fail(err, OIT_E_INPUT, "--sizes: at most %d", BENCH_MAX_SIZES);
        /* N alone means NxN */
        char square[64];
        if (!strchr(item, 'x') && strlen(item) < 30) {
            snprintf(square, sizeof square, "%sx%s", item, item);
            item = square;
        }
        oit_status status = parse_size(item, &widths[*count], &heights[*count], err);
        if (status != OIT_OK) {
            char message[OIT_ERROR_MESSAGE_SIZE];
            snprintf(message, sizeof message, "%s", err->message);
            return oit_fail(err, OIT_E_INPUT, "--sizes: %s", message + (strncmp(message, "--size", 6) == 0 ? 7 : 0));
        }
        ++*count;
    }
    if (*count == 0)
        return oit_fail(err, OIT_E_INPUT, "--sizes needs at least one WxH");
    return OIT_OK;
}

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
    /* --orbit-sequence: the temporal stability of the error (orbit_sequence) */
    int orbit_frames; /* 0: not measured */
    double flicker, flicker_max, orbit_rmse_mean;
} run_result;

/* Runs warm-up + measured frames of one algorithm on the session's model;
 * keeps the last image in *image when image is not NULL. */
/* budget_ms > 0: stop measuring once the measured frames took that long,
 * after at least BENCH_MIN_FRAMES of them (heavy scenes on llvmpipe). */
static oit_status run_algorithm(session *s, const render_options *o, int warmup, int frames, double budget_ms,
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
static double stages_sum(const run_result *r, const char *const *prefixes, int prefix_count)
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

/* -------------------------------------------------------- orbit sequence */

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
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) {
            double sum = 0.0;
            for (int k = 0; k < 4; ++k)
                sum += modelview[k * 4 + row] * m[col * 4 + k];
            out[col * 4 + row] = sum;
        }
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
    if (status == OIT_OK)
        status = oit_algorithm_render(&oit_algorithm_reference, reference->alg, reference->scene, &reference->frame, err);
    oit_image *target = cached ? cached : scratch;
    oit_image_free(target);
    if (status == OIT_OK)
        status = oit_algorithm_reference.read_image(reference->alg, target, err);
    *out = target;
    return status;
}

/* --orbit-sequence: count frames of a slow orbit (step_degrees of azimuth a
 * frame) with the algorithm, and the CPU reference of each. e = image -
 * reference per RGB channel (0..255); flicker is the mean over consecutive
 * frame pairs of mean |e(i) - e(i-1)| over pixels and channels, flicker_max
 * the largest pair, orbit_rmse_mean the mean of the frames' error rmse.
 * reference_frames: count images kept between the algorithms of one scene
 * and size (NULL: render the reference every time). */
static oit_status run_orbit(session *s, const render_options *o, int count, double step_degrees,
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

/* ------------------------------------------------------------- output */

static const char csv_header[] =
    "scene,model,view,algorithm,width,height,vertices,triangles,components,warmup,frames,"
    "cpu_ms_median,cpu_ms_min,cpu_ms_max,gpu_ms_median,gpu_ms_min,gpu_ms_max,memory_bytes,scene_bytes,"
    "fragments,max_list,mean_list,psi,layers,overflow_retries,bytes_per_fragment,ref_max_diff,"
    "ref_mean_diff,ref_over_tolerance_percent,error_rmse,error_psnr,error_ssim,error_max,error_share_over_2,"
    "flicker,flicker_max,orbit_rmse_mean,stages,error\n";
#define CSV_RUN_COLUMNS 29 /* warmup .. stages: empty in a failed run's row */

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

static void format_optional_int(char *out, size_t size, int64_t value)
{
    if (value >= 0)
        snprintf(out, size, "%lld", (long long)value);
    else
        out[0] = '\0';
}

static void format_optional_double(char *out, size_t size, double value)
{
    if (value >= 0.0)
        snprintf(out, size, "%.6g", value);
    else
        out[0] = '\0';
}

static void write_csv_row(FILE *f, const bench_scene *scene, const session *s, const char *label, int width,
                          int height, const run_result *r)
{
    const oit_stats *st = &r->last;
    const oit_model *m = &s->model;
    csv_field(f, scene->name);
    fputc(',', f);
    csv_field(f, scene->options.model_path);
    fputc(',', f);
    csv_field(f, scene->view);
    fprintf(f, ",%s,%d,%d,", label, width, height);
    if (s->model_loaded)
        fprintf(f, "%u,%u,%u", m->vertex_count, m->triangle_count, m->component_count);
    else
        fputs(",,", f);
    if (!r->ok) {
        for (int column = 0; column < CSV_RUN_COLUMNS; ++column)
            fputc(',', f);
        fputc(',', f);
        csv_field(f, r->error);
        fputc('\n', f);
        return;
    }
    char fragments[32], max_list[32], mean_list[32], psi[32], layers[32], retries[32], bpf[32];
    format_optional_int(fragments, sizeof fragments, st->fragments);
    format_optional_int(max_list, sizeof max_list, st->max_list);
    format_optional_double(mean_list, sizeof mean_list, st->mean_list);
    format_optional_double(psi, sizeof psi, st->psi);
    format_optional_int(layers, sizeof layers, st->layers);
    format_optional_int(retries, sizeof retries, st->overflow_retries);
    format_optional_double(bpf, sizeof bpf, st->bytes_per_fragment);
    fprintf(f, ",%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,%llu,%s,%s,%s,%s,%s,%s,%s,", r->warmup, r->frames,
            r->cpu_ms.median, r->cpu_ms.min, r->cpu_ms.max, r->gpu_ms.median, r->gpu_ms.min, r->gpu_ms.max,
            (unsigned long long)r->memory_max, (unsigned long long)s->gpu_scene.gpu_bytes, fragments,
            max_list, mean_list, psi, layers, retries, bpf);
    if (r->has_reference_diff)
        fprintf(f, "%d,%.6f,%.6f,", r->diff.max_channel_diff, r->diff.mean_diff,
                100.0 * r->diff.share_over_tolerance);
    else
        fputs(",,,", f);
    if (r->has_error) {
        const oit_image_error *e = &r->error_figures;
        fprintf(f, "%.9g,", e->rmse);
        if (isfinite(e->psnr_db)) /* empty: identical images */
            fprintf(f, "%.9g", e->psnr_db);
        fprintf(f, ",%.9g,%d,%.9g,", e->ssim, e->max, e->share_over_2);
    } else {
        fputs(",,,,,", f);
    }
    if (r->orbit_frames > 0)
        fprintf(f, "%.9g,%.9g,%.9g,", r->flicker, r->flicker_max, r->orbit_rmse_mean);
    else
        fputs(",,,", f);
    /* stages: name=median/min/max, separated by ';' */
    for (int j = 0; j < r->stage_count; ++j)
        fprintf(f, "%s%s=%.4f/%.4f/%.4f", j ? ";" : "", r->stages[j].name, r->stages[j].ms.median,
                r->stages[j].ms.min, r->stages[j].ms.max);
    fputs(",\n", f);
}

/* One row as a JSON object (--json's results, and the bundle's), with the
 * bundle's file names where files is not NULL. */
static void write_json_row(FILE *f, const bench_scene *scene, const session *s,
                           const bench_algorithm *algorithm, int width, int height, const run_result *r,
                           int tolerance, const row_files *files)
{
    const oit_stats *st = &r->last;
    const oit_model *m = &s->model;
    fprintf(f, "{\"scene\": ");
    json_string(f, scene->name);
    fprintf(f, ", \"model\": ");
    json_string(f, scene->options.model_path);
    fprintf(f, ", \"view\": ");
    json_string(f, scene->view);
    fprintf(f, ", \"algorithm\": ");
    json_string(f, algorithm->label);
    fprintf(f, ", \"width\": %d, \"height\": %d", width, height);
    if (s->model_loaded) {
        fprintf(f, ", \"vertices\": %u, \"triangles\": %u, \"components\": %u", m->vertex_count,
                m->triangle_count, m->component_count);
        json_warnings(f, m);
    }
    if (files) {
        const char *keys[3] = {"image", "reference_image", "error_map"};
        const char *names[3] = {files->image, files->reference, files->error_map};
        for (int k = 0; k < 3; ++k)
            if (names[k][0]) {
                fprintf(f, ", \"%s\": ", keys[k]);
                json_string(f, names[k]);
            }
    }
    if (!r->ok) {
        fprintf(f, ", \"error\": ");
        json_string(f, r->error);
        fputc('}', f);
        return;
    }
    fprintf(f, ", \"warmup\": %d, \"frames\": %d", r->warmup, r->frames);
    fprintf(f, ", \"cpu_ms\": {\"median\": %.4f, \"min\": %.4f, \"max\": %.4f}", r->cpu_ms.median,
            r->cpu_ms.min, r->cpu_ms.max);
    fprintf(f, ", \"gpu_ms\": {\"median\": %.4f, \"min\": %.4f, \"max\": %.4f}", r->gpu_ms.median,
            r->gpu_ms.min, r->gpu_ms.max);
    fprintf(f, ", \"stages\": [");
    for (int j = 0; j < r->stage_count; ++j)
        fprintf(f, "%s{\"name\": \"%s\", \"median\": %.4f, \"min\": %.4f, \"max\": %.4f}", j ? ", " : "",
                r->stages[j].name, r->stages[j].ms.median, r->stages[j].ms.min, r->stages[j].ms.max);
    fprintf(f, "], \"memory_bytes\": %llu, \"scene_bytes\": %llu", (unsigned long long)r->memory_max,
            (unsigned long long)s->gpu_scene.gpu_bytes);
    json_stats_figures(f, st, false);
    if (r->has_reference_diff)
        fprintf(f,
                ", \"reference\": {\"max_channel_diff\": %d, \"mean_diff\": %.6f, "
                "\"over_tolerance_percent\": %.6f, \"tolerance\": %d}",
                r->diff.max_channel_diff, r->diff.mean_diff, 100.0 * r->diff.share_over_tolerance, tolerance);
    if (r->has_error) {
        fputs(", ", f);
        json_image_error(f, &r->error_figures, "error_");
    }
    if (r->orbit_frames > 0)
        fprintf(f,
                ", \"orbit_frames\": %d, \"flicker\": %.9g, \"flicker_max\": %.9g, \"orbit_rmse_mean\": %.9g",
                r->orbit_frames, r->flicker, r->flicker_max, r->orbit_rmse_mean);
    fputc('}', f);
}

static void write_row(bench_output *out, const bench_scene *scene, const session *s,
                      const bench_algorithm *algorithm, int width, int height, const run_result *r)
{
    if (r->ok) {
        char what[OIT_NAME_SIZE * 2];
        snprintf(what, sizeof what, "%s, %s", scene->name, algorithm->label);
        warn_if_truncated(what, &scene->options.config, &r->last);
    }
    if (out->csv) {
        write_csv_row(out->csv, scene, s, algorithm->label, width, height, r);
        fflush(out->csv);
    }
    if (out->json) {
        fprintf(out->json, "%s\n    ", out->json_rows++ ? "," : "");
        write_json_row(out->json, scene, s, algorithm, width, height, r, out->tolerance, NULL);
        fflush(out->json);
    }
}

/* ------------------------------------------------------------ progress */

typedef struct progress_state {
    bool tty;
    int index, total;
    const char *scene, *algorithm;
    int width, height;
} progress_state;

static void progress_frame(void *data, int frame, int frames)
{
    const progress_state *p = data;
    if (p->tty)
        fprintf(stderr, "\rbench [%d/%d] %s %s %dx%d frame %d/%d\033[K", p->index, p->total, p->scene,
                p->algorithm, p->width, p->height, frame, frames);
}

static void progress_done(const progress_state *p, const run_result *r)
{
    if (p->tty)
        fputc('\r', stderr);
    if (r->ok)
        fprintf(stderr, "bench [%d/%d] %s %s %dx%d: cpu %.2f ms (median of %d), gpu %.2f ms%s\n", p->index,
                p->total, p->scene, p->algorithm, p->width, p->height, r->cpu_ms.median, r->frames,
                r->gpu_ms.median, p->tty ? "\033[K" : "");
    else
        fprintf(stderr, "bench [%d/%d] %s %s %dx%d: failed: %s%s\n", p->index, p->total, p->scene, p->algorithm,
                p->width, p->height, r->error, p->tty ? "\033[K" : "");
}

/* -------------------------------------------------------------- bench */

static const char bench_help[] =
    "usage: oit bench (--scene-list FILE | --model PATH [--name NAME]) [options] [render options]\n"
    "Scenes x algorithms x sizes in one process: warm-up frames, then N measured frames;\n"
    "per-stage and frame times (median, min, max), memory, fragments, longest list, Psi and the\n"
    "difference from the reference, one row per run as CSV and/or JSON.\n"
    "  --scene-list FILE      one scene per line: NAME MODEL [render options such as --orbit AZ,EL or\n"
    "                         --modelview/--projection]; '#' comments (bat/setup.py writes one)\n"
    "  --model PATH           a single scene (named --name, default the file name)\n"
    "  --scenes LIST          only these scenes: comma-separated names or patterns (engine*)\n"
    "  --algorithms LIST      default blend,dp,ddp,ll,ib,wboit; also reference and ll-array;\n"
    "                         NAME:K sets the layers of kbuffer, hybrid, mlab (kbuffer:16),\n"
    "                         NAME:MOMENTS the moments of mboit (mboit:power6)\n"
    "  --sizes LIST           WxH or N (NxN), comma-separated (default 600x600)\n"
    "  --frames N             measured frames per run (default 10)\n"
    "  --warmup N             frames rendered first and not measured (default 2)\n"
    "  --time-budget SECONDS  stop measuring a run after this long, once it has 3 frames (default: none)\n"
    "  --csv FILE             write the CSV there (default: stdout unless --json is given)\n"
    "  --json FILE            write the JSON there ('-' for stdout)\n"
    "  --reference-max-pixels N  compare with the CPU reference where width*height <= N\n"
    "                         (default 65536; 0: never)\n"
    "  --tolerance T          channel difference counted as a mismatch (default 2)\n"
    "  --orbit-sequence N     also render N frames (2..3600) of a slow orbit and the reference of\n"
    "                         each; report flicker, flicker_max and orbit_rmse_mean\n"
    "  --orbit-step DEG       azimuth per frame of the orbit sequence (default 0.5)\n"
    "  --bundle DIR           write a result bundle: images, reference images, error maps and\n"
    "                         bundle.json (command, commit, machine, driver, scenes, figures)\n"
    "  --quiet                no progress lines on stderr\n"
    "Render options (--backend, --alpha, --shading, --max-memory, ...) apply to every scene; a scene\n"
    "line's own options override them. A run that fails is a row with an error; the exit status is\n"
    "then 3 after every other run has finished.\n";

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

/* Returns -1 to go on, or the exit status (--help, bad arguments). */
static int parse_bench_arguments(int argc, char **argv, bench_settings *b)
{
    memset(b, 0, sizeof *b);
    render_options_defaults(&b->base);
    b->frames = BENCH_DEFAULT_FRAMES;
    b->warmup = BENCH_DEFAULT_WARMUP;
    b->reference_pixels = BENCH_DEFAULT_REFERENCE_PIXELS;
    b->tolerance = BENCH_DEFAULT_TOLERANCE;
    b->orbit_step = BENCH_DEFAULT_ORBIT_STEP;
    const char *algorithms_text = "blend,dp,ddp,ll,ib,wboit";
    const char *sizes_text = "600x600";
    oit_error err = {{0}};
    oit_status status = OIT_OK;
    for (int i = 0; i < argc; ++i) {
        const char *flag = argv[i];
        bool has_value = i + 1 < argc;
        if (strcmp(flag, "--help") == 0 || strcmp(flag, "-h") == 0) {
            fputs(bench_help, stdout);
            return EXIT_OK;
        } else if (strcmp(flag, "--quiet") == 0) {
            b->quiet = true;
        } else if (strcmp(flag, "--scene-list") == 0 && has_value) {
            b->scene_list_path = argv[++i];
        } else if (strcmp(flag, "--model") == 0 && has_value) {
            b->single_model = argv[++i];
        } else if (strcmp(flag, "--name") == 0 && has_value) {
            b->single_name = argv[++i];
        } else if (strcmp(flag, "--scenes") == 0 && has_value) {
            b->scene_patterns = argv[++i];
        } else if (strcmp(flag, "--algorithms") == 0 && has_value) {
            algorithms_text = argv[++i];
        } else if (strcmp(flag, "--sizes") == 0 && has_value) {
            sizes_text = argv[++i];
        } else if (strcmp(flag, "--csv") == 0 && has_value) {
            b->csv_path = argv[++i];
        } else if (strcmp(flag, "--json") == 0 && has_value) {
            b->json_path = argv[++i];
        } else if (strcmp(flag, "--frames") == 0 && has_value) {
            if (!parse_int(argv[++i], 1, MAX_FRAMES, &b->frames))
                return usage_error("--frames must be a whole number in [1, 10000], got '%s'", argv[i]);
        } else if (strcmp(flag, "--warmup") == 0 && has_value) {
            if (!parse_int(argv[++i], 0, MAX_FRAMES, &b->warmup))
                return usage_error("--warmup must be a whole number in [0, 10000], got '%s'", argv[i]);
        } else if (strcmp(flag, "--reference-max-pixels") == 0 && has_value) {
            if (!parse_int(argv[++i], 0, (long)MAX_IMAGE_SIDE * MAX_IMAGE_SIDE, &b->reference_pixels))
                return usage_error("--reference-max-pixels must be a whole number >= 0, got '%s'", argv[i]);
        } else if (strcmp(flag, "--time-budget") == 0 && has_value) {
            double seconds;
            if (!parse_double(argv[++i], &seconds) || !(seconds >= 0.0 && seconds <= 1e6))
                return usage_error("--time-budget must be a number of seconds >= 0, got '%s'", argv[i]);
            b->budget_ms = 1000.0 * seconds;
        } else if (strcmp(flag, "--tolerance") == 0 && has_value) {
            if (!parse_int(argv[++i], 0, 255, &b->tolerance))
                return usage_error("--tolerance must be a whole number in [0, 255], got '%s'", argv[i]);
        } else if (strcmp(flag, "--orbit-sequence") == 0 && has_value) {
            if (!parse_int(argv[++i], BENCH_ORBIT_MIN, BENCH_ORBIT_MAX, &b->orbit_frames))
                return usage_error(
                    "--orbit-sequence must be a whole number of frames from 2 to 3600, got '%s'", argv[i]);
        } else if (strcmp(flag, "--orbit-step") == 0 && has_value) {
            if (!parse_double(argv[++i], &b->orbit_step) ||
                !(fabs(b->orbit_step) > 0.0 && fabs(b->orbit_step) <= 360.0))
                return usage_error(
                    "--orbit-step must be a non-zero number of degrees, at most 360 either way, "
                    "got '%s'",
                    argv[i]);
            b->orbit_step_given = true;
        } else if (strcmp(flag, "--bundle") == 0 && has_value) {
            b->bundle_path = argv[++i];
        } else if (strcmp(flag, "--out") == 0 || strcmp(flag, "--algorithm") == 0 ||
                   strcmp(flag, "--size") == 0) {
            return usage_error("bench: %s is not a bench option: use --algorithms, --sizes or a scene list",
                               flag);
        } else {
            int parsed = parse_render_option(argc, argv, &i, &b->base, &err, &status);
            if (parsed < 0)
                return report(status, &err);
            if (parsed == 0)
                return usage_error("bench: unknown option or missing value '%s'", flag);
        }
    }
    if (!b->scene_list_path && !b->single_model)
        return usage_error("bench needs --scene-list FILE or --model PATH%s", "");
    if (b->orbit_step_given && b->orbit_frames == 0)
        return usage_error("--orbit-step needs --orbit-sequence N%s", "");
    status = parse_algorithms(algorithms_text, b->algorithms, &b->algorithm_count, &err);
    if (status == OIT_OK)
        status = parse_sizes(sizes_text, b->widths, b->heights, &b->size_count, &err);
    return status == OIT_OK ? -1 : report(status, &err);
}

/* The scenes of --scene-list and --model; how many --scenes selects. */
static oit_status bench_scenes(const bench_settings *b, scene_list *scenes, int *selected, oit_error *err)
{
    oit_status status = OIT_OK;
    if (b->scene_list_path)
        status = scene_list_read(scenes, &b->base, b->scene_list_path, err);
    if (status == OIT_OK && b->single_model) {
        const char *slash = strrchr(b->single_model, '/');
        char name[256];
        snprintf(name, sizeof name, "%s", b->single_name ? b->single_name : slash ? slash + 1 : b->single_model);
        char *dot = strrchr(name, '.');
        if (!b->single_name && dot && dot != name)
            *dot = '\0';
        char *tokens[2] = {name, (char *)b->single_model};
        status = scene_add(scenes, &b->base, 2, tokens, "--model", err);
    }
    *selected = 0;
    for (int k = 0; status == OIT_OK && k < scenes->count; ++k)
        *selected += scene_selected(b->scene_patterns, scenes->items[k].name);
    if (status == OIT_OK && *selected == 0)
        status = oit_fail(err, OIT_E_INPUT, "--scenes %s matches none of the %d scenes", b->scene_patterns,
                          scenes->count);
    return status;
}

/* Closes the outputs. The files are written beside their targets and renamed
 * over them here (oit_atomic_file), both or neither: when the run succeeded
 * (keep) and both were written whole; else they are dropped, leaving the
 * previous files as they were. A write that failed anywhere (a full disk) is
 * an error naming the file, not an exit 0 with a short file. */
static oit_status bench_output_close(bench_output *out, bool keep, oit_error *err)
{
    oit_status status = OIT_OK;
    oit_atomic_file *files[2] = {out->csv_file, out->json_file};
    FILE *streams[2] = {out->csv, out->json};
    const char *flags[2] = {"--csv", "--json"};
    for (int k = 0; k < 2; ++k) {
        oit_error file_err;
        oit_status file_status = OIT_OK;
        if (files[k] && keep)
            file_status = oit_atomic_file_finish(files[k], &file_err);
        else if (!files[k] && streams[k] == stdout && (fflush(stdout) != 0 || ferror(stdout)))
            file_status = oit_fail(&file_err, OIT_E_RUNTIME, "%s: cannot write stdout: %s", flags[k],
                                   strerror(errno));
        if (file_status != OIT_OK && status == OIT_OK) {
            status = file_status;
            *err = file_err;
        }
    }
    for (int k = 0; k < 2; ++k) {
        if (!files[k])
            continue;
        oit_error file_err;
        if (keep && status == OIT_OK) {
            status = oit_atomic_file_commit(files[k], &file_err); /* only the rename is left */
            if (status != OIT_OK)
                *err = file_err;
        } else {
            oit_atomic_file_abort(files[k], OIT_E_RUNTIME, NULL, NULL);
        }
    }
    out->csv = out->json = NULL;
    out->csv_file = out->json_file = NULL;
    return status;
}

/* True once a write to an output failed: the run stops rather than measure
 * what cannot be written. */
static bool bench_output_failed(const bench_output *out)
{
    return (out->csv_file && oit_atomic_file_failed(out->csv_file)) ||
           (out->json_file && oit_atomic_file_failed(out->json_file)) ||
           (out->csv == stdout && ferror(stdout)) || (out->json == stdout && ferror(stdout));
}

static oit_status bench_output_open(const bench_settings *b, bench_output *out, oit_error *err)
{
    memset(out, 0, sizeof *out);
    out->tolerance = (int)b->tolerance;
    oit_status status = OIT_OK;
    if (b->csv_path && strcmp(b->csv_path, "-") != 0) {
        status = oit_atomic_file_open(b->csv_path, "--csv", 0, &out->csv_file, err);
        if (status == OIT_OK)
            out->csv = oit_atomic_file_stream(out->csv_file);
    } else if (b->csv_path || (!b->json_path && !b->bundle_path)) {
        out->csv = stdout;
    }
    if (status == OIT_OK && b->json_path && strcmp(b->json_path, "-") != 0) {
        status = oit_atomic_file_open(b->json_path, "--json", 0, &out->json_file, err);
        if (status == OIT_OK)
            out->json = oit_atomic_file_stream(out->json_file);
    } else if (status == OIT_OK && b->json_path) {
        out->json = stdout;
    }
    if (status != OIT_OK) {
        oit_error ignored;
        bench_output_close(out, false, &ignored);
    }
    return status;
}

/* The CSV header, and the JSON's opening: date, renderer, machine, command. */
static void bench_output_begin(bench_output *out, const bench_settings *b, bool has_gl, int argc, char **argv)
{
    if (out->csv)
        fputs(csv_header, out->csv);
    if (!out->json)
        return;
    FILE *f = out->json;
    char date[64];
    iso_time(date, sizeof date);
    struct utsname machine;
    if (uname(&machine) != 0)
        memset(&machine, 0, sizeof machine);
    fprintf(f, "{\"date\": \"%s\", \"renderer\": ", date);
    json_string(f, has_gl ? oit_gl_renderer_string() : "none (CPU reference)");
    fprintf(f, ", \"backend\": \"%s\", \"machine\": ", b->base.backend == OIT_BACKEND_EGL ? "egl" : "osmesa");
    char machine_text[600];
    snprintf(machine_text, sizeof machine_text, "%s %s %s", machine.sysname, machine.release, machine.machine);
    json_string(f, machine_text);
    fprintf(f, ", \"command\": ");
    char command[4096] = "oit bench";
    size_t used = strlen(command);
    for (int i = 0; i < argc && used < sizeof command; ++i)
        used += (size_t)snprintf(command + used, sizeof command - used, " %s", argv[i]);
    json_string(f, command);
    fprintf(f, ", \"warmup\": %ld, \"frames\": %ld, \"time_budget_s\": %g", b->warmup, b->frames,
            b->budget_ms / 1000.0);
    if (b->orbit_frames > 0)
        fprintf(f, ", \"orbit_sequence\": %ld, \"orbit_step_degrees\": %.9g", b->orbit_frames, b->orbit_step);
    fprintf(f, ", \"results\": [");
    fflush(f);
}

static void bench_output_end(bench_output *out, int failures)
{
    if (!out->json)
        return;
    struct rusage usage;
    long max_rss_kb = getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss : -1;
    fprintf(out->json, "\n  ], \"failures\": %d, \"max_rss_kb\": %ld}\n", failures, max_rss_kb);
}

/* ------------------------------------------------------------- bundle */

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

/* The bundle's name of a scene or algorithm: letters, digits and '-' (the
 * rest become '-'), so that '_' and '.' separate the parts of a file name. */
static void bundle_part(char *out, size_t size, const char *text)
{
    size_t n = 0;
    for (const char *c = text; *c && n + 1 < size; ++c)
        out[n++] = (isalnum((unsigned char)*c) || *c == '-') ? *c : '-';
    out[n] = '\0';
}

/* The longest name a bundle file gets: SCENE_ALGORITHM_WxH.error.png. */
static size_t bundle_longest_name(const bench_settings *b, const scene_list *scenes, char *longest, size_t size)
{
    size_t most = 0;
    char scene_part[256], algorithm_part[64], name[512];
    for (int i = 0; i < scenes->count; ++i) {
        if (!scene_selected(b->scene_patterns, scenes->items[i].name))
            continue;
        bundle_part(scene_part, sizeof scene_part, scenes->items[i].name);
        for (int a = 0; a < b->algorithm_count; ++a) {
            bundle_part(algorithm_part, sizeof algorithm_part, b->algorithms[a].label);
            for (int z = 0; z < b->size_count; ++z) {
                int n = snprintf(name, sizeof name, "%s_%s_%dx%d.error.png", scene_part, algorithm_part,
                                 b->widths[z], b->heights[z]);
                if (n > 0 && (size_t)n > most) {
                    most = (size_t)n;
                    snprintf(longest, size, "%s", name);
                }
            }
        }
    }
    return most;
}

static oit_status bundle_check(const bench_settings *b, const scene_list *scenes, bench_bundle *bundle,
                               oit_error *err)
{
    const char *given = b->bundle_path;
    char *path = bundle->given;
    if (!*given)
        return oit_fail(err, OIT_E_INPUT, "--bundle: empty directory name");
    if (strlen(given) >= sizeof bundle->given)
        return oit_fail(err, OIT_E_INPUT, "--bundle: the path is too long");
    snprintf(path, sizeof bundle->given, "%s", given);
    for (size_t n = strlen(path); n > 1 && path[n - 1] == '/'; --n)
        path[n - 1] = '\0';
    if (strcmp(path, "/") == 0)
        return oit_fail(err, OIT_E_INPUT, "--bundle /: not a bundle directory");
    /* file names must be unique: scene_algorithm_WxH.png */
    char first[256], second[256];
    for (int i = 0; i < scenes->count; ++i)
        for (int j = 0; j < i; ++j) {
            if (!scene_selected(b->scene_patterns, scenes->items[i].name) ||
                !scene_selected(b->scene_patterns, scenes->items[j].name))
                continue;
            bundle_part(first, sizeof first, scenes->items[i].name);
            bundle_part(second, sizeof second, scenes->items[j].name);
            if (strcmp(first, second) == 0)
                return oit_fail(err, OIT_E_INPUT,
                                "--bundle: scenes '%s' and '%s' would share the file name '%s' in the bundle",
                                scenes->items[j].name, scenes->items[i].name, first);
        }
    for (int i = 0; i < b->algorithm_count; ++i)
        for (int j = 0; j < i; ++j) {
            bundle_part(first, sizeof first, b->algorithms[i].label);
            bundle_part(second, sizeof second, b->algorithms[j].label);
            if (strcmp(first, second) == 0)
                return oit_fail(
                    err, OIT_E_INPUT,
                    "--bundle: algorithms '%s' and '%s' would share the file name '%s' in the bundle",
                    b->algorithms[j].label, b->algorithms[i].label, first);
        }
    for (int i = 0; i < b->size_count; ++i)
        for (int j = 0; j < i; ++j)
            if (b->widths[i] == b->widths[j] && b->heights[i] == b->heights[j])
                return oit_fail(err, OIT_E_INPUT, "--bundle: size %dx%d is listed twice", b->widths[i],
                                b->heights[i]);
    /* the name, its links, its directory, a FIFO or a file in its place: as for every output */
    char *target = NULL;
    oit_status status = oit_output_target(path, "--bundle", &target, err);
    if (status != OIT_OK)
        return status;
    snprintf(bundle->path, sizeof bundle->path, "%s", target);
    bool too_long = strlen(target) >= sizeof bundle->path;
    free(target);
    if (too_long)
        return oit_fail(err, OIT_E_INPUT, "--bundle %s: the path is too long", path);
    /* the names of the files in it (and their temporaries' paths) */
    char longest[512] = "";
    size_t longest_length = bundle_longest_name(b, scenes, longest, sizeof longest);
    if (longest_length > NAME_MAX)
        return oit_fail(err, OIT_E_INPUT,
                        "--bundle %s: %s: the file name '%.60s...' would have %zu bytes (at most %d: shorten the "
                        "scene's name)",
                        path, strerror(ENAMETOOLONG), longest, longest_length, NAME_MAX);
    if (oit_temporary_path_length(bundle->path) + 1 + longest_length + 16 >= PATH_MAX)
        return oit_fail(err, OIT_E_INPUT, "--bundle %s: %s: its files' paths would pass %d bytes", path,
                        strerror(ENAMETOOLONG), PATH_MAX - 1);
    struct stat info;
    if (stat(bundle->path, &info) != 0)
        return OIT_OK; /* a new name */
    bundle->replaces = true;
    bundle->mode = info.st_mode & 07777;
    DIR *directory = opendir(bundle->path);
    if (!directory)
        return oit_fail(err, OIT_E_INPUT, "--bundle %s: cannot read: %s", path, strerror(errno));
    int entries = 0;
    bool has_json = false;
    char odd[256] = "";
    struct dirent *entry;
    while ((entry = readdir(directory)) != NULL) {
        if (strcmp(entry->d_name, ".") == 0 || strcmp(entry->d_name, "..") == 0)
            continue;
        ++entries;
        has_json |= strcmp(entry->d_name, "bundle.json") == 0;
        char full[4400];
        snprintf(full, sizeof full, "%s/%s", bundle->path, entry->d_name);
        struct stat item;
        if (!odd[0] && (lstat(full, &item) != 0 || !S_ISREG(item.st_mode)))
            snprintf(odd, sizeof odd, "%s", entry->d_name);
    }
    closedir(directory);
    if (entries > 0 && !has_json)
        return oit_fail(err, OIT_E_INPUT,
                        "--bundle %s: the directory is not empty and not a bundle (no bundle.json)", path);
    if (odd[0])
        return oit_fail(err, OIT_E_INPUT,
                        "--bundle %s: holds '%s', which is not a regular file: not a bundle", path, odd);
    return OIT_OK;
}

static oit_status bundle_open(const bench_settings *b, const scene_list *scenes, bench_bundle *bundle,
                              oit_error *err)
{
    memset(bundle, 0, sizeof *bundle);
    bundle->temp.fd = bundle->temp.watch = -1;
    oit_status status = bundle_check(b, scenes, bundle, err);
    if (status != OIT_OK)
        return status;
    oit_error temp_err;
    if (oit_temporary_create(bundle->path, true, &bundle->temp, &temp_err) != OIT_OK)
        return oit_fail(err, OIT_E_INPUT, "--bundle %s: cannot create its temporary folder: %s", bundle->given,
                        temp_err.message);
    /* the permissions of the bundle it replaces (else 0777 less the umask, as mkdir) */
    if (bundle->replaces && fchmod(bundle->temp.fd, (mode_t)bundle->mode) != 0)
        return oit_fail(err, OIT_E_INPUT, "--bundle %s: cannot give %s the permissions %o: %s", bundle->given,
                        bundle->temp.path, bundle->mode, strerror(errno));
    bundle->rows = open_memstream(&bundle->rows_text, &bundle->rows_size);
    bundle->scenes = open_memstream(&bundle->scenes_text, &bundle->scenes_size);
    if (!bundle->rows || !bundle->scenes)
        return oit_fail(err, OIT_E_RUNTIME, "--bundle: out of memory");
    return OIT_OK;
}

/* The driver, while the context is current. */
static void bundle_driver(bench_bundle *bundle, bool has_gl)
{
    const char *strings[3] = {"", "", ""};
    if (has_gl) {
        strings[0] = oit_gl_renderer_string();
        strings[1] = oit_gl_version_string();
        strings[2] = oit_gl_vendor_string();
    }
    snprintf(bundle->renderer, sizeof bundle->renderer, "%s", strings[0] ? strings[0] : "");
    snprintf(bundle->gl_version, sizeof bundle->gl_version, "%s", strings[1] ? strings[1] : "");
    snprintf(bundle->gl_vendor, sizeof bundle->gl_vendor, "%s", strings[2] ? strings[2] : "");
}

/* Writes an image into the bundle as NAME; a failure stops the run. */
static void bundle_png(bench_bundle *bundle, const char *name, const oit_image *image)
{
    if (bundle->status != OIT_OK)
        return;
    char path[4600];
    snprintf(path, sizeof path, "%s/%s", bundle->temp.path, name);
    oit_error err;
    if (oit_png_write(path, image, &err) != OIT_OK) {
        bundle->status = OIT_E_RUNTIME;
        oit_fail(&bundle->err, OIT_E_RUNTIME, "--bundle: %s", err.message);
    }
}

/* FNV-1a 64 of a file and its size; false if it cannot be read. */
static bool file_checksum(const char *path, uint64_t *hash, long long *bytes)
{
    FILE *file;
    if (oit_open_regular_file(path, NULL, &file, NULL) != OIT_OK)
        return false;
    uint64_t h = 0xcbf29ce484222325ull;
    long long total = 0;
    unsigned char buffer[65536];
    size_t n;
    while ((n = fread(buffer, 1, sizeof buffer, file)) > 0) {
        for (size_t k = 0; k < n; ++k) {
            h ^= buffer[k];
            h *= 0x100000001b3ull;
        }
        total += (long long)n;
    }
    bool ok = !ferror(file);
    fclose(file);
    *hash = h;
    *bytes = total;
    return ok;
}

/* A scene's entry: its model (path, bytes, checksum) and render options;
 * the cameras follow, one per size (bundle_camera), then bundle_scene_end. */
static void bundle_scene_begin(bench_bundle *bundle, const bench_scene *scene)
{
    FILE *f = bundle->scenes;
    const render_options *o = &scene->options;
    fprintf(f, "%s\n    {\"name\": ", bundle->scene_count++ ? "," : "");
    json_string(f, scene->name);
    fprintf(f, ", \"model\": ");
    json_string(f, o->model_path);
    uint64_t hash;
    long long bytes;
    if (file_checksum(o->model_path, &hash, &bytes))
        fprintf(f, ", \"model_bytes\": %lld, \"model_fnv1a64\": \"%016llx\"", bytes,
                (unsigned long long)hash);
    else
        fprintf(f, ", \"model_bytes\": null, \"model_fnv1a64\": null");
    fprintf(f, ", \"view\": ");
    json_string(f, scene->view);
    fprintf(
        f,
        ", \"render_options\": {\"alpha\": %.9g, \"shading\": \"%s\", \"background\": [%.9g, %.9g, %.9g], "
        "\"backend\": \"%s\", \"max_memory_bytes\": %llu, \"sort\": \"%s\", \"max_layers\": %d, "
        "\"layers\": %d, \"moments\": \"%s\", \"modulation\": \"%s\", \"orbit\": [%.9g, %.9g], "
        "\"matrices_given\": %s}",
        o->alpha, o->shading == OIT_SHADE_FLAT ? "flat" : "headlight", o->background[0], o->background[1],
        o->background[2], o->backend == OIT_BACKEND_EGL ? "egl" : "osmesa",
        (unsigned long long)o->config.max_memory_bytes,
        o->config.ll_sort == OIT_LL_SORT_LOCAL_ARRAY ? "array" : "insertion", o->config.max_layers,
        o->config.layers, oit_moments_name(o->config.moments), oit_modulation_mode_name(o->modulation.mode),
        o->orbit[0], o->orbit[1], o->has_modelview && o->has_projection ? "true" : "false");
    fprintf(f, ", \"cameras\": [");
    bundle->camera_count = 0;
}

static void bundle_camera(bench_bundle *bundle, const oit_frame_settings *frame)
{
    FILE *f = bundle->scenes;
    fprintf(f, "%s{\"width\": %d, \"height\": %d, \"modelview\": ", bundle->camera_count++ ? ", " : "",
            frame->width, frame->height);
    json_matrix_rows(f, frame->modelview);
    fprintf(f, ", \"projection\": ");
    json_matrix_rows(f, frame->projection);
    fputc('}', f);
}

static void bundle_scene_end(bench_bundle *bundle, oit_status load, const oit_error *load_err)
{
    fputc(']', bundle->scenes);
    if (load != OIT_OK) {
        fprintf(bundle->scenes, ", \"error\": ");
        json_string(bundle->scenes, load_err->message);
    }
    fputc('}', bundle->scenes);
}

static void bundle_row(bench_bundle *bundle, const bench_scene *scene, const session *s,
                       const bench_algorithm *algorithm, int width, int height, const run_result *r,
                       int tolerance, const row_files *files)
{
    fprintf(bundle->rows, "%s\n    ", bundle->row_count++ ? "," : "");
    write_json_row(bundle->rows, scene, s, algorithm, width, height, r, tolerance, files);
}

/* The commit of the source tree: $OIT_COMMIT when set (a script that knows
 * it), else `git describe --always --dirty` in the tree oit was built from
 * (OIT_SOURCE_DIR), else "unknown". */
static void source_commit(char *out, size_t size, const char **how)
{
    const char *given = getenv("OIT_COMMIT");
    if (given && *given) {
        snprintf(out, size, "%s", given);
        *how = "OIT_COMMIT";
        return;
    }
    snprintf(out, size, "unknown");
    *how = "unknown";
#ifdef OIT_SOURCE_DIR
    char quoted[4200];
    size_t n = 0;
    for (const char *c = OIT_SOURCE_DIR; *c && n + 5 < sizeof quoted; ++c) {
        if (*c == '\'') {
            memcpy(quoted + n, "'\\''", 4);
            n += 4;
        } else {
            quoted[n++] = *c;
        }
    }
    quoted[n] = '\0';
    char command[4400];
    snprintf(command, sizeof command,
             "git --no-optional-locks -C '%s' describe --always --dirty 2>/dev/null </dev/null", quoted);
    fflush(NULL);
    FILE *pipe = popen(command, "r");
    if (!pipe)
        return;
    char line[256] = "";
    bool got = fgets(line, sizeof line, pipe) != NULL;
    int exit_status = pclose(pipe);
    line[strcspn(line, "\r\n")] = '\0';
    if (got && exit_status == 0 && line[0]) {
        snprintf(out, size, "%s", line);
        *how = "git describe";
    }
#endif
}

/* The machine: uname, CPU model, logical CPUs, memory. */
static void json_machine(FILE *f)
{
    struct utsname machine;
    if (uname(&machine) != 0)
        memset(&machine, 0, sizeof machine);
    fprintf(f, "{\"sysname\": ");
    json_string(f, machine.sysname);
    fprintf(f, ", \"release\": ");
    json_string(f, machine.release);
    fprintf(f, ", \"version\": ");
    json_string(f, machine.version);
    fprintf(f, ", \"machine\": ");
    json_string(f, machine.machine);
    char cpu[256] = "unknown";
    FILE *cpuinfo = fopen("/proc/cpuinfo", "r");
    if (cpuinfo) {
        char line[1024];
        while (fgets(line, sizeof line, cpuinfo))
            if (strncmp(line, "model name", 10) == 0 && strchr(line, ':')) {
                const char *value = strchr(line, ':') + 1;
                value += strspn(value, " \t");
                snprintf(cpu, sizeof cpu, "%.*s", (int)strcspn(value, "\r\n"), value);
                break;
            }
        fclose(cpuinfo);
    }
    fprintf(f, ", \"cpu\": ");
    json_string(f, cpu);
    long cpus = sysconf(_SC_NPROCESSORS_ONLN), pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    fprintf(f, ", \"logical_cpus\": %ld, \"memory_bytes\": %lld}", cpus,
            pages > 0 && page > 0 ? (long long)pages * page : -1LL);
}

/* bundle.json, then DIR.tmp.XXXXXX renamed to DIR (a previous bundle at DIR
 * is moved aside first and removed after). */
static oit_status bundle_commit(bench_bundle *bundle, const bench_settings *b, bool has_gl, int argc,
                                char **argv, int failures, oit_error *err)
{
    if (bundle->status != OIT_OK) {
        *err = bundle->err;
        return bundle->status;
    }
    fclose(bundle->rows);
    fclose(bundle->scenes);
    bundle->rows = bundle->scenes = NULL;
    char path[4600];
    snprintf(path, sizeof path, "%s/bundle.json", bundle->temp.path);
    oit_atomic_file *file = NULL;
    oit_status status = oit_atomic_file_open(path, "--bundle", 0, &file, err);
    if (status != OIT_OK)
        return status;
    FILE *f = oit_atomic_file_stream(file);
    char date[64], commit[256];
    const char *how;
    iso_time(date, sizeof date);
    source_commit(commit, sizeof commit, &how);
    fprintf(f,
            "{\"format\": \"oit-bench-bundle\", \"version\": 1, \"date\": \"%s\", \"command\": [\"oit\", "
            "\"bench\"",
            date);
    for (int i = 0; i < argc; ++i) {
        fputs(", ", f);
        json_string(f, argv[i]);
    }
    fprintf(f, "],\n  \"commit\": ");
    json_string(f, commit);
    fprintf(f, ", \"commit_from\": \"%s\",\n  \"machine\": ", how);
    json_machine(f);
    fprintf(f, ",\n  \"driver\": {\"backend\": \"%s\", \"renderer\": ",
            b->base.backend == OIT_BACKEND_EGL ? "egl" : "osmesa");
    if (has_gl) {
        json_string(f, bundle->renderer);
        fprintf(f, ", \"gl_version\": ");
        json_string(f, bundle->gl_version);
        fprintf(f, ", \"gl_vendor\": ");
        json_string(f, bundle->gl_vendor);
    } else {
        fprintf(f, "null, \"gl_version\": null, \"gl_vendor\": null");
    }
    fprintf(f, "},\n  \"parameters\": {\"sizes\": [");
    for (int z = 0; z < b->size_count; ++z)
        fprintf(f, "%s[%d, %d]", z ? ", " : "", b->widths[z], b->heights[z]);
    fprintf(f,
            "], \"frames\": %ld, \"warmup\": %ld, \"time_budget_s\": %g, \"reference_max_pixels\": %ld, "
            "\"tolerance\": %ld, \"orbit_sequence\": %ld, \"orbit_step_degrees\": %.9g, \"scenes\": ",
            b->frames, b->warmup, b->budget_ms / 1000.0, b->reference_pixels, b->tolerance, b->orbit_frames,
            b->orbit_frames ? b->orbit_step : 0.0);
    if (b->scene_patterns)
        json_string(f, b->scene_patterns);
    else
        fputs("null", f);
    fprintf(f, ", \"algorithms\": [");
    for (int a = 0; a < b->algorithm_count; ++a) {
        const bench_algorithm *algorithm = &b->algorithms[a];
        fprintf(f, "%s{\"label\": ", a ? ", " : "");
        json_string(f, algorithm->label);
        fprintf(
            f, ", \"algorithm\": \"%s\", \"exact\": %s, \"sort\": %s, \"layers\": %d, \"moments\": %s%s%s}",
            algorithm->ops->name, algorithm->ops->exact ? "true" : "false",
            algorithm->sort_array ? "\"array\"" : "null", algorithm->layers, algorithm->moments ? "\"" : "",
            algorithm->moments ? oit_moments_name(algorithm->moments) : "null",
            algorithm->moments ? "\"" : "");
    }
    fprintf(f, "]},\n  \"scenes\": [");
    fwrite(bundle->scenes_text, 1, bundle->scenes_size, f);
    fprintf(f, "\n  ],\n  \"results\": [");
    fwrite(bundle->rows_text, 1, bundle->rows_size, f);
    fprintf(f, "\n  ],\n  \"failures\": %d}\n", failures);
    status = oit_atomic_file_commit(file, err);
    if (status != OIT_OK)
        return status;
    /* DIR: a previous bundle or an empty directory is swapped with the new
     * one in one step, then removed from the temporary's name */
    if (!bundle->replaces) {
        if (rename(bundle->temp.path, bundle->path) != 0)
            return oit_fail(err, OIT_E_RUNTIME, "--bundle %s: cannot rename %s to it: %s", bundle->given,
                            bundle->temp.path, strerror(errno));
        oit_temporary_release(&bundle->temp, false);
        return OIT_OK;
    }
    if (renameat2(AT_FDCWD, bundle->temp.path, AT_FDCWD, bundle->path, RENAME_EXCHANGE) == 0) {
        oit_temporary_release(&bundle->temp, true); /* the previous bundle, now at the temporary's name */
        return OIT_OK;
    }
    if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP)
        return oit_fail(err, OIT_E_RUNTIME, "--bundle %s: cannot replace it with %s: %s", bundle->given,
                        bundle->temp.path, strerror(errno));
    /* a file system that cannot swap: the previous one goes aside (onto an empty temporary folder) first */
    oit_temporary old;
    oit_error old_err;
    if (oit_temporary_create(bundle->path, true, &old, &old_err) != OIT_OK)
        return oit_fail(err, OIT_E_RUNTIME, "--bundle %s: cannot move the previous bundle aside: %s", bundle->given,
                        old_err.message);
    if (rename(bundle->path, old.path) != 0) {
        int saved = errno;
        oit_temporary_release(&old, true);
        return oit_fail(err, OIT_E_RUNTIME, "--bundle %s: cannot move the previous bundle aside: %s",
                        bundle->given, strerror(saved));
    }
    if (rename(bundle->temp.path, bundle->path) != 0) {
        int saved = errno;
        rename(old.path, bundle->path);
        oit_temporary_release(&old, false);
        return oit_fail(err, OIT_E_RUNTIME, "--bundle %s: cannot rename %s to it: %s", bundle->given,
                        bundle->temp.path, strerror(saved));
    }
    oit_temporary_release(&bundle->temp, false);
    oit_temporary_release(&old, true);
    return OIT_OK;
}

/* Drops what bundle_commit did not rename (a run that failed). */
static void bundle_close(bench_bundle *bundle)
{
    if (bundle->rows)
        fclose(bundle->rows);
    if (bundle->scenes)
        fclose(bundle->scenes);
    free(bundle->rows_text);
    free(bundle->scenes_text);
    oit_temporary_release(&bundle->temp, true);
    memset(bundle, 0, sizeof *bundle);
}

/* Every algorithm on one scene at one size, after the reference image where
 * the size allows; one row each. Returns the number of failed runs, or -1
 * when out of memory. */
static int bench_scene_size(const bench_settings *b, session *s, const bench_scene *scene, oit_status load,
                            const oit_error *load_err, int width, int height, bench_output *out,
                            bench_bundle *bundle, progress_state *progress)
{
    render_options o = scene->options;
    o.width = width;
    o.height = height;
    char scene_part[256];
    bundle_part(scene_part, sizeof scene_part, scene->name);
    row_files files;
    memset(&files, 0, sizeof files);
    if (bundle && load == OIT_OK) {
        oit_frame_settings frame;
        oit_error ignored;
        if (render_frame_settings(s, &o, &frame, &ignored) == OIT_OK)
            bundle_camera(bundle, &frame);
    }
    oit_image reference_image = {0};
    bool has_reference = false;
    if (load == OIT_OK && b->reference_pixels > 0 && (long)width * height <= b->reference_pixels) {
        render_options ro = o;
        ro.algorithm = oit_algorithm_find("reference");
        run_result *rr = calloc(1, sizeof *rr);
        oit_error ref_err = {{0}};
        if (rr)
            has_reference =
                run_algorithm(s, &ro, 0, 1, 0.0, rr, &reference_image, NULL, NULL, &ref_err) == OIT_OK;
        free(rr);
        if (!has_reference && !b->quiet)
            fprintf(stderr, "bench: %s %dx%d: no reference image: %s\n", scene->name, width, height,
                    rr ? ref_err.message : "out of memory");
        if (has_reference && bundle) {
            snprintf(files.reference, sizeof files.reference, "%s_%dx%d.reference.png", scene_part, width,
                     height);
            bundle_png(bundle, files.reference, &reference_image);
        }
    }
    /* --orbit-sequence: the reference's frames, kept for every algorithm when they fit */
    oit_image *orbit_references = NULL;
    if (load == OIT_OK && b->orbit_frames > 0 &&
        (unsigned long long)b->orbit_frames * (unsigned long long)width * (unsigned long long)height * 4ull <=
            BENCH_ORBIT_CACHE_BYTES)
        orbit_references = calloc((size_t)b->orbit_frames, sizeof *orbit_references);
    int failures = 0;
    for (int a = 0; a < b->algorithm_count; ++a) {
        const bench_algorithm *algorithm = &b->algorithms[a];
        o.algorithm = algorithm->ops;
        o.config.ll_sort = algorithm->sort_array ? OIT_LL_SORT_LOCAL_ARRAY : scene->options.config.ll_sort;
        o.config.layers = algorithm->layers ? algorithm->layers : scene->options.config.layers;
        o.config.moments = algorithm->moments ? algorithm->moments : scene->options.config.moments;
        run_result *r = calloc(1, sizeof *r);
        if (!r) {
            failures = -1;
            break;
        }
        progress->index++;
        progress->scene = scene->name;
        progress->algorithm = algorithm->label;
        progress->width = width;
        progress->height = height;
        oit_error run_err = *load_err;
        oit_status run = load;
        row_files *row = NULL;
        if (load == OIT_OK) {
            /* the CPU reference is measured on one frame: it is the oracle, not a contender */
            bool cpu = !o.algorithm->uses_gl;
            oit_image image = {0};
            run = run_algorithm(s, &o, cpu ? 0 : (int)b->warmup, cpu ? 1 : (int)b->frames, b->budget_ms, r,
                                has_reference || bundle ? &image : NULL, b->quiet ? NULL : progress_frame,
                                progress, &run_err);
            if (run == OIT_OK && has_reference) {
                oit_error compare_err;
                r->has_reference_diff = oit_image_compare(&image, &reference_image, (int)b->tolerance,
                                                          &r->diff, &compare_err) == OIT_OK;
                r->has_error = oit_image_error_compute(&image, &reference_image, &r->error_figures,
                                                       &compare_err) == OIT_OK;
            }
            if (run == OIT_OK && bundle) {
                char algorithm_part[64];
                bundle_part(algorithm_part, sizeof algorithm_part, algorithm->label);
                row = &files;
                snprintf(files.image, sizeof files.image, "%s_%s_%dx%d.png", scene_part, algorithm_part,
                         width, height);
                bundle_png(bundle, files.image, &image);
                files.error_map[0] = '\0';
                oit_image map = {0};
                oit_error map_err;
                if (has_reference &&
                    oit_image_error_map(&image, &reference_image, true, &map, &map_err) == OIT_OK) {
                    snprintf(files.error_map, sizeof files.error_map, "%s_%s_%dx%d.error.png", scene_part,
                             algorithm_part, width, height);
                    bundle_png(bundle, files.error_map, &map);
                }
                oit_image_free(&map);
            }
            oit_image_free(&image);
            if (run == OIT_OK && b->orbit_frames > 0)
                run = run_orbit(s, &o, (int)b->orbit_frames, b->orbit_step, orbit_references, r, &run_err);
        }
        if (run != OIT_OK) {
            r->ok = false;
            snprintf(r->error, sizeof r->error, "%s", run_err.message);
            ++failures;
        }
        write_row(out, scene, s, algorithm, width, height, r);
        if (bundle)
            bundle_row(bundle, scene, s, algorithm, width, height, r, (int)b->tolerance, row);
        if (!b->quiet)
            progress_done(progress, r);
        free(r);
    }
    if (orbit_references)
        for (long k = 0; k < b->orbit_frames; ++k)
            oit_image_free(&orbit_references[k]);
    free(orbit_references);
    oit_image_free(&reference_image);
    return failures;
}

int command_bench(int argc, char **argv)
{
    bench_settings *b = calloc(1, sizeof *b);
    bench_bundle *bundle = calloc(1, sizeof *bundle);
    if (!b || !bundle) {
        free(b);
        free(bundle);
        fprintf(stderr, "oit: error: out of memory\n");
        return EXIT_RUNTIME;
    }
    int parsed = parse_bench_arguments(argc, argv, b);
    if (parsed >= 0) {
        free(b);
        free(bundle);
        return parsed;
    }
    oit_error err = {{0}};
    scene_list scenes = {0};
    int selected = 0;
    bench_output out = {0};
    session s;
    memset(&s, 0, sizeof s);
    s.backend = b->base.backend;
    s.debug = b->base.config.debug;
    bool needs_gl = false;
    for (int a = 0; a < b->algorithm_count; ++a)
        needs_gl |= b->algorithms[a].ops->uses_gl;

    /* every output, before anything is read or rendered (the bundle's below, with its scenes' names) */
    oit_status status = OIT_OK;
    if (b->csv_path && strcmp(b->csv_path, "-") != 0)
        status = check_output_path("--csv", b->csv_path, &err);
    if (status == OIT_OK && b->json_path && strcmp(b->json_path, "-") != 0)
        status = check_output_path("--json", b->json_path, &err);
    if (status == OIT_OK)
        status = bench_scenes(b, &scenes, &selected, &err);
    bench_bundle *use_bundle = b->bundle_path ? bundle : NULL;
    if (status == OIT_OK && use_bundle)
        status = bundle_open(b, &scenes, bundle, &err);
    if (status == OIT_OK)
        status = bench_output_open(b, &out, &err);
    /* the context before the first row: its renderer string goes into the header */
    if (status == OIT_OK && needs_gl)
        status = oit_find_shader_dir(program_path, s.shader_dir, sizeof s.shader_dir, &err);
    if (status == OIT_OK && needs_gl)
        status = oit_gl_context_create(s.backend, s.debug, &s.gl, &err);
    if (status == OIT_OK && use_bundle)
        bundle_driver(bundle, needs_gl);
    int failures = 0;
    if (status == OIT_OK) {
        bench_output_begin(&out, b, needs_gl, argc, argv);
        progress_state progress = {
            isatty(fileno(stderr)) != 0, 0, selected * b->size_count * b->algorithm_count, NULL, NULL, 0, 0};
        for (int k = 0; status == OIT_OK && !bench_output_failed(&out) && k < scenes.count; ++k) {
            const bench_scene *scene = &scenes.items[k];
            if (!scene_selected(b->scene_patterns, scene->name))
                continue;
            /* a model that does not load fails its rows; the other scenes go on */
            oit_error load_err = {{0}};
            oit_status load = session_set_model(&s, scene->options.model_path, &load_err);
            if (use_bundle)
                bundle_scene_begin(bundle, scene);
            for (int z = 0; status == OIT_OK && !bench_output_failed(&out) && z < b->size_count; ++z) {
                int failed = bench_scene_size(b, &s, scene, load, &load_err, b->widths[z], b->heights[z],
                                              &out, use_bundle, &progress);
                if (failed < 0)
                    status = oit_fail(&err, OIT_E_RUNTIME, "out of memory");
                else
                    failures += failed;
                if (status == OIT_OK && use_bundle && bundle->status != OIT_OK) {
                    status = bundle->status;
                    err = bundle->err;
                }
            }
            if (use_bundle)
                bundle_scene_end(bundle, load, &load_err);
        }
        bench_output_end(&out, failures);
    }
    if (status == OIT_OK && use_bundle)
        status = bundle_commit(bundle, b, needs_gl, argc, argv, failures, &err);
    oit_error close_err;
    oit_status close_status = bench_output_close(&out, status == OIT_OK, &close_err);
    if (status == OIT_OK && close_status != OIT_OK) {
        status = close_status;
        err = close_err;
    }
    bundle_close(bundle);
    session_close(&s);
    scene_list_free(&scenes);
    free(b);
    free(bundle);
    if (status != OIT_OK)
        return report(status, &err);
    if (failures) {
        fprintf(stderr, "oit: error: bench: %d run(s) failed; their rows carry the error\n", failures);
        return EXIT_RUNTIME;
    }
    return EXIT_OK;
}

/* ------------------------------------------------------------ measure */

/* The tasks of the source's measuring build (thesis appendix E.3). */
typedef struct measure_task {
    const char *name;
    const char *algorithm;
    const char *const timed[4]; /* stage-name prefixes whose medians make the task's time */
    int timed_count;
} measure_task;

static const measure_task measure_tasks[] = {
    {"linked-lists", "ll", {"clear", "fill", "sort", "compose"}, 4},
    {"ib-construction", "ib", {"clear", "fill", "sort", "neighbours"}, 4},
    {"diffusion", "ib", {"diffusion"}, 1},
    {"diffusion-gauss", "ib", {"diffusion", "blur"}, 2},
    {"distance-curvature", "ib", {"curvature_distance"}, 1},
};

static const char measure_help[] =
    "usage: oit measure [options] TASK COUNTER NAME PATH m00 .. m33 p00 .. p33 [VIEWPORT]\n"
    "The source's measuring command line (thesis appendix E.3): renders the model with the\n"
    "16 modelview and 16 projection numbers (each row by row) and appends one result line to the\n"
    "results file.\n"
    "  TASK      1 linked lists, 2 Illustration Buffer construction (fill, sort, neighbours),\n"
    "            3 one diffusion pass, 4 one diffusion pass + one Gaussian pass,\n"
    "            5 distance + curvature (8 neighbours)\n"
    "  COUNTER   the view's number (1 general, 2 longest lists), written with the name\n"
    "  NAME      the model's name in the results; PATH the model file\n"
    "  VIEWPORT  N (NxN) or WxH (default 600x600)\n"
    "options (before TASK):\n"
    "  --results FILE  the results file (default $OIT_MEASURE_RESULTS, else measure_task<TASK>.txt)\n"
    "  --frames N      measured frames, their median is reported (default 10)\n"
    "  --warmup N      unmeasured frames first (default 2)\n"
    "  --backend egl|osmesa\n"
    "result line, tab-separated (a '#' header when the file is new):\n"
    "  task name counter width height vertices triangles fragments max_list psi_percent\n"
    "  task_ms frame_ms fps stages\n"
    "task_ms is the median of the task's stages; frame_ms the median CPU frame time; fps 1000/frame_ms.\n";

int command_measure(int argc, char **argv)
{
    const char *results_path = getenv("OIT_MEASURE_RESULTS");
    long frames = BENCH_DEFAULT_FRAMES, warmup = BENCH_DEFAULT_WARMUP;
    oit_backend backend = OIT_BACKEND_EGL;
    int i = 0;
    for (; i < argc && strncmp(argv[i], "--", 2) == 0; ++i) {
        const char *flag = argv[i];
        bool has_value = i + 1 < argc;
        if (strcmp(flag, "--help") == 0) {
            fputs(measure_help, stdout);
            return EXIT_OK;
        } else if (strcmp(flag, "--results") == 0 && has_value) {
            results_path = argv[++i];
        } else if (strcmp(flag, "--frames") == 0 && has_value) {
            if (!parse_int(argv[++i], 1, MAX_FRAMES, &frames))
                return usage_error("measure: --frames must be a whole number in [1, 10000], got '%s'", argv[i]);
        } else if (strcmp(flag, "--warmup") == 0 && has_value) {
            if (!parse_int(argv[++i], 0, MAX_FRAMES, &warmup))
                return usage_error("measure: --warmup must be a whole number in [0, 10000], got '%s'", argv[i]);
        } else if (strcmp(flag, "--backend") == 0 && has_value) {
            ++i;
            if (strcmp(argv[i], "egl") == 0)
                backend = OIT_BACKEND_EGL;
            else if (strcmp(argv[i], "osmesa") == 0)
                backend = OIT_BACKEND_OSMESA;
            else
                return usage_error("measure: --backend must be egl or osmesa, got '%s'", argv[i]);
        } else {
            return usage_error("measure: unknown option or missing value '%s'", flag);
        }
    }
    int positional = argc - i;
    char **args = argv + i;
    if (positional != 36 && positional != 37) {
        fprintf(stderr,
                "oit: error: measure needs TASK COUNTER NAME PATH, 16 modelview and 16 projection numbers "
                "and an optional VIEWPORT (36 or 37 arguments), got %d (see oit measure --help)\n",
                positional);
        return EXIT_USAGE;
    }
    long task_number, counter;
    if (!parse_int(args[0], 1, 5, &task_number))
        return usage_error("measure: TASK must be 1 (linked lists), 2 (ib construction), 3 (diffusion), "
                           "4 (diffusion + Gaussian) or 5 (distance + curvature), got '%s'",
                           args[0]);
    if (!parse_int(args[1], 0, 1000000, &counter))
        return usage_error("measure: COUNTER must be a whole number >= 0, got '%s'", args[1]);
    const char *name = args[2];
    if (name[0] == '\0' || strpbrk(name, "\t\n\r"))
        return usage_error("measure: NAME must be non-empty and without tabs or line breaks, got '%s'", name);
    const char *model_path = args[3];
    oit_error err = {{0}};
    double rows[2][16];
    for (int k = 0; k < 32; ++k) {
        char text[128];
        snprintf(text, sizeof text, "%s", args[4 + k]);
        size_t length = strlen(text);
        if (length > 0 && text[length - 1] == ',') /* tolerate "1.0," as pasted from a matrix */
            text[length - 1] = '\0';
        if (!parse_double(text, &rows[k / 16][k % 16])) {
            fprintf(stderr, "oit: error: measure: %s element %d (row %d, column %d) is not a number: '%s'\n",
                    k < 16 ? "modelview" : "projection", k % 16, (k % 16) / 4, k % 4, args[4 + k]);
            return EXIT_USAGE;
        }
    }
    render_options o;
    render_options_defaults(&o);
    o.backend = backend;
    o.model_path = model_path;
    o.width = o.height = BENCH_DEFAULT_SIZE;
    if (positional == 37) {
        char size_text[64];
        const char *viewport = args[36];
        if (!strchr(viewport, 'x') && strlen(viewport) < 30) {
            snprintf(size_text, sizeof size_text, "%sx%s", viewport, viewport);
            viewport = size_text;
        }
        oit_status size_status = parse_size(viewport, &o.width, &o.height, &err);
        if (size_status != OIT_OK) {
            fprintf(stderr, "oit: error: measure: VIEWPORT must be N or WxH (1..%d per side), got '%s'\n",
                    MAX_IMAGE_SIDE, args[36]);
            return EXIT_USAGE;
        }
    }
    oit_status status = matrix_from_rows("measure: modelview", rows[0], o.modelview, &err);
    if (status == OIT_OK)
        status = matrix_from_rows("measure: projection", rows[1], o.projection, &err);
    if (status == OIT_OK)
        status = oit_matrices_validate(o.modelview, o.projection, &err);
    if (status != OIT_OK)
        return report(status, &err);
    o.has_modelview = o.has_projection = true;

    const measure_task *task = &measure_tasks[task_number - 1];
    o.algorithm = oit_algorithm_find(task->algorithm);
    switch (task_number) {
    case 3: /* one diffusion pass, no blur */
        o.modulation.mode = OIT_MODULATE_FIELDS;
        o.modulation.diffusion_iterations = 1;
        o.modulation.blur_iterations = -1;
        break;
    case 4: /* one diffusion pass and one Gaussian (blur) pass */
        o.modulation.mode = OIT_MODULATE_FIELDS;
        o.modulation.diffusion_iterations = 1;
        o.modulation.blur_iterations = 1;
        break;
    case 5: /* the thesis measured curvature with 8 neighbours */
        o.modulation.mode = OIT_MODULATE_DIST_CURV;
        o.modulation.curvature_neighbours = 8;
        break;
    default:
        break;
    }

    char default_results[64];
    if (!results_path || !results_path[0]) {
        snprintf(default_results, sizeof default_results, "measure_task%ld.txt", task_number);
        results_path = default_results;
    }
    /* before the model is read: a FIFO would block, a long name fail after the work */
    status = check_output_path("measure: results file", results_path, &err);
    if (status != OIT_OK)
        return report(status, &err);
    session s;
    status = session_open(&s, model_path, backend, false, &err);
    run_result *r = calloc(1, sizeof *r);
    if (status == OIT_OK && !r)
        status = oit_fail(&err, OIT_E_RUNTIME, "out of memory");
    if (status == OIT_OK)
        status = run_algorithm(&s, &o, (int)warmup, (int)frames, 0.0, r, NULL, NULL, NULL, &err);
    /* appended under an exclusive lock, in one write: concurrent runs keep
     * every line, and a failed write leaves the lines before (oit_atomic_file) */
    oit_atomic_file *results_file = NULL;
    if (status == OIT_OK)
        status = oit_atomic_file_open(results_path, "measure", OIT_ATOMIC_APPEND, &results_file, &err);
    if (status == OIT_OK) {
        FILE *results = oit_atomic_file_stream(results_file);
        const oit_stats *st = &r->last;
        double task_ms = stages_sum(r, task->timed, task->timed_count);
        double fps = r->cpu_ms.median > 0.0 ? 1000.0 / r->cpu_ms.median : 0.0;
        char stages[2048] = "";
        size_t used = 0;
        for (int j = 0; j < r->stage_count && used < sizeof stages; ++j)
            used += (size_t)snprintf(stages + used, sizeof stages - used, "%s%s=%.4f", j ? ";" : "",
                                     r->stages[j].name, r->stages[j].ms.median);
        if (oit_atomic_file_kept_bytes(results_file) == 0)
            fprintf(results, "# oit measure results (thesis appendix E.3); renderer: %s\n"
                             "# task\tname\tcounter\twidth\theight\tvertices\ttriangles\tfragments\tmax_list\t"
                             "psi_percent\ttask_ms\tframe_ms\tfps\tstages\n",
                    oit_gl_renderer_string());
        char line[4096];
        snprintf(line, sizeof line, "%ld\t%s\t%ld\t%d\t%d\t%u\t%u\t%lld\t%lld\t%.2f\t%.4f\t%.4f\t%.1f\t%s\n",
                 task_number, name, counter, o.width, o.height, s.model.vertex_count, s.model.triangle_count,
                 (long long)st->fragments, (long long)st->max_list, st->psi >= 0.0 ? 100.0 * st->psi : -1.0,
                 task_ms, r->cpu_ms.median, fps, stages);
        fputs(line, results);
        status = oit_atomic_file_commit(results_file, &err);
        results_file = NULL;
        if (status == OIT_OK)
            printf("%s %s %ld (%s) %dx%d: %.3f ms, frame %.3f ms, %lld fragments, longest list %lld -> %s\n",
                   task->name, name, counter, model_path, o.width, o.height, task_ms, r->cpu_ms.median,
                   (long long)st->fragments, (long long)st->max_list, results_path);
    }
    oit_atomic_file_abort(results_file, status, NULL, NULL);
    free(r);
    session_close(&s);
    return report(status, &err);
}
