/*
 * turntable_command.c: oit render --turntable N --out DIR: N frames of an
 * orbit about the up axis through the model's centre (oit.h, "turntables"),
 * DIR/frame_0000.png ... and DIR/turntable.mp4, DIR replaced whole. Each
 * frame is render_session.c's frame (render_setup_create: the algorithm,
 * modulation, sections, explode, size, and whatever else the render options
 * set) with the turntable's modelview; --json lists each frame's modelview
 * so that `oit render --modelview M --projection P` renders it alone.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "json_output.h"
#include "turntable_command.h"

void turntable_options_defaults(turntable_options *t)
{
    memset(t, 0, sizeof *t);
    t->fps = 30;
    t->up = OIT_TURNTABLE_UP_Y;
}

int turntable_parse_option(int argc, char **argv, int *i, turntable_options *t, oit_error *err, oit_status *status)
{
    const char *flag = argv[*i];
    bool frames = strcmp(flag, "--turntable") == 0, fps = strcmp(flag, "--fps") == 0,
         up = strcmp(flag, "--turntable-up") == 0;
    if (strcmp(flag, "--no-video") == 0) {
        t->no_video = true;
        return 1;
    }
    if (!frames && !fps && !up)
        return 0;
    if (*i + 1 >= argc) {
        *status = oit_fail(err, OIT_E_INPUT, "%s needs a value", flag);
        return -1;
    }
    const char *value = argv[++*i];
    long number;
    if (frames) {
        if (!parse_int(value, 1, OIT_TURNTABLE_FRAMES_MAX, &number)) {
            *status = oit_fail(err, OIT_E_INPUT, "--turntable must be a whole number of frames in [1, %d], got '%s'",
                               OIT_TURNTABLE_FRAMES_MAX, value);
            return -1;
        }
        t->frames = (int)number;
    } else if (fps) {
        if (!parse_int(value, 1, OIT_VIDEO_FPS_MAX, &number)) {
            *status = oit_fail(err, OIT_E_INPUT, "--fps must be a whole number in [1, %d], got '%s'",
                               OIT_VIDEO_FPS_MAX, value);
            return -1;
        }
        t->fps = (int)number;
        t->fps_given = true;
    } else {
        static const char *const words[] = {"y", "z", "x", "view"};
        int found = -1;
        for (int k = 0; k < 4; ++k)
            if (strcmp(value, words[k]) == 0)
                found = k;
        if (found < 0) {
            *status = oit_fail(err, OIT_E_INPUT, "--turntable-up must be x, y, z or view, got '%s'", value);
            return -1;
        }
        t->up = (oit_turntable_up)found;
        t->up_given = true;
    }
    return 1;
}

void turntable_print_help(FILE *out)
{
    fprintf(out,
            "  --turntable N          with --out DIR: N frames (1..%d) of a full orbit of the camera about\n"
            "                         the up axis through the model's centre, frame i at 360*i/N degrees:\n"
            "                         DIR/frame_0000.png ... and DIR/turntable.mp4 (H.264, yuv420p: even\n"
            "                         sizes only); DIR is new, empty or a previous turntable, replaced whole;\n"
            "                         --json lists each frame's modelview\n"
            "  --turntable-up AXIS    x | y | z (model axes) | view (what the camera shows as up); default y\n"
            "  --fps F                the video's frames per second, 1..%d (default 30)\n"
            "  --no-video             the PNGs only (any size)\n",
            OIT_TURNTABLE_FRAMES_MAX, OIT_VIDEO_FPS_MAX);
}

static double now_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static void json_vector(FILE *out, const double v[3])
{
    fprintf(out, "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
}

int turntable_run(render_options *o, const turntable_options *t, const char *other_flag)
{
    oit_error err = {{0}};
    if (other_flag)
        return usage_error("--turntable cannot take %s (it renders each frame once)", other_flag);
    if (!o->out_path)
        return usage_error("--turntable needs --out DIR, the folder for the frames and the video%s", "");
    if (o->frames != 1)
        return usage_error("--turntable cannot take --frames (it renders each frame once)%s", "");
    if (t->no_video && t->fps_given)
        return usage_error("--fps is the video's: it cannot go with --no-video%s", "");
    int fps = t->no_video ? 0 : t->fps;
    if (fps && oit_video_check_size(o->width, o->height, &err) != OIT_OK) {
        fprintf(stderr, "oit: error: --turntable: %s (give an even --size, or --no-video)\n", err.message);
        return EXIT_USAGE;
    }
    /* the folder, before anything renders */
    oit_status status = oit_turntable_output_check(o->out_path, "--out", t->frames, &err);
    if (status != OIT_OK)
        return report(status, &err);

    session s;
    status = session_open_import(&s, o->model_path, o->backend, o->config.debug, &o->import, &err);
    render_setup setup;
    memset(&setup, 0, sizeof setup);
    if (status == OIT_OK)
        status = render_setup_create(&s, o, &setup, &err);
    /* the orbit: about the up axis through the model's centre (its bounding
     * box's, in file coordinates: the workbench's orbit centre) */
    double base[16], axis[3], centre[3];
    const oit_model *loaded = s.derived ? &s.source_model : &s.model;
    if (status == OIT_OK) {
        memcpy(base, setup.frame.modelview, sizeof base);
        memcpy(centre, loaded->origin, sizeof centre);
        status = oit_turntable_axis(base, t->up, axis, &err);
    }
    oit_turntable_output *output = NULL;
    if (status == OIT_OK)
        status = oit_turntable_output_open(o->out_path, "--out", o->width, o->height, t->frames, fps, &output, &err);
    const oit_algorithm_ops *ops = o->algorithm;
    double (*modelviews)[16] = calloc((size_t)t->frames, sizeof *modelviews);
    if (status == OIT_OK && !modelviews)
        status = oit_fail(&err, OIT_E_RUNTIME, "out of memory for %d frames", t->frames);
    double render_ms = 0.0;
    bool truncated = false;
    for (int f = 0; status == OIT_OK && f < t->frames; ++f) {
        oit_turntable_modelview(base, centre, axis, f, t->frames, modelviews[f]);
        memcpy(setup.frame.modelview, modelviews[f], sizeof setup.frame.modelview);
        status = oit_matrices_validate(setup.frame.modelview, setup.frame.projection, &err);
        double start = now_ms();
        if (status == OIT_OK)
            status = oit_algorithm_render(ops, setup.alg, setup.scene, &setup.frame, &err);
        oit_image image = {0};
        if (status == OIT_OK)
            status = ops->read_image(setup.alg, &image, &err);
        oit_overlay_info overlay; /* --axes, --scale-bar on every frame, as on a single render */
        if (status == OIT_OK)
            status = render_overlay(&s, o, &setup.frame, &image, &overlay, &err);
        render_ms += now_ms() - start;
        if (status == OIT_OK) {
            oit_stats stats;
            ops->stats(setup.alg, &stats);
            truncated |= stats.truncated;
            status = oit_turntable_output_add(output, &image, &err);
        }
        oit_image_free(&image);
    }
    double png_ms = 0.0, video_ms = 0.0;
    if (output)
        oit_turntable_output_times(output, &png_ms, &video_ms);
    if (status == OIT_OK) {
        double start = now_ms();
        status = oit_turntable_output_commit(output, &err);
        video_ms += now_ms() - start;
        output = NULL;
    }
    oit_turntable_output_abort(output);
    if (status == OIT_OK && truncated)
        fprintf(stderr, "oit: warning: %s: --max-layers %d cut some turntable frames short\n", ops->name,
                o->config.max_layers);
    if (status == OIT_OK && o->json) {
        static const char *const up_words[] = {"y", "z", "x", "view"};
        printf("{\"algorithm\": ");
        json_string(stdout, ops->name);
        printf(", \"model\": ");
        json_string(stdout, o->model_path);
        printf(", \"width\": %d, \"height\": %d, \"turntable\": %d, \"up\": \"%s\", \"axis\": ", o->width,
               o->height, t->frames, up_words[t->up]);
        json_vector(stdout, axis);
        printf(", \"centre\": ");
        json_vector(stdout, centre);
        printf(", \"projection\": ");
        json_matrix_rows(stdout, setup.frame.projection);
        printf(", \"out\": ");
        json_string(stdout, o->out_path);
        if (fps) {
            printf(", \"video\": \"" OIT_TURNTABLE_VIDEO_NAME "\", \"fps\": %d", fps);
        } else
            printf(", \"video\": null");
        printf(", \"render_ms\": %.3f, \"png_ms\": %.3f, \"video_ms\": %.3f, \"frames\": [", render_ms, png_ms,
               video_ms);
        for (int f = 0; f < t->frames; ++f) {
            printf("%s\n  {\"index\": %d, \"degrees\": %.17g, \"png\": \"frame_%04d.png\", \"modelview\": ",
                   f ? "," : "", f, 360.0 * f / t->frames, f);
            json_matrix_rows(stdout, modelviews[f]);
            printf("}");
        }
        printf("]}\n");
    } else if (status == OIT_OK) {
        printf("%s: %d turntable frames of %dx%d in %s (%s%s), render %.1f ms, png %.1f ms, video %.1f ms\n",
               ops->name, t->frames, o->width, o->height, o->out_path, "frame_0000.png ...",
               fps ? ", " OIT_TURNTABLE_VIDEO_NAME : "", render_ms, png_ms, video_ms);
    }
    free(modelviews);
    if (setup.alg)
        ops->destroy(setup.alg);
    session_close(&s);
    return report(status, &err);
}
