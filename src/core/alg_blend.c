/*
 * alg_blend.c: plain alpha blending in submission order, the cheapest and
 * deliberately wrong baseline. One geometry pass with the depth test off
 * blends every fragment "over" a float target cleared to the background
 * (C = a*c + (1-a)*C, exact only if triangles arrive back to front); a
 * full-screen pass writes the RGBA8 output.
 */
#include <stdlib.h>

#include "capabilities.h"
#include "gl_util.h"

struct oit_algorithm {
    oit_algorithm_config config;
    GLuint draw_program, resolve_program;
    GLuint accumulation;             /* RGBA32F */
    GLuint accumulation_framebuffer;
    oit_gl_output output;
    oit_gl_memory memory; /* every texture above and the output's */
    oit_stage_timer timer;
    oit_stats stats;
};

static void blend_destroy(oit_algorithm *alg)
{
    if (!alg)
        return;
    glDeleteProgram(alg->draw_program);
    glDeleteProgram(alg->resolve_program);
    oit_gl_memory_delete_textures(&alg->memory, 1, &alg->accumulation);
    glDeleteFramebuffers(1, &alg->accumulation_framebuffer);
    oit_gl_output_release(&alg->output);
    oit_timer_destroy(&alg->timer);
    free(alg);
}

static oit_status blend_create(const oit_algorithm_config *config, oit_algorithm **out,
                               oit_error *err)
{
    *out = NULL;
    oit_algorithm *alg = calloc(1, sizeof *alg);
    if (!alg)
        return oit_fail(err, OIT_E_RUNTIME, "blend: out of memory");
    alg->config = *config;
    alg->output.memory = &alg->memory;
    oit_stats_reset(&alg->stats);
    oit_status status = oit_gl_program(config->shader_dir, "common/geometry.vert",
                                       "blend/draw.frag", &alg->draw_program, err);
    if (status == OIT_OK)
        status = oit_gl_program(config->shader_dir, "common/fullscreen.vert",
                                "blend/resolve.frag", &alg->resolve_program, err);
    if (status != OIT_OK) {
        blend_destroy(alg);
        return status;
    }
    oit_timer_create(&alg->timer);
    *out = alg;
    return OIT_OK;
}

static oit_status blend_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    oit_status status = oit_gl_output_resize(&alg->output, width, height, err);
    if (status != OIT_OK)
        return status;
    oit_gl_memory_delete_textures(&alg->memory, 1, &alg->accumulation);
    if (!alg->accumulation_framebuffer)
        glGenFramebuffers(1, &alg->accumulation_framebuffer);
    alg->accumulation =
        oit_gl_memory_texture_2d(&alg->memory, OIT_GL_MEMORY_PIXELS, GL_RGBA32F, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, alg->accumulation_framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           alg->accumulation, 0);
    status = oit_gl_check_framebuffer("blend: the RGBA32F target", width, height, &alg->memory, err);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != OIT_OK)
        return status;
    alg->stats.memory_bytes = oit_gl_memory_total(&alg->memory);
    return oit_gl_check("blend: resize", err);
}

static oit_status stage_check(const oit_algorithm *alg, const char *stage, oit_error *err)
{
    if (alg->timer.cancelled)
        return oit_timer_status(&alg->timer, err);
    return alg->config.debug ? oit_gl_check(stage, err) : OIT_OK;
}

static oit_status blend_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err)
{
    if (!scene->has_gpu)
        return oit_fail(err, OIT_E_RUNTIME, "blend: the scene is not on the GPU");
    if (frame->width != alg->output.width || frame->height != alg->output.height) {
        oit_status status = blend_resize(alg, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }
    oit_stats_reset(&alg->stats);
    alg->stats.memory_bytes = oit_gl_memory_total(&alg->memory);
    alg->stats.bytes_per_pixel = (double)oit_gl_memory_bytes(&alg->memory, OIT_GL_MEMORY_PIXELS) /
                                 ((double)frame->width * (double)frame->height);
    oit_timer_frame_begin(&alg->timer, frame);
    oit_gl_bind_part_alpha(scene, frame); /* per-part opacity, every part */

    oit_timer_stage_begin(&alg->timer, "draw");
    glBindFramebuffer(GL_FRAMEBUFFER, alg->accumulation_framebuffer);
    glViewport(0, 0, frame->width, frame->height);
    glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* alpha stays 1: the target starts opaque (the background) */
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(alg->draw_program);
    oit_gl_set_frame_uniforms(frame);
    oit_gl_draw_scene(scene);
    glDisable(GL_BLEND);
    oit_status status = stage_check(alg, "blend: draw", err);

    if (status == OIT_OK) {
        oit_timer_stage_begin(&alg->timer, "resolve");
        glBindFramebuffer(GL_FRAMEBUFFER, alg->output.framebuffer);
        glViewport(0, 0, frame->width, frame->height);
        glUseProgram(alg->resolve_program);
        glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_ACCUM);
        glBindTexture(GL_TEXTURE_2D, alg->accumulation);
        oit_gl_draw_fullscreen(&alg->output);
        glBindTexture(GL_TEXTURE_2D, 0);
        glActiveTexture(GL_TEXTURE0);
        status = stage_check(alg, "blend: resolve", err);
    }
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    oit_timer_frame_end(&alg->timer, &alg->stats);
    if (status == OIT_OK)
        status = oit_gl_check("blend: render", err);
    return status;
}

static oit_status blend_read_image(oit_algorithm *alg, oit_image *out, oit_error *err)
{
    return oit_gl_output_read(&alg->output, out, err);
}

static void blend_stats(const oit_algorithm *alg, oit_stats *out)
{
    *out = alg->stats;
}

static const oit_capabilities blend_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "blending in submission order never has two fragments of a pixel at once",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("blending in submission order never sees the adjacent "
                                                      "pixels' fragments of the same surface")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
};

const oit_algorithm_ops oit_algorithm_blend = {
    .name = "blend",
    .summary = "alpha blending in submission order (one pass, not order-independent)",
    .uses_gl = true,
    .exact = false,
    .capabilities = &blend_capabilities,
    .create = blend_create,
    .resize = blend_resize,
    .render = blend_render,
    .read_image = blend_read_image,
    .stats = blend_stats,
    .destroy = blend_destroy,
};
