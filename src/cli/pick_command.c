/*
 * pick_command.c: `oit pick --model M [render options] --pixel X,Y [--rank N]
 * [--json]`: the part that adds most to pixel (X, Y)'s colour (or the N-th
 * most), by the reference's maths (oit_pick_pixel). The camera and opacity
 * come from the render options, parsed by parse_render_option as `oit render`
 * parses them, so a pick names what that render shows.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>
#include <time.h>

#include "json_output.h"
#include "local_options.h"
#include "modulation_options.h"
#include "pick_command.h"
#include "render_session.h"

static void print_pick_help(FILE *out)
{
    fputs("usage: oit pick --model PATH --pixel X,Y [--rank N] [--json] [render options]\n"
          "  --pixel X,Y            the pixel, X from the left and Y from the top row (as in the PNG)\n"
          "  --rank N               the part adding the N-th most to the pixel's colour (default 1);\n"
          "                         past the last part: none\n"
          "  --json                 print {\"part\", \"path\", \"index\", \"contribution\", \"depth\", \"point\", ...}\n"
          "The camera and opacity options are oit render's: --size, --modelview, --projection, --orbit,\n"
          "--alpha, --component-alpha, --hide, --focus-*, --section, --section-parts, --caps,\n"
          "--tessellation, --explode (oit render --help): the pick is on the model as drawn, its parts\n"
          "moved by --explode; a fragment a section plane removes is never picked. A part's\n"
          "contribution is the sum over its fragments at the pixel centre of alpha * T (T: the\n"
          "transmittance in front), in the reference's exact order; depth is the canonical depth of its\n"
          "nearest fragment there (0 near plane .. 1 far plane), point that fragment's position in the\n"
          "file's coordinates. The view and the non-local modulations do not change the pick.\n",
          out);
}

static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* pick_ms: the wall time of oit_pick_pixel (the model's load excluded) */
static void print_pick(const oit_model *model, const oit_pick *pick, long rank, bool json, double pick_ms)
{
    const oit_pick_part *part = rank <= (long)pick->part_count ? &pick->parts[rank - 1] : NULL;
    char path[1024] = "";
    if (part)
        oit_model_component_path(model, part->component, path, sizeof path);
    if (!json) {
        if (!part)
            printf("background (rank %ld of %u parts; background %.6g)\n", rank, pick->part_count,
                   pick->background);
        else
            printf("%s (index %u, rank %ld of %u): contribution %.6g, depth %.9g, point %.9g,%.9g,%.9g\n",
                   path, part->component, rank, pick->part_count, part->contribution, part->depth,
                   part->point[0], part->point[1], part->point[2]);
        return;
    }
    if (!part) {
        printf("{\"part\": null, \"rank\": %ld, \"parts\": %u, \"background\": %.9g, \"pick_ms\": %.3f}\n", rank,
               pick->part_count, pick->background, pick_ms);
        return;
    }
    fputs("{\"part\": ", stdout);
    json_string(stdout, model->components[part->component].name);
    fputs(", \"path\": ", stdout);
    json_string(stdout, path);
    printf(", \"index\": %u, \"contribution\": %.9g, \"depth\": %.9g, \"point\": [%.17g, %.17g, %.17g], "
           "\"triangle\": %u, \"rank\": %ld, \"parts\": %u, \"background\": %.9g, \"pick_ms\": %.3f}\n",
           part->component, part->contribution, part->depth, part->point[0], part->point[1], part->point[2],
           part->triangle, rank, pick->part_count, pick->background, pick_ms);
}

int command_pick(int argc, char **argv)
{
    render_options o;
    render_options_defaults(&o);
    oit_error err = {{0}};
    oit_status status = OIT_OK;
    bool has_pixel = false;
    long pixel[2] = {0, 0}, rank = 1;
    for (int i = 0; i < argc; ++i) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            print_pick_help(stdout);
            return EXIT_OK;
        }
        if (strcmp(argv[i], "--pixel") == 0) {
            if (i + 1 >= argc)
                return usage_error("--pixel needs a value%s", "");
            const char *value = argv[++i];
            double xy[2];
            if (parse_number_list(value, xy, 2) != 2 || xy[0] != (double)(long)xy[0] ||
                xy[1] != (double)(long)xy[1] || !(xy[0] >= -(double)MAX_IMAGE_SIDE) ||
                !(xy[0] <= 2.0 * MAX_IMAGE_SIDE) || !(xy[1] >= -(double)MAX_IMAGE_SIDE) ||
                !(xy[1] <= 2.0 * MAX_IMAGE_SIDE))
                return usage_error("--pixel needs X,Y, two whole numbers, got '%s'", value);
            pixel[0] = (long)xy[0];
            pixel[1] = (long)xy[1];
            has_pixel = true;
            continue;
        }
        if (strcmp(argv[i], "--rank") == 0) {
            if (i + 1 >= argc)
                return usage_error("--rank needs a value%s", "");
            if (!parse_int(argv[++i], 1, 1L << 30, &rank))
                return usage_error("--rank must be a whole number from 1, got '%s'", argv[i]);
            continue;
        }
        int parsed = parse_render_option(argc, argv, &i, &o, &err, &status);
        if (parsed < 0)
            return report(status, &err);
        if (parsed == 0)
            return usage_error("pick: unknown option '%s'", argv[i]);
    }
    if (!o.model_path)
        return usage_error("pick needs --model PATH%s", "");
    if (!has_pixel)
        return usage_error("pick needs --pixel X,Y%s", "");
    /* the pixel is checked against the size before the model loads */
    if (pixel[0] < 0 || pixel[1] < 0 || pixel[0] >= o.width || pixel[1] >= o.height) {
        status = oit_fail(&err, OIT_E_INPUT, "pick: pixel %ld,%ld is outside the %dx%d image (0..%d, 0..%d)",
                          pixel[0], pixel[1], o.width, o.height, o.width - 1, o.height - 1);
        return report(status, &err);
    }

    session s;
    status = session_open_import(&s, o.model_path, o.backend, o.config.debug, &o.import, &err);
    oit_frame_settings frame;
    oit_pick pick = {0};
    /* the model as drawn: picking follows the exploded parts (and the caps) */
    if (status == OIT_OK)
        status = session_prepare_model(&s, &o, &err);
    if (status == OIT_OK)
        status = render_frame_settings(&s, &o, &frame, &err);
    double start = wall_ms();
    if (status == OIT_OK)
        status = oit_pick_pixel(&s.model, &frame, (int)pixel[0], (int)pixel[1], &pick, &err);
    if (status == OIT_OK)
        print_pick(&s.model, &pick, rank, o.json, wall_ms() - start);
    oit_pick_release(&pick);
    session_close(&s);
    return report(status, &err);
}
