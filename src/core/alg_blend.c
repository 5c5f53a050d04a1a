/*
 * alg_blend.c: plain alpha blending in submission order, the cheapest and
 * deliberately wrong baseline. One geometry pass with the depth test off
 * blends every fragment "over" a float target cleared to the background
 * (C = a*c + (1-a)*C, exact only if triangles arrive back to front); a
 * full-screen pass writes the RGBA8 output.
 */
#include "capabilities.h"
#include "gpu_algorithm.h"

typedef struct blend_state {
    oit_gpu_algorithm gpu; /* first: output, memory, timer, statistics, programs */
    GLuint draw_program, resolve_program;
    GLuint accumulation;             /* RGBA32F */
    GLuint accumulation_framebuffer;
} blend_state;

static void blend_destroy(oit_algorithm *alg)
{
    blend_state *s = (blend_state *)alg;
    if (!s)
        return;
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    glDeleteFramebuffers(1, &s->accumulation_framebuffer);
    oit_gpu_destroy(&s->gpu);
}

static oit_status blend_create(const oit_algorithm_config *config, oit_algorithm **out,
                               oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(blend_state), "blend", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    blend_state *s = (blend_state *)gpu;
    status = oit_gpu_program(gpu, "common/geometry.vert", "blend/draw.frag", &s->draw_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/fullscreen.vert", "blend/resolve.frag", &s->resolve_program, err);
    return oit_gpu_created(&s->gpu, status, blend_destroy, out, err);
}

static oit_status blend_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    blend_state *s = (blend_state *)alg;
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    s->accumulation = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    status = oit_gpu_framebuffer(&s->gpu, &s->accumulation_framebuffer, "accumulation", &s->accumulation, 1, 0,
                                 width, height, err);
    return oit_gpu_resize_end(&s->gpu, status, width, height, err);
}

static oit_status blend_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err)
{
    blend_state *s = (blend_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, blend_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;

    oit_timer_stage_begin(&s->gpu.timer, "draw");
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulation_framebuffer);
    glViewport(0, 0, frame->width, frame->height);
    glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    /* alpha stays 1: the target starts opaque (the background) */
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glUseProgram(s->draw_program);
    oit_gl_draw_scene(scene);
    glDisable(GL_BLEND);
    status = oit_gpu_stage_check(&s->gpu, "draw", err);

    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "resolve");
        glBindFramebuffer(GL_FRAMEBUFFER, s->gpu.output.framebuffer);
        glViewport(0, 0, frame->width, frame->height);
        glUseProgram(s->resolve_program);
        glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_ACCUM);
        glBindTexture(GL_TEXTURE_2D, s->accumulation);
        oit_gl_draw_fullscreen(&s->gpu.output);
        glBindTexture(GL_TEXTURE_2D, 0);
        glActiveTexture(GL_TEXTURE0);
        status = oit_gpu_stage_check(&s->gpu, "resolve", err);
    }
    return oit_gpu_frame_end(&s->gpu, status, err);
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
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = blend_destroy,
};
