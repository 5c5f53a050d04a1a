/*
 * measure.c: `oit measure`, the source's measuring command line (thesis
 * appendix E.3): TASK COUNTER NAME PATH m00..m33 p00..p33 [VIEWPORT], one
 * result line appended to a results file per run (measure.h).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench.h" /* parse_size_or_side */
#include "bench_run.h"
#include "measure.h"

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
        oit_status size_status = parse_size_or_side(args[36], &o.width, &o.height, &err);
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
