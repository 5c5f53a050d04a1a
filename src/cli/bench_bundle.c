/*
 * bench_bundle.c: `oit bench --bundle DIR` (bench_bundle.h): the bundle's
 * file names, checked before any work; its images; bundle.json with the
 * command, the commit, the machine, the driver, the parameters, the scenes
 * and the rows; and DIR replaced by the new bundle in one step.
 */
#define _GNU_SOURCE /* renameat2 (RENAME_EXCHANGE), open_memstream */
#include <ctype.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/utsname.h>
#include <unistd.h>

#include "bench_bundle.h"
#include "json_output.h"

/* The bundle's name of a scene or algorithm: letters, digits and '-' (the
 * rest become '-'), so that '_' and '.' separate the parts of a file name. */
static void bundle_part(char *out, size_t size, const char *text)
{
    size_t n = 0;
    for (const char *c = text; *c && n + 1 < size; ++c)
        out[n++] = (isalnum((unsigned char)*c) || *c == '-') ? *c : '-';
    out[n] = '\0';
}

/* A run's file: SCENE_ALGORITHM_WxH followed by suffix; the length of the whole name. */
static int run_file_name(char *out, size_t size, const char *scene, const char *algorithm, int width, int height,
                         const char *suffix)
{
    char scene_part[256], algorithm_part[64];
    bundle_part(scene_part, sizeof scene_part, scene);
    bundle_part(algorithm_part, sizeof algorithm_part, algorithm);
    return snprintf(out, size, "%s_%s_%dx%d%s", scene_part, algorithm_part, width, height, suffix);
}

/* The longest name a bundle file gets: SCENE_ALGORITHM_WxH.error.png. */
static size_t bundle_longest_name(const bench_settings *b, const scene_list *scenes, char *longest, size_t size)
{
    size_t most = 0;
    char name[512];
    for (int i = 0; i < scenes->count; ++i) {
        if (!scene_selected(b->scene_patterns, scenes->items[i].name))
            continue;
        for (int a = 0; a < b->algorithm_count; ++a)
            for (int z = 0; z < b->size_count; ++z) {
                int n = run_file_name(name, sizeof name, scenes->items[i].name, b->algorithms[a].label,
                                      b->widths[z], b->heights[z], ".error.png");
                if (n > 0 && (size_t)n > most) {
                    most = (size_t)n;
                    snprintf(longest, size, "%s", name);
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
    bool replaces = false;
    unsigned mode = 0;
    status = oit_output_folder_check(bundle->path, "--bundle", path, "bundle", "bundle.json", &replaces, &mode, err);
    bundle->replaces = replaces;
    bundle->mode = mode;
    return status;
}

oit_status bundle_open(const bench_settings *b, const scene_list *scenes, bench_bundle *bundle,
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

void bundle_driver(bench_bundle *bundle, bool has_gl)
{
    snprintf(bundle->renderer, sizeof bundle->renderer, "%s", has_gl ? oit_gl_renderer_string() : "");
    snprintf(bundle->gl_version, sizeof bundle->gl_version, "%s", has_gl ? oit_gl_version_string() : "");
    snprintf(bundle->gl_vendor, sizeof bundle->gl_vendor, "%s", has_gl ? oit_gl_vendor_string() : "");
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

void bundle_reference(bench_bundle *bundle, const bench_scene *scene, int width, int height,
                      const oit_image *reference, row_files *files)
{
    char scene_part[256];
    bundle_part(scene_part, sizeof scene_part, scene->name);
    snprintf(files->reference, sizeof files->reference, "%s_%dx%d.reference.png", scene_part, width, height);
    bundle_png(bundle, files->reference, reference);
}

void bundle_run_images(bench_bundle *bundle, const bench_scene *scene, const bench_algorithm *algorithm,
                       int width, int height, const oit_image *image, const oit_image *reference,
                       row_files *files)
{
    run_file_name(files->image, sizeof files->image, scene->name, algorithm->label, width, height, ".png");
    bundle_png(bundle, files->image, image);
    files->error_map[0] = '\0';
    oit_image map = {0};
    oit_error map_err;
    if (reference && oit_image_error_map(image, reference, true, &map, &map_err) == OIT_OK) {
        run_file_name(files->error_map, sizeof files->error_map, scene->name, algorithm->label, width, height,
                      ".error.png");
        bundle_png(bundle, files->error_map, &map);
    }
    oit_image_free(&map);
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
void bundle_scene_begin(bench_bundle *bundle, const bench_scene *scene)
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
        o->alpha, oit_setting_word(OIT_SETTING_SHADING, o->shading), o->background[0], o->background[1],
        o->background[2], oit_setting_word(OIT_SETTING_BACKEND, o->backend),
        (unsigned long long)o->config.max_memory_bytes, oit_setting_word(OIT_SETTING_SORT, o->config.ll_sort),
        o->config.max_layers, o->config.layers, oit_setting_word(OIT_SETTING_MOMENTS, o->config.moments),
        oit_setting_word(OIT_SETTING_MODULATION, o->modulation.mode),
        o->orbit[0], o->orbit[1], o->has_modelview && o->has_projection ? "true" : "false");
    fprintf(f, ", \"cameras\": [");
    bundle->camera_count = 0;
}

void bundle_camera(bench_bundle *bundle, const oit_frame_settings *frame)
{
    FILE *f = bundle->scenes;
    fprintf(f, "%s{\"width\": %d, \"height\": %d, \"modelview\": ", bundle->camera_count++ ? ", " : "",
            frame->width, frame->height);
    json_matrix_rows(f, frame->modelview);
    fprintf(f, ", \"projection\": ");
    json_matrix_rows(f, frame->projection);
    fputc('}', f);
}

void bundle_scene_end(bench_bundle *bundle, oit_status load, const oit_error *load_err)
{
    fputc(']', bundle->scenes);
    if (load != OIT_OK) {
        fprintf(bundle->scenes, ", \"error\": ");
        json_string(bundle->scenes, load_err->message);
    }
    fputc('}', bundle->scenes);
}

void bundle_row(bench_bundle *bundle, const bench_scene *scene, const session *s,
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
oit_status bundle_commit(bench_bundle *bundle, const bench_settings *b, bool has_gl, int argc,
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
            f, ", \"algorithm\": \"%s\", \"exact\": %s, \"sort\": %s%s%s, \"layers\": %d, \"moments\": %s%s%s}",
            algorithm->ops->name, algorithm->ops->exact ? "true" : "false", algorithm->sort >= 0 ? "\"" : "",
            algorithm->sort >= 0 ? oit_setting_word(OIT_SETTING_SORT, algorithm->sort) : "null",
            algorithm->sort >= 0 ? "\"" : "", algorithm->layers, algorithm->moments ? "\"" : "",
            algorithm->moments ? oit_setting_word(OIT_SETTING_MOMENTS, algorithm->moments) : "null",
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
void bundle_close(bench_bundle *bundle)
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

