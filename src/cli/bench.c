/*
 * bench.c: `oit bench` and `oit measure`.
 *
 * oit bench runs scenes x algorithms x sizes in one process: one GL context,
 * each model loaded and uploaded once, each algorithm created once per scene
 * and size, warm-up frames, then N measured frames whose figures are reported
 * as median, minimum and maximum. One row per run goes to CSV and/or JSON as
 * soon as it is measured: into FILE.tmp.XXXXXX beside FILE, renamed over FILE
 * when the run ends (oit_atomic_file), so a long run that is interrupted
 * keeps its rows there and the previous FILE stays whole.
 *
 * oit measure is the source's measuring command line (thesis appendix E.3):
 * TASK COUNTER NAME PATH m00..m33 p00..p33 [VIEWPORT], one result line
 * appended to a results file per run.
 */
#define _XOPEN_SOURCE 700 /* strtok_r, strdup, fnmatch */
#include <errno.h>
#include <fnmatch.h>
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
        if (t >= 2 && used < sizeof view)
            used += (size_t)snprintf(view + used, sizeof view - used, "%s%s", t > 2 ? " " : "", owned);
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

/* A scene list: one scene per line, NAME MODEL [render options], words
 * separated by blanks; '#' starts a comment. */
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
        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *tokens[BENCH_MAX_TOKENS];
        int count = 0;
        char *save = NULL;
        for (char *token = strtok_r(line, " \t\r\n", &save); token;
             token = strtok_r(NULL, " \t\r\n", &save)) {
            if (count == BENCH_MAX_TOKENS) {
                status = oit_fail(err, OIT_E_INPUT, "%s: more than %d words on the line", where,
                                  BENCH_MAX_TOKENS);
                break;
            }
            tokens[count++] = token;
        }
        if (status != OIT_OK || count == 0)
            continue;
        status = scene_add(list, base, count, tokens, where, err);
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
 * ("ll-array" is ll --sort array, as the thesis's table 5.3 compares). */
typedef struct bench_algorithm {
    char label[32];
    const oit_algorithm_ops *ops;
    bool sort_array;
} bench_algorithm;

static oit_status parse_algorithms(const char *text, bench_algorithm *out, int *count, oit_error *err)
{
    char buffer[1024];
    if (strlen(text) >= sizeof buffer)
        return oit_fail(err, OIT_E_INPUT, "--algorithms: list too long");
    strcpy(buffer, text);
    *count = 0;
    char *save = NULL;
    for (char *name = strtok_r(buffer, ",", &save); name; name = strtok_r(NULL, ",", &save)) {
        if (*count == BENCH_MAX_ALGORITHMS)
            return oit_fail(err, OIT_E_INPUT, "--algorithms: at most %d", BENCH_MAX_ALGORITHMS);
        bench_algorithm *a = &out[*count];
        memset(a, 0, sizeof *a);
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
        snprintf(a->label, sizeof a->label, "%s", name);
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
        status = ops->render(alg, setup.scene, &setup.frame, err);
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

/* ------------------------------------------------------------- output */

static const char csv_header[] =
    "scene,model,view,algorithm,width,height,vertices,triangles,components,warmup,frames,"
    "cpu_ms_median,cpu_ms_min,cpu_ms_max,gpu_ms_median,gpu_ms_min,gpu_ms_max,memory_bytes,scene_bytes,"
    "fragments,max_list,mean_list,psi,layers,overflow_retries,bytes_per_fragment,ref_max_diff,"
    "ref_mean_diff,ref_over_tolerance_percent,stages,error\n";

typedef struct bench_output {
    FILE *csv; /* stdout, or the stream of csv_file */
    FILE *json;
    oit_atomic_file *csv_file, *json_file; /* NULL for stdout */
    int json_rows;
    int tolerance;
} bench_output;

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

static void write_row(bench_output *out, const bench_scene *scene, const session *s, const char *label,
                      int width, int height, const run_result *r)
{
    const oit_stats *st = &r->last;
    const oit_model *m = &s->model;
    if (r->ok) {
        char what[OIT_NAME_SIZE * 2];
        snprintf(what, sizeof what, "%s, %s", scene->name, label);
        warn_if_truncated(what, &scene->options.config, st);
    }
    if (out->csv) {
        FILE *f = out->csv;
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
            for (int column = 0; column < 21; ++column) /* warmup .. stages are empty */
                fputc(',', f);
            fputc(',', f);
            csv_field(f, r->error);
            fputc('\n', f);
        } else {
            char fragments[32], max_list[32], mean_list[32], psi[32], layers[32], retries[32], bpf[32];
            format_optional_int(fragments, sizeof fragments, st->fragments);
            format_optional_int(max_list, sizeof max_list, st->max_list);
            format_optional_double(mean_list, sizeof mean_list, st->mean_list);
            format_optional_double(psi, sizeof psi, st->psi);
            format_optional_int(layers, sizeof layers, st->layers);
            format_optional_int(retries, sizeof retries, st->overflow_retries);
            format_optional_double(bpf, sizeof bpf, st->bytes_per_fragment);
            fprintf(f, ",%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%llu,%llu,%s,%s,%s,%s,%s,%s,%s,", r->warmup,
                    r->frames, r->cpu_ms.median, r->cpu_ms.min, r->cpu_ms.max, r->gpu_ms.median,
                    r->gpu_ms.min, r->gpu_ms.max, (unsigned long long)r->memory_max,
                    (unsigned long long)s->gpu_scene.gpu_bytes, fragments, max_list, mean_list, psi,
                    layers, retries, bpf);
            if (r->has_reference_diff)
                fprintf(f, "%d,%.6f,%.6f,", r->diff.max_channel_diff, r->diff.mean_diff,
                        100.0 * r->diff.share_over_tolerance);
            else
                fputs(",,,", f);
            /* stages: name=median/min/max, separated by ';' */
            for (int j = 0; j < r->stage_count; ++j)
                fprintf(f, "%s%s=%.4f/%.4f/%.4f", j ? ";" : "", r->stages[j].name, r->stages[j].ms.median,
                        r->stages[j].ms.min, r->stages[j].ms.max);
            fputs(",\n", f);
        }
        fflush(f);
    }
    if (out->json) {
        FILE *f = out->json;
        fprintf(f, "%s\n    {\"scene\": ", out->json_rows++ ? "," : "");
        json_string(f, scene->name);
        fprintf(f, ", \"model\": ");
        json_string(f, scene->options.model_path);
        fprintf(f, ", \"view\": ");
        json_string(f, scene->view);
        fprintf(f, ", \"algorithm\": \"%s\", \"width\": %d, \"height\": %d", label, width, height);
        if (s->model_loaded) {
            fprintf(f, ", \"vertices\": %u, \"triangles\": %u, \"components\": %u", m->vertex_count,
                    m->triangle_count, m->component_count);
            json_warnings(f, m);
        }
        if (!r->ok) {
            fprintf(f, ", \"error\": ");
            json_string(f, r->error);
            fputc('}', f);
        } else {
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
            if (st->fragments >= 0)
                fprintf(f, ", \"fragments\": %lld", (long long)st->fragments);
            if (st->max_list >= 0)
                fprintf(f, ", \"max_list\": %lld", (long long)st->max_list);
            if (st->mean_list >= 0.0)
                fprintf(f, ", \"mean_list\": %.6g", st->mean_list);
            if (st->psi >= 0.0)
                fprintf(f, ", \"psi\": %.6g", st->psi);
            if (st->layers >= 0)
                fprintf(f, ", \"layers\": %lld", (long long)st->layers);
            if (st->overflow_retries >= 0)
                fprintf(f, ", \"overflow_retries\": %lld", (long long)st->overflow_retries);
            fprintf(f, ", \"truncated\": %s", st->truncated ? "true" : "false");
            if (st->bytes_per_fragment >= 0.0)
                fprintf(f, ", \"bytes_per_fragment\": %.6g", st->bytes_per_fragment);
            if (r->has_reference_diff)
                fprintf(f,
                        ", \"reference\": {\"max_channel_diff\": %d, \"mean_diff\": %.6f, "
                        "\"over_tolerance_percent\": %.6f, \"tolerance\": %d}",
                        r->diff.max_channel_diff, r->diff.mean_diff, 100.0 * r->diff.share_over_tolerance,
                        out->tolerance);
            fputc('}', f);
        }
        fflush(f);
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
    "  --algorithms LIST      default blend,dp,ddp,ll,ib,wboit; also reference and ll-array\n"
    "  --sizes LIST           WxH or N (NxN), comma-separated (default 600x600)\n"
    "  --frames N             measured frames per run (default 10)\n"
    "  --warmup N             frames rendered first and not measured (default 2)\n"
    "  --time-budget SECONDS  stop measuring a run after this long, once it has 3 frames (default: none)\n"
    "  --csv FILE             write the CSV there (default: stdout unless --json is given)\n"
    "  --json FILE            write the JSON there ('-' for stdout)\n"
    "  --reference-max-pixels N  compare with the CPU reference where width*height <= N\n"
    "                         (default 65536; 0: never)\n"
    "  --tolerance T          channel difference counted as a mismatch (default 2)\n"
    "  --quiet                no progress lines on stderr\n"
    "Render options (--backend, --alpha, --shading, --max-memory, ...) apply to every scene; a scene\n"
    "line's own options override them. A run that fails is a row with an error; the exit status is\n"
    "then 3 after every other run has finished.\n";

/* What the bench's command line asks for. */
typedef struct bench_settings {
    render_options base; /* render options for every scene */
    const char *scene_list_path, *single_model, *single_name, *scene_patterns;
    const char *csv_path, *json_path;
    bench_algorithm algorithms[BENCH_MAX_ALGORITHMS];
    int algorithm_count;
    int widths[BENCH_MAX_SIZES], heights[BENCH_MAX_SIZES], size_count;
    long frames, warmup, reference_pixels, tolerance;
    double budget_ms;
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
        } else if (strcmp(flag, "--out") == 0 || strcmp(flag, "--algorithm") == 0 ||
                   strcmp(flag, "--size") == 0) {
            return usage_error("bench: %s is not a bench option: use --algorithms, --sizes or a scene list", flag);
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
    } else if (b->csv_path || !b->json_path) {
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
    fprintf(f, ", \"warmup\": %ld, \"frames\": %ld, \"time_budget_s\": %g, \"results\": [", b->warmup, b->frames,
            b->budget_ms / 1000.0);
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

/* Every algorithm on one scene at one size, after the reference image where
 * the size allows; one row each. Returns the number of failed runs, or -1
 * when out of memory. */
static int bench_scene_size(const bench_settings *b, session *s, const bench_scene *scene, oit_status load,
                            const oit_error *load_err, int width, int height, bench_output *out,
                            progress_state *progress)
{
    render_options o = scene->options;
    o.width = width;
    o.height = height;
    oit_image reference_image = {0};
    bool has_reference = false;
    if (load == OIT_OK && b->reference_pixels > 0 && (long)width * height <= b->reference_pixels) {
        render_options ro = o;
        ro.algorithm = oit_algorithm_find("reference");
        run_result *rr = calloc(1, sizeof *rr);
        oit_error ref_err = {{0}};
        if (rr)
            has_reference = run_algorithm(s, &ro, 0, 1, 0.0, rr, &reference_image, NULL, NULL, &ref_err) == OIT_OK;
        free(rr);
        if (!has_reference && !b->quiet)
            fprintf(stderr, "bench: %s %dx%d: no reference image: %s\n", scene->name, width, height,
                    rr ? ref_err.message : "out of memory");
    }
    int failures = 0;
    for (int a = 0; a < b->algorithm_count; ++a) {
        const bench_algorithm *algorithm = &b->algorithms[a];
        o.algorithm = algorithm->ops;
        o.config.ll_sort = algorithm->sort_array ? OIT_LL_SORT_LOCAL_ARRAY : scene->options.config.ll_sort;
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
        if (load == OIT_OK) {
            /* the CPU reference is measured on one frame: it is the oracle, not a contender */
            bool cpu = !o.algorithm->uses_gl;
            oit_image image = {0};
            run = run_algorithm(s, &o, cpu ? 0 : (int)b->warmup, cpu ? 1 : (int)b->frames, b->budget_ms, r,
                                has_reference ? &image : NULL, b->quiet ? NULL : progress_frame, progress, &run_err);
            if (run == OIT_OK && has_reference) {
                oit_error compare_err;
                r->has_reference_diff = oit_image_compare(&image, &reference_image, (int)b->tolerance, &r->diff,
                                                          &compare_err) == OIT_OK;
            }
            oit_image_free(&image);
        }
        if (run != OIT_OK) {
            r->ok = false;
            snprintf(r->error, sizeof r->error, "%s", run_err.message);
            ++failures;
        }
        write_row(out, scene, s, algorithm->label, width, height, r);
        if (!b->quiet)
            progress_done(progress, r);
        free(r);
    }
    oit_image_free(&reference_image);
    return failures;
}

int command_bench(int argc, char **argv)
{
    bench_settings *b = calloc(1, sizeof *b);
    if (!b) {
        fprintf(stderr, "oit: error: out of memory\n");
        return EXIT_RUNTIME;
    }
    int parsed = parse_bench_arguments(argc, argv, b);
    if (parsed >= 0) {
        free(b);
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

    oit_status status = bench_scenes(b, &scenes, &selected, &err);
    if (status == OIT_OK)
        status = bench_output_open(b, &out, &err);
    /* the context before the first row: its renderer string goes into the header */
    if (status == OIT_OK && needs_gl)
        status = oit_find_shader_dir(program_path, s.shader_dir, sizeof s.shader_dir, &err);
    if (status == OIT_OK && needs_gl)
        status = oit_gl_context_create(s.backend, s.debug, &s.gl, &err);
    int failures = 0;
    if (status == OIT_OK) {
        bench_output_begin(&out, b, needs_gl, argc, argv);
        progress_state progress = {isatty(fileno(stderr)) != 0, 0,
                                   selected * b->size_count * b->algorithm_count, NULL, NULL, 0, 0};
        for (int k = 0; status == OIT_OK && !bench_output_failed(&out) && k < scenes.count; ++k) {
            const bench_scene *scene = &scenes.items[k];
            if (!scene_selected(b->scene_patterns, scene->name))
                continue;
            /* a model that does not load fails its rows; the other scenes go on */
            oit_error load_err = {{0}};
            oit_status load = session_set_model(&s, scene->options.model_path, &load_err);
            for (int z = 0; status == OIT_OK && !bench_output_failed(&out) && z < b->size_count; ++z) {
                int failed = bench_scene_size(b, &s, scene, load, &load_err, b->widths[z], b->heights[z], &out,
                                              &progress);
                if (failed < 0)
                    status = oit_fail(&err, OIT_E_RUNTIME, "out of memory");
                else
                    failures += failed;
            }
        }
        bench_output_end(&out, failures);
    }
    oit_error close_err;
    oit_status close_status = bench_output_close(&out, status == OIT_OK, &close_err);
    if (status == OIT_OK && close_status != OIT_OK) {
        status = close_status;
        err = close_err;
    }
    session_close(&s);
    scene_list_free(&scenes);
    free(b);
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
    session s;
    status = session_open(&s, model_path, backend, false, &err);
    run_result *r = calloc(1, sizeof *r);
    if (status == OIT_OK && !r)
        status = oit_fail(&err, OIT_E_RUNTIME, "out of memory");
    if (status == OIT_OK)
        status = run_algorithm(&s, &o, (int)warmup, (int)frames, 0.0, r, NULL, NULL, NULL, &err);
    /* appended atomically: the previous lines and the new one are written
     * beside the file and renamed over it (oit_atomic_file) */
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
