/*
 * bench.c: `oit bench` runs scenes x algorithms x sizes in one process: one
 * GL context, each model loaded and uploaded once, each algorithm created
 * once per scene and size, warm-up frames, then N measured frames whose
 * figures are reported as median, minimum and maximum (bench_run.c), one row
 * per run in CSV and/or JSON (bench_output.c) and, with --bundle, a result
 * bundle (bench_bundle.c). The scenes come from a scene list or --model
 * (bench_scenes.c).
 */
#define _GNU_SOURCE /* strtok_r */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "bench.h"
#include "bench_bundle.h"
#include "bench_output.h"
#include "bench_run.h"
#include "bench_scenes.h"

#define BENCH_DEFAULT_REFERENCE_PIXELS (256 * 256)
#define BENCH_DEFAULT_TOLERANCE 2 /* the exact algorithms' tolerance in the tests */
#define BENCH_ORBIT_MIN 2
#define BENCH_ORBIT_MAX 3600
#define BENCH_DEFAULT_ORBIT_STEP 0.5 /* degrees of azimuth per frame of --orbit-sequence */
/* --orbit-sequence keeps the reference's frames of a scene and size for the
 * next algorithms when they fit in this many bytes (else renders them again) */
#define BENCH_ORBIT_CACHE_BYTES (256ull << 20)

/* ------------------------------------------------------- the command line */

/* What an algorithm's parameter may be, for messages. */
static const char *parameter_kind(const oit_algorithm_ops *ops)
{
    if (oit_algorithm_reads(ops, OIT_OPTION_SAMPLES))
        return "samples 1, 4, 8 or 16";
    if (oit_algorithm_reads(ops, OIT_OPTION_WAVELET_RANK))
        return "a rank R";
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
    int sort = -1;
    a->sort = -1;
    if (strncmp(name, "ll-", 3) == 0 && oit_setting_value(OIT_SETTING_SORT, name + 3, strlen(name + 3), &sort)) {
        a->ops = oit_algorithm_find("ll");
        a->sort = sort;
    } else {
        a->ops = oit_algorithm_find(name);
    }
    if (!a->ops)
        return oit_fail(err, OIT_E_INPUT,
                        "--algorithms: unknown algorithm '%s' (oit algorithms lists them; also ll-insertion, ll-array, ll-bma, ll-merge)",
                        name);
    if (!parameter)
        return OIT_OK;
    if (!*parameter)
        return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': no parameter after the colon", a->label);
    bool numeric = strspn(parameter, "+-0123456789") == strlen(parameter);
    int moments = -1;
    if (!oit_setting_value(OIT_SETTING_MOMENTS, parameter, strlen(parameter), &moments))
        moments = -1;
    const oit_algorithm_ops *ops = a->ops;
    if (numeric && oit_algorithm_reads(ops, OIT_OPTION_SAMPLES)) {
        long samples;
        if (!parse_int(parameter, 1, 16, &samples) || (samples != 1 && samples != 4 && samples != 8 && samples != 16))
            return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': samples must be 1, 4, 8 or 16", a->label);
        a->samples = (int)samples;
    } else if (numeric && oit_algorithm_reads(ops, OIT_OPTION_LAYERS)) {
        long layers;
        if (!parse_int(parameter, 1, OIT_LAYERS_MAX, &layers))
            return oit_fail(err, OIT_E_INPUT,
                            "--algorithms: '%s': layers must be a whole number from 1 to %d", a->label,
                            OIT_LAYERS_MAX);
        a->layers = (int)layers;
    } else if (numeric && oit_algorithm_reads(ops, OIT_OPTION_WAVELET_RANK)) {
        long rank;
        if (!parse_int(parameter, 1, OIT_WAVELET_RANK_MAX, &rank))
            return oit_fail(err, OIT_E_INPUT, "--algorithms: '%s': the wavelet rank must be a whole number from 1 to %d",
                            a->label, OIT_WAVELET_RANK_MAX);
        a->wavelet_rank = (int)rank;
    } else if (moments >= 0 && oit_algorithm_reads(ops, OIT_OPTION_MOMENTS)) {
        a->moments = (oit_moments)moments;
    } else if (oit_algorithm_reads(ops, OIT_OPTION_LAYERS) || oit_algorithm_reads(ops, OIT_OPTION_MOMENTS) ||
               oit_algorithm_reads(ops, OIT_OPTION_SAMPLES) ||
               oit_algorithm_reads(ops, OIT_OPTION_WAVELET_RANK)) {
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

oit_status parse_size_or_side(const char *text, int *width, int *height, oit_error *err)
{
    char square[64];
    if (!strchr(text, 'x') && strlen(text) < 30) {
        snprintf(square, sizeof square, "%sx%s", text, text);
        text = square;
    }
    return parse_size(text, width, height, err);
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
        oit_status status = parse_size_or_side(item, &widths[*count], &heights[*count], err);
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

static const char bench_help[] =
    "usage: oit bench (--scene-list FILE | --model PATH [--name NAME]) [options] [render options]\n"
    "Scenes x algorithms x sizes in one process: warm-up frames, then N measured frames;\n"
    "per-stage and frame times (median, min, max), memory, fragments, longest list, Psi, the\n"
    "list-length histograms (the algorithm's, and the scene's from the reference) and the\n"
    "difference from the reference, one row per run as CSV and/or JSON.\n"
    "  --scene-list FILE      one scene per line: NAME MODEL [render options such as --orbit AZ,EL or\n"
    "                         --modelview/--projection]; '#' comments (bat/setup.py writes one)\n"
    "  --model PATH           a single scene (named --name, default the file name)\n"
    "  --scenes LIST          only these scenes: comma-separated names or patterns (engine*)\n"
    "  --algorithms LIST      default blend,dp,ddp,ll,ib,wboit; also reference and ll-array;\n"
    "                         NAME:K sets the layers of kbuffer, hybrid, mlab (kbuffer:16),\n"
    "                         NAME:MOMENTS the moments of mboit (mboit:power6), NAME:N the\n"
    "                         samples of stochastic (stochastic:16), NAME:R the rank of wavelet,\n"
    "                         1..3 (wavelet:2)\n"
    "  --sizes LIST           WxH or N (NxN), comma-separated (default 600x600)\n"
    "  --frames N             measured frames per run (default 10)\n"
    "  --warmup N             frames rendered first and not measured (default 2)\n"
    "  --time-budget SECONDS  stop measuring a run after this long, once it has 3 frames (default: none)\n"
    "  --csv FILE             write the CSV there (default: stdout unless --json is given)\n"
    "  --json FILE            write the JSON there ('-' for stdout)\n"
    "  --reference-max-pixels N  compare with the CPU reference where width*height <= N\n"
    "                         (default 65536; 0: never); also the rows' scene_histogram\n"
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

/* -------------------------------------------------------------- the runs */

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
    int scene_bins = 0; /* the reference frame's list-length histogram: every row's scene_histogram */
    uint64_t scene_histogram[OIT_HISTOGRAM_BINS];
    if (load == OIT_OK && b->reference_pixels > 0 && (long)width * height <= b->reference_pixels) {
        render_options ro = o;
        ro.algorithm = oit_algorithm_find("reference");
        run_result *rr = calloc(1, sizeof *rr);
        oit_error ref_err = {{0}};
        if (rr)
            has_reference =
                run_algorithm(s, &ro, 0, 1, 0.0, rr, &reference_image, NULL, NULL, &ref_err) == OIT_OK;
        if (has_reference) {
            scene_bins = rr->last.histogram_bins;
            memcpy(scene_histogram, rr->last.list_histogram, sizeof scene_histogram);
        }
        free(rr);
        if (!has_reference && !b->quiet)
            fprintf(stderr, "bench: %s %dx%d: no reference image: %s\n", scene->name, width, height,
                    rr ? ref_err.message : "out of memory");
        if (has_reference && bundle)
            bundle_reference(bundle, scene, width, height, &reference_image, &files);
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
        o.config.ll_sort = algorithm->sort >= 0 ? (oit_ll_sort)algorithm->sort : scene->options.config.ll_sort;
        o.config.layers = algorithm->layers ? algorithm->layers : scene->options.config.layers;
        o.config.moments = algorithm->moments ? algorithm->moments : scene->options.config.moments;
        o.samples = algorithm->samples ? algorithm->samples : scene->options.samples;
        o.config.wavelet_rank = algorithm->wavelet_rank ? algorithm->wavelet_rank : scene->options.config.wavelet_rank;
        run_result *r = calloc(1, sizeof *r);
        if (!r) {
            failures = -1;
            break;
        }
        r->scene_histogram_bins = scene_bins;
        if (scene_bins > 0)
            memcpy(r->scene_histogram, scene_histogram, sizeof r->scene_histogram);
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
            /* An algorithm reading --samples takes them as its own samples at the pixel
             * centre (stochastic): with the scene anti-aliased, its reference is the
             * reference at the pixel centre, rendered for it alone, and its orbit does
             * not share the scene's cached reference frames. */
            bool own_samples = oit_algorithm_reads(o.algorithm, OIT_OPTION_SAMPLES) && scene->options.samples > 1;
            oit_image centre_reference = {0};
            bool has_centre_reference = false;
            if (run == OIT_OK && has_reference && own_samples) {
                render_options ro = o;
                ro.algorithm = oit_algorithm_find("reference");
                ro.samples = 0;
                run_result *rr = calloc(1, sizeof *rr);
                oit_error ref_err = {{0}};
                has_centre_reference =
                    rr && run_algorithm(s, &ro, 0, 1, 0.0, rr, &centre_reference, NULL, NULL, &ref_err) == OIT_OK;
                free(rr);
            }
            const oit_image *row_reference = own_samples ? &centre_reference : &reference_image;
            if (run == OIT_OK && has_reference && (!own_samples || has_centre_reference)) {
                oit_error compare_err;
                r->has_reference_diff = oit_image_compare(&image, row_reference, (int)b->tolerance,
                                                          &r->diff, &compare_err) == OIT_OK;
                r->has_error = oit_image_error_compute(&image, row_reference, &r->error_figures,
                                                       &compare_err) == OIT_OK;
            }
            oit_image_free(&centre_reference);
            if (run == OIT_OK && bundle) {
                row = &files;
                bundle_run_images(bundle, scene, algorithm, width, height, &image,
                                  has_reference ? &reference_image : NULL, &files);
            }
            oit_image_free(&image);
            if (run == OIT_OK && b->orbit_frames > 0)
                run = run_orbit(s, &o, (int)b->orbit_frames, b->orbit_step, own_samples ? NULL : orbit_references,
                                r, &run_err);
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
            s.import = scene->options.import; /* its --tessellation */
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
