/*
 * bench_output.c: the rows of `oit bench` as CSV and JSON, the files they
 * go to, and the progress lines (bench_output.h). Each row is written and
 * flushed as soon as it is measured: into FILE.tmp.XXXXXX beside FILE,
 * renamed over FILE when the run ends (oit_atomic_file), so the previous
 * FILE stays whole until then; a run that fails or is interrupted removes
 * the temporary.
 */
#define _GNU_SOURCE /* gmtime_r */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/utsname.h>
#include <time.h>

#include "bench_output.h"
#include "json_output.h"

static const char csv_header[] =
    "scene,model,view,algorithm,width,height,vertices,triangles,components,warmup,frames,"
    "cpu_ms_median,cpu_ms_min,cpu_ms_max,gpu_ms_median,gpu_ms_min,gpu_ms_max,memory_bytes,scene_bytes,"
    "fragments,max_list,mean_list,psi,layers,overflow_retries,bytes_per_fragment,ref_max_diff,"
    "ref_mean_diff,ref_over_tolerance_percent,error_rmse,error_psnr,error_ssim,error_max,error_share_over_2,"
    "error_flip,flicker,flicker_max,orbit_rmse_mean,stages,list_histogram,scene_histogram,error\n";
#define CSV_RUN_COLUMNS 32 /* warmup .. scene_histogram: empty in a failed run's row */

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

/* A histogram in one CSV field: the counts of bins 0, 1, ... joined by ';'
 * (no quoting, like stages), the trailing empty bins left out (a reader pads
 * with zeros to OIT_HISTOGRAM_BINS); nothing when there are no bins. */
static void csv_histogram(FILE *out, const uint64_t *counts, int bins)
{
    while (bins > 1 && counts[bins - 1] == 0)
        --bins;
    for (int b = 0; b < bins; ++b)
        fprintf(out, "%s%llu", b ? ";" : "", (unsigned long long)counts[b]);
}

void iso_time(char *out, size_t size)
{
    time_t now = time(NULL);
    struct tm utc;
    gmtime_r(&now, &utc);
    strftime(out, size, "%Y-%m-%dT%H:%M:%SZ", &utc);
}

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
        fprintf(f, ",%.9g,%d,%.9g,%.9g,", e->ssim, e->max, e->share_over_2, e->flip);
    } else {
        fputs(",,,,,,", f);
    }
    if (r->orbit_frames > 0)
        fprintf(f, "%.9g,%.9g,%.9g,", r->flicker, r->flicker_max, r->orbit_rmse_mean);
    else
        fputs(",,,", f);
    /* stages: name=median/min/max, separated by ';' */
    for (int j = 0; j < r->stage_count; ++j)
        fprintf(f, "%s%s=%.4f/%.4f/%.4f", j ? ";" : "", r->stages[j].name, r->stages[j].ms.median,
                r->stages[j].ms.min, r->stages[j].ms.max);
    fputc(',', f);
    csv_histogram(f, st->list_histogram, st->histogram_bins);
    fputc(',', f);
    csv_histogram(f, r->scene_histogram, r->scene_histogram_bins);
    fputs(",\n", f);
}

/* One row as a JSON object (--json's results, and the bundle's), with the
 * bundle's file names where files is not NULL. */
void write_json_row(FILE *f, const bench_scene *scene, const session *s,
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
    json_histogram(f, "list_histogram", st->list_histogram, st->histogram_bins);
    json_histogram(f, "scene_histogram", r->scene_histogram, r->scene_histogram_bins);
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

void write_row(bench_output *out, const bench_scene *scene, const session *s,
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

void progress_frame(void *data, int frame, int frames)
{
    const progress_state *p = data;
    if (p->tty)
        fprintf(stderr, "\rbench [%d/%d] %s %s %dx%d frame %d/%d\033[K", p->index, p->total, p->scene,
                p->algorithm, p->width, p->height, frame, frames);
}

void progress_done(const progress_state *p, const run_result *r)
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

/* Closes the outputs. The files are written beside their targets and renamed
 * over them here (oit_atomic_file), both or neither: when the run succeeded
 * (keep) and both were written whole; else they are dropped, leaving the
 * previous files as they were. A write that failed anywhere (a full disk) is
 * an error naming the file, not an exit 0 with a short file. */
oit_status bench_output_close(bench_output *out, bool keep, oit_error *err)
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
bool bench_output_failed(const bench_output *out)
{
    return (out->csv_file && oit_atomic_file_failed(out->csv_file)) ||
           (out->json_file && oit_atomic_file_failed(out->json_file)) ||
           (out->csv == stdout && ferror(stdout)) || (out->json == stdout && ferror(stdout));
}

oit_status bench_output_open(const bench_settings *b, bench_output *out, oit_error *err)
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
void bench_output_begin(bench_output *out, const bench_settings *b, bool has_gl, int argc, char **argv)
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

void bench_output_end(bench_output *out, int failures)
{
    if (!out->json)
        return;
    struct rusage usage;
    long max_rss_kb = getrusage(RUSAGE_SELF, &usage) == 0 ? usage.ru_maxrss : -1;
    fprintf(out->json, "\n  ], \"failures\": %d, \"max_rss_kb\": %ld}\n", failures, max_rss_kb);
}
