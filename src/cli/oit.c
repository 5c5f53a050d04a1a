/*
 * oit.c: the headless command-line tool.
 *
 *   oit render     render a model with one algorithm, write a PNG, report timings
 *   oit compare    compare two PNG images
 *   oit info       counts, bounds and components of a model
 *   oit gen        write a procedural test scene (OBJ + MTL)
 *   oit demo       render the bundled model with every algorithm, print a table
 *   oit bench      scenes x algorithms x sizes, timings and statistics as CSV/JSON (bench.c)
 *   oit measure    the source's measuring command line, one result line per run (measure.c)
 *   oit algorithms list the algorithms
 *   oit pick       which part adds most to one pixel's colour (pick_command.c)
 *
 * Exit status: 0 success, 1 comparison outside bounds, 2 bad usage or input,
 * 3 GL or runtime failure. Every error is one line on stderr.
 */
#define _XOPEN_SOURCE 700 /* realpath, sigaction */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench.h"
#include "json_output.h"
#include "local_options.h"
#include "measure.h"
#include "modulation_options.h"
#include "pick_command.h"
#include "render_session.h"
#include "session_file.h"
#include "turntable_command.h"

/* --------------------------------------------------------------- JSON */

static void print_render_json(FILE *out, const render_options *o, const session *s,
                              const render_result *r, const oit_image_error *error)
{
    const oit_stats *st = &r->stats;
    fprintf(out, "{\"algorithm\": ");
    json_string(out, o->algorithm->name);
    fprintf(out, ", \"model\": ");
    json_string(out, o->model_path);
    fprintf(out, ", \"backend\": \"%s\"", o->backend == OIT_BACKEND_EGL ? "egl" : "osmesa");
    if (o->algorithm->uses_gl) {
        fprintf(out, ", \"renderer\": ");
        json_string(out, oit_gl_renderer_string());
        fprintf(out, ", \"shaders\": ");
        json_string(out, s->shader_dir);
    }
    fprintf(out, ", \"width\": %d, \"height\": %d, \"frames\": %d", o->width, o->height, o->frames);
    if (oit_algorithm_reads(o->algorithm, OIT_OPTION_SAMPLES)) {
        /* stochastic: its own samples per pixel, all at the pixel centre */
        fprintf(out, ", \"samples\": %d, \"sample_positions\": \"centre\"",
                o->samples > 0 ? o->samples : OIT_STOCHASTIC_SAMPLES_DEFAULT);
        fprintf(out, ", \"seed\": %u, \"stochastic_masks\": \"%s\"", (unsigned)o->config.seed,
                o->config.stochastic_masks == OIT_STOCHASTIC_INDEPENDENT ? "independent" : "stratified");
    } else {
        fprintf(out, ", \"samples\": %d, \"sample_positions\": \"%s\"", o->samples > 0 ? o->samples : 1,
                oit_sample_positions_name(o->samples));
    }
    fprintf(out, ", \"triangles\": %u", s->model.triangle_count);
    json_warnings(out, &s->model);
    /* the camera used, row by row as --modelview/--projection and oit measure take it */
    oit_frame_settings frame;
    oit_error ignored;
    if (render_frame_settings(s, o, &frame, &ignored) == OIT_OK) {
        fprintf(out, ", \"modelview\": ");
        json_matrix_rows(out, frame.modelview);
        fprintf(out, ", \"projection\": ");
        json_matrix_rows(out, frame.projection);
        oit_cli_print_sections_json(out, &s->model, &frame.local);
    }
    /* --explode: the factor, and each part's offset in model units */
    fprintf(out, ", \"explode\": %.9g", o->explode);
    if (o->explode != 0.0 && s->offsets) {
        fputs(", \"parts\": [", out);
        for (uint32_t c = 0; c < s->model.component_count; ++c) {
            const float *v = s->offsets + (size_t)c * 3;
            fprintf(out, "%s{\"name\": ", c ? ", " : "");
            json_string(out, s->model.components[c].name);
            fprintf(out, ", \"offset\": [%.9g, %.9g, %.9g]}", v[0], v[1], v[2]);
        }
        fputc(']', out);
    }
    /* sections: the open parts a section cuts (no cap) */
    if (s->has_sections) {
        fputs(", \"open_cut_parts\": [", out);
        for (uint32_t c = 0, n = 0; s->open_cut && c < s->model.component_count; ++c)
            if (s->open_cut[c]) {
                fputs(n++ ? ", " : "", out);
                json_string(out, s->model.components[c].name);
            }
        fputc(']', out);
    }
    fprintf(out, ", \"gpu_ms\": %.4f, \"cpu_ms\": %.4f", stages_total(st), st->cpu_ms);
    fprintf(out, ", \"stages\": [");
    for (int i = 0; i < st->stage_count; ++i) {
        fprintf(out, "%s{\"name\": ", i ? ", " : "");
        json_string(out, st->stages[i].name);
        fprintf(out, ", \"gpu_ms\": %.4f}", st->stages[i].gpu_ms);
    }
    fprintf(out, "], \"memory_bytes\": %llu", (unsigned long long)st->memory_bytes);
    if (r->gl_allocated_bytes >= 0) /* the independent count of memory_bytes (tests) */
        fprintf(out, ", \"gl_allocated_bytes\": %lld", (long long)r->gl_allocated_bytes);
    json_stats_figures(out, st, true);
    /* --axes, --scale-bar: what was drawn (pixels: x right, y down from the top-left) */
    if (r->overlay.axes) {
        const oit_overlay_info *a = &r->overlay;
        fprintf(out, ", \"axes\": {\"corner\": \"%s\", \"origin\": [%.6f, %.6f], \"length\": %.6f, "
                     "\"directions\": [[%.6f, %.6f], [%.6f, %.6f], [%.6f, %.6f]]}",
                oit_corner_name(o->overlay.axes_corner), a->axes_origin[0], a->axes_origin[1], a->axes_length,
                a->axes_directions[0][0], a->axes_directions[0][1], a->axes_directions[1][0],
                a->axes_directions[1][1], a->axes_directions[2][0], a->axes_directions[2][1]);
    }
    if (o->overlay.scale_bar && r->overlay.scale_bar) {
        const oit_overlay_info *b = &r->overlay;
        fprintf(out, ", \"scale_bar\": {\"length\": %.9g, \"units\": ", b->scale_value);
        json_string(out, b->scale_units);
        fprintf(out, ", \"label\": ");
        json_string(out, b->scale_label);
        fprintf(out, ", \"pixels\": %.6f, \"pixels_per_unit\": %.9g, \"start\": [%.6f, %.6f], "
                     "\"thickness\": %.6f, \"exact\": \"%s\"}",
                b->scale_pixels, b->scale_pixels_per_unit, b->scale_start[0], b->scale_start[1],
                b->scale_thickness, b->scale_exact ? "everywhere (orthographic)" : "at the model's centre's depth");
    } else if (o->overlay.scale_bar)
        fputs(", \"scale_bar\": null", out);
    if (o->out_path) {
        fprintf(out, ", \"out\": ");
        json_string(out, o->out_path);
    }
    if (error) {
        fputs(", \"error\": {", out);
        json_image_error(out, error, "");
        fputc('}', out);
    }
    fprintf(out, "}\n");
}

/* ------------------------------------------------------------ commands */

/* "kbuffer, hybrid, mlab": the algorithms whose capabilities say they read the option. */
static const char *algorithms_reading(unsigned option, char *out, size_t size)
{
    size_t count, used = 0;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    out[0] = '\0';
    for (size_t i = 0; i < count; ++i)
        if (oit_algorithm_reads(list[i], option) && used < size)
            used += (size_t)snprintf(out + used, size - used, "%s%s", used ? ", " : "", list[i]->name);
    return out;
}

/* The render flags and, from the registry and the capabilities, which
 * algorithms there are and which read each algorithm-specific flag. */
static void print_render_help(FILE *out)
{
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    char names[256] = "", reading[128];
    for (size_t i = 0, used = 0; i < count && used < sizeof names; ++i)
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "", list[i]->name);
    fprintf(out,
            "usage: oit render --model PATH [--out FILE.png] [options]\n"
            "       oit render --session FILE.oitsession [--out FILE.png] [options that override it]\n"
            "  --session FILE         a workbench session (docs/sessions.md): its model (relative to the\n"
            "                         file), settings, export size and camera, as Export PNG renders them\n"
            "  --algorithm NAME       %s\n"
            "                         (default ll; oit algorithms says what each renders)\n"
            "  --size WxH             image size, 1..16384 per side (default 256x256)\n"
            "  --modelview M          16 comma-separated numbers, row by row (default: frame the model)\n"
            "  --projection P         16 comma-separated numbers, row by row; clip = P * MV * v\n"
            "  --orbit AZ,EL          default camera turned by azimuth and elevation in degrees (default 0,0)\n"
            "  --alpha A              uniform opacity in [0, 1] (default 0.5), times each material's opacity\n"
            "  --shading MODE         flat | headlight (default headlight: two-sided diffuse from the eye)\n"
            "  --background R,G,B     each in [0, 1] (default 1,1,1)\n"
            "  --backend NAME         egl | osmesa (default egl)\n"
            "  --samples N            anti-aliasing: 1 (default, off), 4, 8 or 16 samples per pixel at\n"
            "                         the standard (Direct3D 11 / Vulkan) positions; every algorithm\n"
            "                         renders N times and the images are averaged (N times the time);\n"
            "                         stochastic: its samples per pixel, 1, 4, 8 (default) or 16, at the\n"
            "                         pixel centre, in one render\n"
            "  --explode F            exploded view, F in [0, 10] (default 0: the assembly as built): each\n"
            "                         part moves away from its parent's centre (the model's, or its node's\n"
            "                         in an assembly tree) by F times its centre's distance from it;\n"
            "                         --json adds each part's \"offset\"\n"
            "  --tessellation T       STEP and IGES: coarse | normal | fine (linear deflection 1/250,\n"
            "                         1/1000, 1/4000 of the model's diagonal; default normal) or a\n"
            "                         linear deflection in millimetres\n",
            names);
    fprintf(out, "  --max-memory MB        budget for growing buffers such as the fragment pool (default\n"
                 "                         1024); read by %s\n",
            algorithms_reading(OIT_OPTION_MAX_MEMORY, reading, sizeof reading));
    fprintf(out, "  --sort VARIANT         %s: insertion (in place) | array (local array of 64) | bma (Knowles'\n"
                 "                         arrays by list length, register blocks) | merge (default: bma's\n"
                 "                         register blocks merged in the lists); the same images\n",
            algorithms_reading(OIT_OPTION_SORT, reading, sizeof reading));
    fprintf(out,
            "  --fragment-pool N      %s: initial fragment pool capacity (default: automatic); it grows\n"
            "                         as needed\n"
            "  --fragment-counter-start N  %s (tests): start the fill's 32-bit fragment counter at N,\n"
            "                         0..4294967295 (default 0), to reach its limit without 2^32 fragments\n"
            "  --buffer-fragment-limit N  %s (tests): address at most N fragments in one buffer, as if\n"
            "                         the GL's limit were that low, so the frame is drawn in bands of rows\n",
            algorithms_reading(OIT_OPTION_FRAGMENT_POOL, reading, sizeof reading), reading, reading);
    fprintf(out,
            "  --max-layers N         %s: peel at most N layers, 1..1000000 (default: no cap, peel\n"
            "                         until nothing is left); a frame the cap cuts short gets a warning\n"
            "                         and \"truncated\": true\n",
            algorithms_reading(OIT_OPTION_MAX_LAYERS, reading, sizeof reading));
    fprintf(out, "  --layers K             %s: layers kept per pixel, 1..%d (default %d)\n",
            algorithms_reading(OIT_OPTION_LAYERS, reading, sizeof reading), OIT_LAYERS_MAX,
            OIT_LAYERS_DEFAULT);
    fprintf(out, "  --moments M            %s: power4, power6 or trig3 (default power4)\n",
            algorithms_reading(OIT_OPTION_MOMENTS, reading, sizeof reading));
    fprintf(out, "  --wavelet-rank R       %s: the Haar basis' rank, 1..%d (default %d): 2^(R+1) coefficients\n"
                 "                         per pixel (4, 8 or 16)\n",
            algorithms_reading(OIT_OPTION_WAVELET_RANK, reading, sizeof reading), OIT_WAVELET_RANK_MAX,
            OIT_WAVELET_RANK_DEFAULT);
    fprintf(out, "  --seed S               %s: the seed of the coverage masks, 0..4294967295 (default 0)\n"
                 "  --stochastic-masks M   %s: stratified (default: exactly round(alpha N) of the N samples)\n"
                 "                         or independent (each sample with probability alpha)\n",
            algorithms_reading(OIT_OPTION_SEED, reading, sizeof reading), reading);
    fputs("  --error-vs-reference   also render the frame with the CPU reference and report the error:\n"
          "                         rmse, psnr, ssim, max, share_over_2 (RGB), flip (mean LDR FLIP, 0..1;\n"
          "                         docs/cli.md); --json adds \"error\": {...}\n"
          "  --error-map FILE.png   write the per-pixel error against the reference as a heat map with a\n"
          "                         legend (black: exact; blue to red: 1 to 64+ of 255, logarithmic)\n"
          "  --error-metric abs|flip  what --error-map shows: abs, the largest channel difference\n"
          "                         (default), or flip, the per-pixel FLIP (0..1) through magma\n",
          out);
    fprintf(out,
            "  --locks-held           %s (tests): every pixel's lock starts taken, so every fragment\n"
            "                         gives up after its tries and the frame fails naming them\n",
            algorithms_reading(OIT_OPTION_LOCKS_HELD, reading, sizeof reading));
    fputs("  --axes[=CORNER]        draw the axes triad (X red, Y green, Z blue, as the view turns the\n"
          "                         model's axes) in a corner: bottom-left (default), bottom-right,\n"
          "                         top-left or top-right; --json adds \"axes\"\n"
          "  --scale-bar            draw a scale bar (1, 2 or 5 x 10^k model units; mm for STEP and\n"
          "                         IGES) measured at the model's centre's depth (exact there; exact\n"
          "                         everywhere for an orthographic projection); --json adds \"scale_bar\"\n",
          out);
    fputs("  --frames N             render N frames; figures are medians over frames 2..N (default 1)\n"
          "  --json                 print one JSON object with timings and statistics on stdout\n"
          "  --debug                debug GL context: every stage is checked for GL errors\n",
          out);
}

static int render_with_options(int argc, char **argv, render_options *options, const session_flags *from_session,
                               bool projection_given);

static int command_render(int argc, char **argv)
{
    render_options o;
    render_options_defaults(&o);
    oit_error err = {{0}};
    oit_status status = OIT_OK;
    /* --session FILE (docs/sessions.md): the session's flags first, parsed by
     * the same parser; the command line's own flags then override them */
    const char *session_path = NULL;
    bool model_given = false, projection_given = false;
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--session") == 0) {
            if (i + 1 >= argc)
                return usage_error("--session needs a value%s", "");
            session_path = argv[i + 1];
        }
        model_given = model_given || strcmp(argv[i], "--model") == 0;
        projection_given = projection_given || strcmp(argv[i], "--projection") == 0;
    }
    session_flags from_session;
    memset(&from_session, 0, sizeof from_session);
    if (session_path) {
        if ((status = session_file_read(session_path, model_given, &from_session, &err)) != OIT_OK)
            return report(status, &err);
        for (int k = 0; k < from_session.count; ++k) {
            session_flag *flag = &from_session.flags[k];
            char *pair[2] = {flag->flag, flag->value};
            int at = 0, parsed = parse_render_option(flag->value ? 2 : 1, pair, &at, &o, &err, &status);
            if (parsed < 0) {
                char reason[OIT_ERROR_MESSAGE_SIZE];
                snprintf(reason, sizeof reason, "%s", err.message);
                status = oit_fail(&err, status, "%s: \"%s\": %s", session_path, flag->key, reason);
                session_flags_free(&from_session);
                return report(status, &err);
            }
            if (parsed == 0) /* a setting this oit has no flag for: said, then left out */
                fprintf(stderr, "oit: warning: %s: \"%s\": unknown field ignored (no %s flag)\n", session_path,
                        flag->key, flag->flag);
        }
    }
    int code = render_with_options(argc, argv, &o, &from_session, projection_given);
    session_flags_free(&from_session); /* o's strings pointed into it */
    return code;
}

/* The render command's own flags (over the session's, already in *options), then the frame. */
static int render_with_options(int argc, char **argv, render_options *options, const session_flags *from_session,
                               bool projection_given)
{
    render_options o = *options;
    oit_error err = {{0}};
    oit_status status = OIT_OK;
    bool error_vs_reference = false;
    const char *error_map_path = NULL;
    const char *error_metric_word = NULL;
    oit_error_metric error_metric = OIT_ERROR_METRIC_ABS;
    turntable_options turntable;
    turntable_options_defaults(&turntable);
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--session") == 0) {
            ++i;
            continue;
        }
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_render_help(stdout);
            turntable_print_help(stdout);
            oit_cli_print_local_help(stdout);
            oit_cli_print_modulation_help(stdout);
            return EXIT_OK;
        }
        if (strcmp(argv[i], "--error-vs-reference") == 0) {
            error_vs_reference = true;
            continue;
        }
        if (strcmp(argv[i], "--error-map") == 0) {
            if (i + 1 >= argc)
                return usage_error("--error-map needs a value%s", "");
            error_map_path = argv[++i];
            continue;
        }
        if (strcmp(argv[i], "--error-metric") == 0) {
            if (i + 1 >= argc)
                return usage_error("--error-metric needs a value%s", "");
            error_metric_word = argv[++i];
            if ((status = oit_error_metric_parse(error_metric_word, &error_metric, &err)) != OIT_OK)
                return report(status, &err);
            continue;
        }
        int turntable_parsed = turntable_parse_option(argc, argv, &i, &turntable, &err, &status);
        if (turntable_parsed < 0)
            return report(status, &err);
        if (turntable_parsed > 0)
            continue;
        int parsed = parse_render_option(argc, argv, &i, &o, &err, &status);
        if (parsed < 0)
            return report(status, &err);
        if (parsed == 0)
            return usage_error("render: unknown option '%s'", argv[i]);
    }
    /* another --size than the session's: its matrices keep the vertical
     * field of view (the horizontal scale follows the new aspect) */
    if (from_session->has_matrices && !projection_given &&
        (long)o.width * from_session->height != (long)o.height * from_session->width)
        o.projection[0] = o.projection[5] * o.height / o.width;
    if (error_metric_word && !error_map_path)
        return usage_error("--error-metric goes with --error-map FILE.png%s", "");
    if (!o.model_path)
        return usage_error("render needs --model PATH (or --session FILE)%s", "");
    if (turntable.frames > 0)
        return turntable_run(&o, &turntable,
                             error_vs_reference ? "--error-vs-reference" : error_map_path ? "--error-map" : NULL);
    if (turntable.fps_given || turntable.up_given || turntable.no_video)
        return usage_error("--fps, --turntable-up and --no-video go with --turntable N%s", "");
    if (o.out_path && (status = check_output_path("--out", o.out_path, &err)) != OIT_OK)
        return report(status, &err);
    if (error_map_path && (status = check_output_path("--error-map", error_map_path, &err)) != OIT_OK)
        return report(status, &err);

    session s;
    status = session_open_import(&s, o.model_path, o.backend, o.config.debug, &o.import, &err);
    render_result result;
    memset(&result, 0, sizeof result);
    if (status == OIT_OK)
        status = render_frames(&s, &o, &result, &err);
    if (status == OIT_OK)
        warn_if_truncated(o.algorithm->name, &o.config, &result.stats);
    if (status == OIT_OK && o.out_path)
        status = oit_png_write(o.out_path, &result.image, &err);
    /* the same frame with the CPU reference: the error figures and map */
    oit_image_error error;
    bool has_error = false;
    if (status == OIT_OK && (error_vs_reference || error_map_path)) {
        render_options reference_options = o;
        reference_options.algorithm = &oit_algorithm_reference;
        reference_options.frames = 1;
        reference_options.out_path = NULL;
        if (oit_algorithm_reads(o.algorithm, OIT_OPTION_SAMPLES))
            reference_options.samples = 0; /* its samples are depth slots at the pixel centre, not anti-aliasing */
        render_result reference;
        memset(&reference, 0, sizeof reference);
        status = render_frames(&s, &reference_options, &reference, &err);
        if (status != OIT_OK) {
            char reason[OIT_ERROR_MESSAGE_SIZE];
            snprintf(reason, sizeof reason, "%s", err.message);
            status = oit_fail(&err, status, "--error-vs-reference: the reference could not render the frame: %s",
                              reason);
        }
        if (status == OIT_OK && error_vs_reference) {
            status = oit_image_error_compute(&result.image, &reference.image, &error, &err);
            has_error = status == OIT_OK;
        }
        if (status == OIT_OK && error_map_path) {
            oit_image map;
            status = oit_image_error_map_metric(&result.image, &reference.image, error_metric, true, &map, &err);
            if (status == OIT_OK)
                status = oit_png_write(error_map_path, &map, &err);
            oit_image_free(&map);
        }
        oit_image_free(&reference.image);
    }
    if (status == OIT_OK) {
        /* an image written to stdout (--out /dev/stdout) is not followed by text there */
        FILE *summary = oit_output_standard_stream(o.out_path) == 1 ||
                                oit_output_standard_stream(error_map_path) == 1
                            ? stderr
                            : stdout;
        if (o.json)
            print_render_json(summary, &o, &s, &result, has_error ? &error : NULL);
        else {
            fprintf(summary, "%s: %dx%d, gpu %.3f ms, cpu %.3f ms, memory %.2f MB%s%s\n",
                    o.algorithm->name, o.width, o.height, stages_total(&result.stats),
                    result.stats.cpu_ms, result.stats.memory_bytes / (1024.0 * 1024.0),
                    o.out_path ? ", wrote " : "", o.out_path ? o.out_path : "");
            if (has_error)
                fprintf(summary, "error vs reference: rmse %.3f, psnr %.2f dB, ssim %.5f, max %d, %.3f%% of pixels "
                                "over 2, flip %.5f\n",
                        error.rmse, error.psnr_db, error.ssim, error.max, error.share_over_2, error.flip);
        }
    }
    oit_image_free(&result.image);
    session_close(&s);
    return report(status, &err);
}

static int command_compare(int argc, char **argv)
{
    const char *paths[2] = {NULL, NULL};
    int path_count = 0;
    long tolerance = 0;
    double max_mismatch_percent = 0.0;
    bool json = false;
    const char *diff_path = NULL;
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--help") == 0) {
            fputs("usage: oit compare A.png B.png [--tolerance T] [--max-mismatch PERCENT] [--json]\n"
                  "  reports the largest and mean channel difference, PSNR, the share of pixels over the\n"
                  "  tolerance, and the mean LDR FLIP (0..1, docs/cli.md; not part of the pass/fail)\n"
                  "  --tolerance T           largest channel difference (0..255) a pixel may have and still\n"
                  "                          match (default 0)\n"
                  "  --max-mismatch PERCENT  share of pixels allowed over the tolerance (default 0)\n"
                  "  --diff FILE.png         write the per-pixel difference, amplified 8x\n"
                  "exit 0 within bounds, 1 outside, 2 on bad input\n",
                  stdout);
            return EXIT_OK;
        } else if (strcmp(argv[i], "--tolerance") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 0, 255, &tolerance))
                return usage_error("--tolerance must be a whole number in [0, 255], got '%s'", argv[i]);
        } else if (strcmp(argv[i], "--max-mismatch") == 0 && i + 1 < argc) {
            if (!parse_double(argv[++i], &max_mismatch_percent) ||
                !(max_mismatch_percent >= 0.0 && max_mismatch_percent <= 100.0))
                return usage_error("--max-mismatch must be a percentage in [0, 100], got '%s'", argv[i]);
        } else if (strcmp(argv[i], "--diff") == 0 && i + 1 < argc) {
            diff_path = argv[++i];
        } else if (strcmp(argv[i], "--json") == 0) {
            json = true;
        } else if (argv[i][0] == '-' && argv[i][1] != '\0') {
            return usage_error("compare: unknown option or missing value '%s'", argv[i]);
        } else if (path_count < 2) {
            paths[path_count++] = argv[i];
        } else {
            return usage_error("compare takes two images, got a third: '%s'", argv[i]);
        }
    }
    if (path_count != 2)
        return usage_error("compare needs two PNG files%s", "");
    oit_error err = {{0}};
    oit_image a = {0}, b = {0};
    oit_image_diff diff;
    oit_status status = diff_path ? check_output_path("--diff", diff_path, &err) : OIT_OK;
    if (status == OIT_OK)
        status = oit_png_read(paths[0], &a, &err);
    if (status == OIT_OK)
        status = oit_png_read(paths[1], &b, &err);
    if (status == OIT_OK)
        status = oit_image_compare(&a, &b, (int)tolerance, &diff, &err);
    double flip = 0.0; /* the mean LDR FLIP of A against B (symmetric) */
    if (status == OIT_OK)
        status = oit_image_flip(&a, &b, OIT_FLIP_PPD_DEFAULT, NULL, &flip, &err);
    if (status == OIT_OK && diff_path) {
        oit_image d = {0};
        status = oit_image_alloc(&d, a.width, a.height, &err);
        for (size_t p = 0; status == OIT_OK && p < (size_t)a.width * a.height; ++p) {
            for (int c = 0; c < 3; ++c) {
                int delta = abs((int)a.rgba[p * 4 + c] - (int)b.rgba[p * 4 + c]) * 8;
                d.rgba[p * 4 + c] = (uint8_t)(delta > 255 ? 255 : delta);
            }
            d.rgba[p * 4 + 3] = 255;
        }
        if (status == OIT_OK)
            status = oit_png_write(diff_path, &d, &err);
        oit_image_free(&d);
    }
    oit_image_free(&a);
    oit_image_free(&b);
    if (status != OIT_OK)
        return report(status, &err);
    double percent = 100.0 * diff.share_over_tolerance;
    bool within = percent <= max_mismatch_percent;
    /* JSON has no infinity: identical images report psnr_db null. */
    char psnr[32];
    if (isinf(diff.psnr_db))
        snprintf(psnr, sizeof psnr, "%s", json ? "null" : "inf");
    else
        snprintf(psnr, sizeof psnr, "%.3f", diff.psnr_db);
    if (json)
        printf("{\"max_channel_diff\": %d, \"mean_diff\": %.6f, \"psnr_db\": %s, "
               "\"over_tolerance_percent\": %.4f, \"tolerance\": %ld, \"within\": %s, \"flip\": %.9g}\n",
               diff.max_channel_diff, diff.mean_diff, psnr, percent, tolerance, within ? "true" : "false", flip);
    else
        printf("max channel diff %d, mean diff %.4f, PSNR %s dB, %.3f%% of pixels over tolerance %ld: %s; "
               "FLIP %.5f\n",
               diff.max_channel_diff, diff.mean_diff, psnr, percent, tolerance, within ? "within" : "OUTSIDE", flip);
    return within ? EXIT_OK : EXIT_MISMATCH;
}

static int command_info(int argc, char **argv)
{
    const char *model_path = NULL;
    bool json = false;
    oit_import_options import = {OIT_TESSELLATION_NORMAL, 0.0};
    oit_error err = {{0}};
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--model") == 0 && i + 1 < argc)
            model_path = argv[++i];
        else if (strcmp(argv[i], "--json") == 0)
            json = true;
        else if (strcmp(argv[i], "--tessellation") == 0 && i + 1 < argc) {
            oit_status parsed = oit_import_options_parse_tessellation(argv[++i], &import, &err);
            if (parsed != OIT_OK)
                return report(parsed, &err);
        } else if (strcmp(argv[i], "--help") == 0) {
            fputs("usage: oit info --model PATH [--json] [--tessellation coarse|normal|fine|MM]\n", stdout);
            return EXIT_OK;
        } else
            return usage_error("info: unknown option or missing value '%s'", argv[i]);
    }
    if (!model_path)
        return usage_error("info needs --model PATH%s", "");
    oit_model m;
    /* a FIFO, /dev/zero or a directory is refused before the importer sees it */
    oit_status status = oit_check_regular_file(model_path, "model", &err);
    if (status == OIT_OK)
        status = oit_model_load_contained_with(model_path, NULL, &import, &m, &err);
    if (status != OIT_OK)
        return report(status, &err);
    print_model_warnings(&m);
    double lo[3], hi[3]; /* in the file's coordinates */
    for (int k = 0; k < 3; ++k) {
        lo[k] = m.origin[k] + m.bounds_min[k];
        hi[k] = m.origin[k] + m.bounds_max[k];
    }
    if (json) {
        printf("{\"model\": ");
        json_string(stdout, model_path);
        json_warnings(stdout, &m);
        printf(", \"vertices\": %u, \"welded_vertices\": %u, \"triangles\": %u, \"planes\": %u, "
               "\"components\": %u",
               m.vertex_count, m.welded_count, m.triangle_count, m.plane_count, m.component_count);
        printf(", \"bounds_min\": [%.9g, %.9g, %.9g], \"bounds_max\": [%.9g, %.9g, %.9g]", lo[0], lo[1], lo[2],
               hi[0], hi[1], hi[2]);
        printf(", \"centre\": [%.9g, %.9g, %.9g], \"radius\": %g, \"longest_edge\": %.9g",
               m.origin[0], m.origin[1], m.origin[2], m.radius, m.longest_edge);
        if (m.unit_name[0]) {
            printf(", \"unit\": ");
            json_string(stdout, m.unit_name);
            printf(", \"unit_to_mm\": %.9g", m.unit_to_mm);
        }
        if (m.tessellation_linear_mm > 0)
            printf(", \"tessellation\": {\"linear_deflection_mm\": %.6g, \"angular_deflection_deg\": %.4g, "
                   "\"triangles\": %u, \"ms\": %.1f}",
                   m.tessellation_linear_mm, m.tessellation_angular_rad * (180.0 / 3.14159265358979324), m.triangle_count,
                   m.tessellation_ms);
        printf(", \"nodes\": %u, \"parts\": [", m.node_count);
        for (uint32_t c = 0; c < m.component_count; ++c) {
            const oit_component *p = &m.components[c];
            char path[OIT_NAME_SIZE * 40]; /* 32 levels of names and the part (model_assimp.c) */
            oit_model_component_path(&m, c, path, sizeof path);
            printf("%s{\"name\": ", c ? ", " : "");
            json_string(stdout, p->name);
            printf(", \"path\": ");
            json_string(stdout, path);
            printf(", \"colour\": [%.4g, %.4g, %.4g], \"opacity\": %.4g, \"triangles\": %u, "
                   "\"longest_edge\": %.9g, \"closed\": %s",
                   p->colour[0], p->colour[1], p->colour[2], p->opacity, p->triangle_count,
                   p->longest_edge, p->closed ? "true" : "false");
            /* its bounds over the vertices of its triangles, in file coordinates
             * and relative to the centre ("centre" above), as the model keeps
             * them and the exploded view measures them */
            float part_lo[3] = {INFINITY, INFINITY, INFINITY}, part_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
            for (uint64_t i = (uint64_t)p->first_triangle * 3;
                 i < ((uint64_t)p->first_triangle + p->triangle_count) * 3 && i < (uint64_t)m.triangle_count * 3;
                 ++i)
                for (int k = 0; k < 3; ++k) {
                    float v = m.positions[(size_t)m.indices[i] * 3 + k];
                    part_lo[k] = v < part_lo[k] ? v : part_lo[k];
                    part_hi[k] = v > part_hi[k] ? v : part_hi[k];
                }
            if (p->triangle_count)
                printf(", \"bounds_min\": [%.9g, %.9g, %.9g], \"bounds_max\": [%.9g, %.9g, %.9g]",
                       m.origin[0] + part_lo[0], m.origin[1] + part_lo[1], m.origin[2] + part_lo[2],
                       m.origin[0] + part_hi[0], m.origin[1] + part_hi[1], m.origin[2] + part_hi[2]);
            if (p->triangle_count)
                printf(", \"relative_bounds_min\": [%.9g, %.9g, %.9g], \"relative_bounds_max\": [%.9g, %.9g, %.9g]",
                       part_lo[0], part_lo[1], part_lo[2], part_hi[0], part_hi[1], part_hi[2]);
            putchar('}');
        }
        printf("]}\n");
    } else {
        printf("model       %s\n", model_path);
        printf("vertices    %u (%u distinct positions)\n", m.vertex_count, m.welded_count);
        printf("triangles   %u (%u distinct planes)\n", m.triangle_count, m.plane_count);
        printf("components  %u\n", m.component_count);
        printf("bounds      (%.9g, %.9g, %.9g) .. (%.9g, %.9g, %.9g)\n", lo[0], lo[1], lo[2], hi[0], hi[1],
               hi[2]);
        printf("sphere      centre (%.9g, %.9g, %.9g), radius %g\n", m.origin[0], m.origin[1], m.origin[2],
               m.radius);
        printf("longest edge %g\n", m.longest_edge);
        if (m.unit_name[0])
            printf("unit        %s (%.9g mm; positions in mm)\n", m.unit_name, m.unit_to_mm);
        if (m.tessellation_linear_mm > 0)
            printf("tessellation linear deflection %.6g mm, angular %.4g degrees: %u triangles in %.1f ms\n",
                   m.tessellation_linear_mm, m.tessellation_angular_rad * (180.0 / 3.14159265358979324), m.triangle_count,
                   m.tessellation_ms);
        if (m.node_count)
            printf("assembly    %u nodes\n", m.node_count);
        for (uint32_t c = 0; c < m.component_count; ++c) {
            const oit_component *p = &m.components[c];
            /* with a tree, the path (what --hide and --component-alpha accept besides the name) */
            char path[OIT_NAME_SIZE * 40];
            oit_model_component_path(&m, c, path, sizeof path);
            printf("  %-32s colour (%.3f, %.3f, %.3f) opacity %.3f, %u triangles\n", path, p->colour[0],
                   p->colour[1], p->colour[2], p->opacity, p->triangle_count);
        }
    }
    oit_model_free(&m);
    return EXIT_OK;
}

static int command_gen(int argc, char **argv)
{
    const char *scene = NULL, *out = NULL;
    long complexity = 0;
    size_t count;
    const oit_scene_generator *generators = oit_scene_generator_list(&count);
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--complexity") == 0 && i + 1 < argc) {
            if (!parse_int(argv[++i], 1, 1000, &complexity))
                return usage_error("--complexity must be a whole number in [1, 1000], got '%s'", argv[i]);
        } else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "--list") == 0) {
            printf("usage: oit gen SCENE --out FILE.obj [--complexity N]   (writes FILE.obj and FILE.mtl)\n");
            for (size_t g = 0; g < count; ++g)
                printf("  %-10s %s (default complexity %d)\n", generators[g].name, generators[g].summary,
                       generators[g].default_complexity);
            return EXIT_OK;
        } else if (argv[i][0] != '-' && !scene)
            scene = argv[i];
        else
            return usage_error("gen: unknown option or missing value '%s'", argv[i]);
    }
    if (!scene || !out)
        return usage_error("gen needs SCENE and --out FILE.obj%s", "");
    oit_error err = {{0}};
    oit_status status = check_output_path("--out", out, &err); /* (the MTL's name is checked as it is opened) */
    if (status == OIT_OK)
        status = oit_scene_generate(scene, (int)complexity, out, &err);
    return report(status, &err);
}

/* ', "views": [...], "modulations": [...], "distances": [...], "options": [...]':
 * the values each --flag takes that the algorithm renders, and the render
 * flags it reads, from its capabilities. */
static void json_capabilities(FILE *out, const oit_algorithm_ops *ops)
{
    const oit_capabilities *can = ops->capabilities;
    fputs(", \"views\": [", out);
    for (int v = 0, n = 0; v < OIT_VIEW_COUNT; ++v)
        if (!can->views[v])
            fprintf(out, "%s\"%s\"", n++ ? ", " : "", oit_setting_word(OIT_SETTING_VIEW, v));
    fputs("], \"modulations\": [", out);
    for (int m = 0, n = 0; m < OIT_MODULATION_COUNT; ++m)
        if (!can->modulations[m])
            fprintf(out, "%s\"%s\"", n++ ? ", " : "", oit_setting_word(OIT_SETTING_MODULATION, m));
    fputs("], \"distances\": [", out); /* where a modulation measures distance */
    bool measures = !can->modulations[OIT_MODULATE_DISTANCE] || !can->modulations[OIT_MODULATE_DIST_CURV];
    for (int d = 0, n = 0; measures && d < OIT_DISTANCE_COUNT; ++d)
        if (!can->distances[d])
            fprintf(out, "%s\"%s\"", n++ ? ", " : "", oit_setting_word(OIT_SETTING_DISTANCE, d));
    fputs("], \"options\": [", out);
    int n = 0;
    for (int bit = 0; bit < OIT_OPTION_COUNT; ++bit) {
        if (!oit_algorithm_reads(ops, 1u << bit))
            continue;
        /* each flag of the option */
        const char *flags = oit_option_flags(1u << bit);
        while (*flags) {
            size_t length = strcspn(flags, " ");
            fprintf(out, "%s\"%.*s\"", n++ ? ", " : "", (int)length, flags);
            flags += length + (flags[length] == ' ');
        }
    }
    fputs("]", out);
}

static int command_algorithms(int argc, char **argv)
{
    bool json = false;
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--json") == 0)
            json = true;
        else if (strcmp(argv[i], "--help") == 0) {
            fputs("usage: oit algorithms [--json]   (--json: [{\"name\", \"exact\", \"uses_layers\", "
                  "\"uses_moments\", \"summary\", \"uses_gl\", \"views\", \"modulations\", \"distances\",\n"
                  "                                  \"options\"}]:"
                  "                                  what each renders, from its capabilities)\n",
                  stdout);
            return EXIT_OK;
        } else
            return usage_error("algorithms: unknown option '%s'", argv[i]);
    }
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    if (json)
        printf("[");
    for (size_t i = 0; i < count; ++i) {
        if (!json) {
            printf("%-10s %s\n", list[i]->name, list[i]->summary);
            continue;
        }
        printf("%s{\"name\": ", i ? ", " : "");
        json_string(stdout, list[i]->name);
        printf(", \"exact\": %s, \"uses_layers\": %s, \"uses_moments\": %s, \"summary\": ",
               list[i]->exact ? "true" : "false", oit_algorithm_reads(list[i], OIT_OPTION_LAYERS) ? "true" : "false",
               oit_algorithm_reads(list[i], OIT_OPTION_MOMENTS) ? "true" : "false");
        json_string(stdout, list[i]->summary);
        printf(", \"uses_gl\": %s", list[i]->uses_gl ? "true" : "false");
        json_capabilities(stdout, list[i]);
        printf("}");
    }
    if (json)
        printf("]\n");
    return EXIT_OK;
}

/* The bundled default model: resources/models/gearbox.obj next to the shaders. */
static oit_status find_default_model(char *out, size_t size, oit_error *err)
{
    char shader_dir[4096];
    oit_status status = oit_find_shader_dir(program_path, shader_dir, sizeof shader_dir, err);
    if (status != OIT_OK)
        return status;
    char candidate[4200];
    int written = snprintf(candidate, sizeof candidate, "%s/../resources/models/gearbox.obj", shader_dir);
    if (written < 0 || (size_t)written >= sizeof candidate || size < PATH_MAX ||
        realpath(candidate, out) == NULL)
        return oit_fail(err, OIT_E_INPUT, "the bundled model is missing: looked for %s", candidate);
    return OIT_OK;
}

static int command_demo(int argc, char **argv)
{
    render_options o;
    render_options_defaults(&o);
    const char *out_dir = "oit-demo";
    char default_model[PATH_MAX];
    oit_error err = {{0}};
    oit_status status = OIT_OK;
    o.frames = 5;
    /* a three-quarter view shows the parts behind each other */
    o.orbit[0] = 30.0f;
    o.orbit[1] = 20.0f;
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--help") == 0) {
            printf("usage: oit demo [--out DIR] [--model PATH] [render options]\n"
                   "Renders the model (default: the bundled gearbox) with every algorithm, writes\n"
                   "DIR/<algorithm>.png and prints frame time, memory and the largest difference\n"
                   "from the CPU reference.\n");
            return EXIT_OK;
        }
        if (strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
            out_dir = argv[++i];
            continue;
        }
        int parsed = parse_render_option(argc, argv, &i, &o, &err, &status);
        if (parsed < 0)
            return report(status, &err);
        if (parsed == 0)
            return usage_error("demo: unknown option '%s'", argv[i]);
    }
    if (!o.model_path) {
        status = find_default_model(default_model, sizeof default_model, &err);
        if (status != OIT_OK)
            return report(status, &err);
        o.model_path = default_model;
    }
    if (mkdir(out_dir, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "oit: error: cannot create the output directory %s: %s\n", out_dir, strerror(errno));
        return EXIT_USAGE;
    }
    size_t count;
    const oit_algorithm_ops *const *list = oit_algorithm_list(&count);
    /* every image's name, before anything renders */
    for (size_t i = 0; i < count; ++i) {
        char path[4400];
        snprintf(path, sizeof path, "%s/%s.png", out_dir, list[i]->name);
        status = check_output_path("--out", path, &err);
        if (status != OIT_OK)
            return report(status, &err);
    }
    session s;
    status = session_open(&s, o.model_path, o.backend, o.config.debug, &err);
    if (status != OIT_OK)
        return report(status, &err);

    render_result reference;
    render_options ref_options = o;
    ref_options.algorithm = oit_algorithm_find("reference");
    ref_options.frames = 1;
    status = render_frames(&s, &ref_options, &reference, &err);
    if (status != OIT_OK) {
        session_close(&s);
        return report(status, &err);
    }
    printf("model %s, %u triangles, %dx%d, %d frames each (medians of frames 2..%d)\n", o.model_path,
           s.model.triangle_count, o.width, o.height, o.frames, o.frames);
    printf("%-10s %10s %10s %10s %12s %10s  %s\n", "algorithm", "cpu ms", "gpu ms", "memory MB", "fragments",
           "max diff", "image");
    oit_image centre_reference = {0}; /* the reference at the pixel centre, when it differs */
    for (size_t i = 0; i < count && status == OIT_OK; ++i) {
        render_options run = o;
        run.algorithm = list[i];
        if (!list[i]->uses_gl)
            run.frames = 1;
        render_result r;
        status = render_frames(&s, &run, &r, &err);
        if (status != OIT_OK)
            break;
        char path[4400];
        snprintf(path, sizeof path, "%s/%s.png", out_dir, list[i]->name);
        status = oit_png_write(path, &r.image, &err);
        /* stochastic's --samples are its own, at the pixel centre: so is its reference */
        bool own_samples = oit_algorithm_reads(list[i], OIT_OPTION_SAMPLES) && o.samples > 1;
        if (status == OIT_OK && own_samples && !centre_reference.rgba)
            status = render_centre_reference(&s, &ref_options, &centre_reference, &err);
        oit_image_diff diff = {0};
        if (status == OIT_OK)
            status = oit_image_compare(&r.image, own_samples ? &centre_reference : &reference.image, 0, &diff, &err);
        if (status == OIT_OK) {
            char fragments[32] = "-";
            if (r.stats.fragments >= 0)
                snprintf(fragments, sizeof fragments, "%lld", (long long)r.stats.fragments);
            printf("%-10s %10.2f %10.2f %10.2f %12s %10d  %s\n", list[i]->name, r.stats.cpu_ms,
                   list[i]->uses_gl ? stages_total(&r.stats) : 0.0, r.stats.memory_bytes / (1024.0 * 1024.0),
                   fragments, diff.max_channel_diff, path);
        }
        oit_image_free(&r.image);
    }
    oit_image_free(&reference.image);
    oit_image_free(&centre_reference);
    session_close(&s);
    return report(status, &err);
}

static const char main_help[] =
    "oit: order-independent transparency workbench, headless\n"
    "usage: oit COMMAND [options]   (oit COMMAND --help for each)\n"
    "  render      render a model with one algorithm; write a PNG; report timings (--json)\n"
    "  compare     compare two PNG images: largest and mean difference, PSNR, share over tolerance, FLIP\n"
    "  info        counts, bounds and components of a model\n"
    "  gen         write a procedural test scene (cyclic, onion, spheres, gearbox, coplanar, menger)\n"
    "  demo        render the bundled model with every algorithm and print a table\n"
    "  bench       scenes x algorithms x sizes: frame and stage times, memory, lists; CSV and JSON\n"
    "  measure     the source's measuring command line: TASK COUNTER NAME PATH m00..m33 p00..p33 [VIEWPORT]\n"
    "  algorithms  list the algorithms\n"
    "  pick        which part adds most to one pixel's colour (or the next), by the reference's maths\n"
    "exit status: 0 success, 1 comparison outside bounds, 2 bad usage or input, 3 GL or runtime failure\n";

/* ------------------------------------------------------------ signals */

/* SIGINT, SIGTERM, SIGHUP: the temporaries go (no TARGET.tmp.* is left, the
 * previous outputs stay as they were), then the signal does what it would
 * have done. */
static void on_interrupt(int signal_number)
{
    oit_temporaries_remove_all();
    signal(signal_number, SIG_DFL);
    raise(signal_number); /* delivered when the handler returns */
}

#ifndef OIT_ADDRESS_SANITIZER
static char crash_limit_note[160]; /* composed at start: the handler only copies */

/* A crash (in practice inside the GL driver, e.g. Mesa's shader compiler
 * under a tight `ulimit -v`) is one line and exit 3 like any runtime
 * failure, not a bare "Segmentation fault"; only async-signal-safe calls. */
static void on_crash(int signal_number)
{
    oit_temporaries_remove_all();
    char line[320] = "oit: error: the program crashed (signal ";
    size_t n = strlen(line);
    char digits[8];
    int d = 0;
    for (int v = signal_number; v > 0 && d < 7; v /= 10)
        digits[d++] = (char)('0' + v % 10);
    while (d > 0 && n < sizeof line - 1)
        line[n++] = digits[--d];
    const char *name = signal_number == SIGSEGV   ? ", Segmentation fault)"
                       : signal_number == SIGBUS  ? ", Bus error)"
                       : signal_number == SIGABRT ? ", Aborted)"
                       : signal_number == SIGILL  ? ", Illegal instruction)"
                       : signal_number == SIGFPE  ? ", Floating point exception)"
                                                  : ")";
    for (const char *c = name; *c && n < sizeof line - 1; ++c)
        line[n++] = *c;
    for (const char *c = crash_limit_note; *c && n < sizeof line - 1; ++c)
        line[n++] = *c;
    line[n++] = '\n';
    (void)!write(STDERR_FILENO, line, n);
    _exit(EXIT_RUNTIME);
}
#endif

static void install_signal_handlers(void)
{
    const int interrupts[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t k = 0; k < sizeof interrupts / sizeof interrupts[0]; ++k) {
        struct sigaction action, previous;
        memset(&action, 0, sizeof action);
        action.sa_handler = on_interrupt;
        sigemptyset(&action.sa_mask);
        for (size_t j = 0; j < sizeof interrupts / sizeof interrupts[0]; ++j)
            sigaddset(&action.sa_mask, interrupts[j]); /* one cleanup at a time */
        /* an ignored signal stays ignored (nohup, a background job) */
        if (sigaction(interrupts[k], NULL, &previous) == 0 && previous.sa_handler != SIG_IGN)
            sigaction(interrupts[k], &action, NULL);
    }
#ifndef OIT_ADDRESS_SANITIZER /* (ASan reports a crash itself, with its stack) */
    struct rlimit address_space;
    if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
        snprintf(crash_limit_note, sizeof crash_limit_note,
                 "; the address space is limited to %llu MiB (ulimit -v %llu), which the GL driver may need "
                 "more than",
                 (unsigned long long)(address_space.rlim_cur >> 20),
                 (unsigned long long)(address_space.rlim_cur >> 10));
    const int crashes[] = {SIGSEGV, SIGBUS, SIGABRT, SIGILL, SIGFPE};
    for (size_t k = 0; k < sizeof crashes / sizeof crashes[0]; ++k) {
        struct sigaction action;
        memset(&action, 0, sizeof action);
        action.sa_handler = on_crash;
        action.sa_flags = SA_RESETHAND; /* a second crash inside ends the process */
        sigemptyset(&action.sa_mask);
        sigaction(crashes[k], &action, NULL);
    }
#endif
}

int main(int argc, char **argv)
{
    /* models are imported by this program run again as a contained worker */
    if (oit_import_worker_requested(argc, argv))
        return oit_import_worker_main(argc, argv);
    program_path = argv[0];
    install_signal_handlers();
    if (argc < 2)
        return usage_error("missing command%s", "");
    const char *command = argv[1];
    if (strcmp(command, "--help") == 0 || strcmp(command, "-h") == 0 || strcmp(command, "help") == 0) {
        fputs(main_help, stdout);
        return EXIT_OK;
    }
    static const struct {
        const char *name;
        int (*run)(int argc, char **argv);
    } commands[] = {
        {"render", command_render},   {"compare", command_compare}, {"info", command_info},
        {"gen", command_gen},         {"demo", command_demo},       {"bench", command_bench},
        {"measure", command_measure}, {"algorithms", command_algorithms}, {"pick", command_pick},
    };
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; ++k)
        if (strcmp(command, commands[k].name) == 0)
            return commands[k].run(argc - 2, argv + 2);
    return usage_error("unknown command '%s'", command);
}
