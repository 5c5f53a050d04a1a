/*
 * alg_wboit.c: weighted blended order-independent transparency
 * (McGuire & Bavoil 2013). Approximate, one geometry pass, constant memory.
 *
 * "accumulate": depth test off, every fragment adds w*a*c and w*a into a float
 * accumulation target (additive blending) and multiplies a revealage target
 * by (1 - a) (glBlendFunci(ZERO, ONE_MINUS_SRC_COLOR)). The weight w is in
 * shaders/wboit/accumulate.frag. "compose": C = accum.rgb / max(accum.a, 1e-5)
 * * (1 - revealage) + background * revealage. Float targets throughout (32 bit,
 * so that sums of large weights cannot overflow as they can in 16 bit).
 */
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

typedef struct wboit_state {
    oit_gpu_algorithm gpu;     /* first: output, memory, timer, statistics, programs */
    GLuint accumulate_program; /* geometry.vert + wboit/accumulate.frag */
    GLuint compose_program;    /* fullscreen.vert + wboit/compose.frag */

    GLuint accumulation; /* GL_RGBA32F: rgb = sum w*a*c, a = sum w*a */
    GLuint revealage;    /* GL_R32F: product of (1 - a) */
    GLuint accumulate_framebuffer; /* colour attachments 0 = accumulation, 1 = revealage */
} wboit_state;

static void wboit_release_targets(wboit_state *s)
{
    glDeleteFramebuffers(1, &s->accumulate_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->revealage);
    s->accumulate_framebuffer = 0;
}

static void wboit_destroy(oit_algorithm *alg)
{
    wboit_state *s = (wboit_state *)alg;
    if (!s)
        return;
    wboit_release_targets(s);
    oit_gpu_destroy(&s->gpu);
}

static oit_status wboit_create(const oit_algorithm_config *config, oit_algorithm **out,
                               oit_error *err)
{
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(wboit_state), "wboit", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    wboit_state *s = (wboit_state *)gpu;
    status = oit_gpu_program(gpu, "common/geometry.vert", "wboit/accumulate.frag", &s->accumulate_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/fullscreen.vert", "wboit/compose.frag", &s->compose_program, err);
    return oit_gpu_created(&s->gpu, status, wboit_destroy, out, err);
}

static oit_status wboit_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    wboit_state *s = (wboit_state *)alg;
    wboit_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    s->accumulation = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    s->revealage = oit_gpu_target(&s->gpu, GL_R32F, width, height);
    const GLuint accumulate[2] = {s->accumulation, s->revealage};
    status = oit_gpu_framebuffer(&s->gpu, &s->accumulate_framebuffer, "accumulation", accumulate, 2, 0, width,
                                 height, err);
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK) {
        wboit_release_targets(s);
        s->gpu.output.width = s->gpu.output.height = 0;
    }
    return status;
}

static oit_status wboit_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err)
{
    wboit_state *s = (wboit_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, wboit_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glViewport(0, 0, frame->width, frame->height);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST); /* every fragment counts, in any order */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);

    oit_timer_stage_begin(&s->gpu.timer, "accumulate");
    static const GLfloat empty_accumulation[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    static const GLfloat empty_revealage[4] = {1.0f, 0.0f, 0.0f, 0.0f};
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulate_framebuffer);
    glClearBufferfv(GL_COLOR, 0, empty_accumulation);
    glClearBufferfv(GL_COLOR, 1, empty_revealage);
    glEnable(GL_BLEND);
    glBlendEquationi(0, GL_FUNC_ADD);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendEquationi(1, GL_FUNC_ADD);
    glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
    glUseProgram(s->accumulate_program);
    oit_gl_draw_scene(scene);
    glDisable(GL_BLEND);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, "accumulate", err);

    const oit_texture_unit composed[] = {{OIT_TEXUNIT_ACCUM, s->accumulation},
                                         {OIT_TEXUNIT_REVEALAGE, s->revealage}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed,
                                      2, err);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static const oit_capabilities wboit_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "weighted blending accumulates fragments with no order",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("weighted blending keeps no fragment, so no pixel sees its "
                                                      "neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
};

const oit_algorithm_ops oit_algorithm_wboit = {
    .name = "wboit",
    .summary = "weighted blended OIT (McGuire & Bavoil 2013): one pass, approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &wboit_capabilities,
    .create = wboit_create,
    .resize = wboit_resize,
    .render = wboit_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = wboit_destroy,
};
