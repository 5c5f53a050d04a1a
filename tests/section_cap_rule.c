/*
 * section_cap_rule.c OBJ: the caps' exemption from their own plane
 * (docs/sections.md, "Section planes"), which the command line cannot reach
 * until a cap is made: the OBJ has a square "front" at z = 0.01 and a square
 * "back" at z = -0.5. The plane z <= 0 removes the front square, unless its
 * vertices are marked a cap of that plane (oit_model.vertex_section_cap = 1):
 * then it stays, as a cap lying on its plane must; a second plane z <= 0.005
 * still removes it. dp, ll and ib (the component attribute's cap bits) match
 * the reference within 2/255 in each case, the kept and removed images
 * differ, and the pick at the centre finds the front square only when kept.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "oit.h"

static int failures;

static void check(int ok, const char *what, const oit_error *err)
{
    printf("%s: %s%s%s\n", ok ? "ok  " : "FAIL", what, err ? ": " : "", err ? err->message : "");
    if (!ok)
        ++failures;
}

static oit_status render(const char *name, const char *shader_dir, const oit_scene *scene,
                         const oit_frame_settings *frame, oit_image *out, oit_error *err)
{
    const oit_algorithm_ops *ops = oit_algorithm_find(name);
    oit_algorithm_config config;
    oit_algorithm_config_defaults(&config);
    config.shader_dir = shader_dir;
    oit_algorithm *alg = NULL;
    oit_status status = oit_algorithm_create(ops, &config, &alg, err);
    if (status == OIT_OK)
        status = oit_algorithm_resize(ops, alg, frame->width, frame->height, err);
    if (status == OIT_OK)
        status = oit_algorithm_render(ops, alg, scene, frame, err);
    if (status == OIT_OK)
        status = ops->read_image(alg, out, err);
    if (alg)
        ops->destroy(alg);
    return status;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s OBJ\n", argv[0]);
        return 2;
    }
    oit_error err = {{0}};
    oit_gl_context *context = NULL;
    char shader_dir[1024];
    oit_model model;
    if (oit_gl_context_create(OIT_BACKEND_EGL, false, &context, &err) != OIT_OK ||
        oit_find_shader_dir(argv[0], shader_dir, sizeof shader_dir, &err) != OIT_OK ||
        oit_model_load(argv[1], &model, &err) != OIT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    uint32_t front = 0;
    while (front < model.component_count && strcmp(model.components[front].name, "front") != 0)
        ++front;
    model.vertex_section_cap = calloc(model.vertex_count, 1);
    if (front == model.component_count || !model.vertex_section_cap) {
        fprintf(stderr, "no part 'front' in %s\n", argv[1]);
        return 1;
    }

    oit_frame_settings frame;
    memset(&frame, 0, sizeof frame);
    frame.width = frame.height = 32;
    frame.alpha = 0.5f;
    frame.shading = OIT_SHADE_FLAT;
    frame.background[0] = frame.background[1] = frame.background[2] = 1.0f;
    if (oit_default_camera(&model, frame.width, frame.height, 0.0, 0.0, frame.modelview, frame.projection,
                           &err) != OIT_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    frame.local.section_count = 1;
    frame.local.sections[0][2] = 1.0; /* z <= 0 */

    /* case 0: not a cap (removed); 1: a cap of plane 1 (kept); 2: a cap of
     * plane 1, with plane 2 z <= 0.005 (removed) */
    oit_image reference[3];
    memset(reference, 0, sizeof reference);
    for (int c = 0; c < 3; ++c) {
        for (uint32_t v = 0; v < model.vertex_count; ++v)
            model.vertex_section_cap[v] = (c > 0 && model.vertex_component[v] == front) ? 1 : 0;
        frame.local.section_count = c == 2 ? 2 : 1;
        frame.local.sections[1][2] = 1.0;
        frame.local.sections[1][3] = 0.005;
        oit_scene scene;
        if (oit_scene_upload(&scene, &model, &err) != OIT_OK) {
            check(0, "upload", &err);
            break;
        }
        char what[160];
        oit_status status = render("reference", shader_dir, &scene, &frame, &reference[c], &err);
        snprintf(what, sizeof what, "case %d: reference renders", c);
        check(status == OIT_OK, what, status == OIT_OK ? NULL : &err);
        const char *exact[] = {"dp", "ll", "ib"};
        for (size_t a = 0; a < 3 && status == OIT_OK; ++a) {
            oit_image image = {0};
            oit_image_diff diff = {0};
            oit_status s = render(exact[a], shader_dir, &scene, &frame, &image, &err);
            if (s == OIT_OK)
                s = oit_image_compare(&image, &reference[c], 2, &diff, &err);
            snprintf(what, sizeof what, "case %d: %s matches the reference (max diff %d)", c, exact[a],
                     diff.max_channel_diff);
            check(s == OIT_OK && diff.pixels_over_tolerance == 0, what, s == OIT_OK ? NULL : &err);
            oit_image_free(&image);
        }
        oit_pick pick;
        status = oit_pick_pixel(&model, &frame, frame.width / 2, frame.height / 2, &pick, &err);
        bool front_picked = status == OIT_OK && pick.part_count > 0 && pick.parts[0].component == front;
        snprintf(what, sizeof what, "case %d: the pick %s the front square", c, c == 1 ? "finds" : "passes");
        check(status == OIT_OK && front_picked == (c == 1), what, status == OIT_OK ? NULL : &err);
        oit_pick_release(&pick);
        oit_scene_release(&scene);
    }
    oit_image_diff diff = {0};
    check(oit_image_compare(&reference[0], &reference[1], 2, &diff, &err) == OIT_OK &&
              diff.pixels_over_tolerance > 0,
          "the cap kept differs from the square removed", NULL);
    check(oit_image_compare(&reference[0], &reference[2], 0, &diff, &err) == OIT_OK &&
              diff.pixels_over_tolerance == 0,
          "another plane removes the cap as it removes the square", NULL);
    for (int c = 0; c < 3; ++c)
        oit_image_free(&reference[c]);
    oit_model_free(&model);
    oit_gl_context_destroy(context);
    printf("%s\n", failures ? "section cap rule: FAILED" : "section cap rule: all passed");
    return failures ? 1 : 0;
}
