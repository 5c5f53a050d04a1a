/*
 * alg_stochastic.c: stochastic transparency (Enderton, Sintorn, Shirley &
 * Luebke 2010). Approximate, two geometry passes and a resolve, memory
 * linear in the pixel's sample count S.
 *
 * llvmpipe's multisampling stops at 4 samples (GL_MAX_SAMPLES), too few for
 * S = 8 or 16, so the samples are not the GL's: per pixel S depth slots
 * (uint, the window depth's bits) in one shader storage buffer. The samples
 * all sit at the pixel centre; this is the paper's stochastic depth buffer,
 * not anti-aliasing.
 * 1. "depth": depth test off; every fragment of opacity a covers a subset of
 *    the S samples (shaders/stochastic/common.glsl: stratified, exactly
 *    round(a S) distinct samples from a seeded permutation, after Laine &
 *    Karras 2011, or independent, each with probability a) and keeps the
 *    nearest depth in each covered slot (atomicMin).
 * 2. "accumulate": depth test off; every fragment adds v a c and v a, v the
 *    share of the S slots at or behind its depth (its estimated
 *    transmittance), into a float target, and multiplies a revealage target
 *    by 1 - a (wboit's targets and blending).
 * 3. "compose": the paper's alpha-corrected resolve, C = sum(v a c) / sum(v a)
 *    * (1 - T) + background * T with T = product of (1 - a) exact, which is
 *    wboit's resolve (shaders/wboit/compose.frag) on these targets.
 * S is the frame's --samples (0: OIT_STOCHASTIC_SAMPLES_DEFAULT), read here
 * (OIT_OPTION_SAMPLES), not by the central supersampling. Memory per pixel:
 * 4 S (slots) + 16 (RGBA32F) + 4 (R32F) + 4 (RGBA8 output) = 24 + 4 S bytes.
 */
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

typedef struct stochastic_state {
    oit_gpu_algorithm gpu;     /* first: output, memory, timer, statistics, programs */
    GLuint depth_program;      /* geometry.vert + stochastic/depth.frag */
    GLuint accumulate_program; /* geometry.vert + stochastic/accumulate.frag */
    GLuint compose_program;    /* fullscreen.vert + wboit/compose.frag */

    GLuint depth_slots;  /* SSBO: width x height x slot_samples uint */
    int slot_samples;    /* the S the slots were made for (0: none yet) */
    GLuint accumulation; /* GL_RGBA32F: rgb = sum v a c, a = sum v a */
    GLuint revealage;    /* GL_R32F: product of (1 - a) */
    GLuint accumulate_framebuffer; /* colour attachments 0 = accumulation, 1 = revealage */
} stochastic_state;

static void stochastic_release_targets(stochastic_state *s)
{
    glDeleteFramebuffers(1, &s->accumulate_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->revealage);
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->depth_slots);
    s->accumulate_framebuffer = 0;
    s->slot_samples = 0;
}

static void stochastic_destroy(oit_algorithm *alg)
{
    stochastic_state *s = (stochastic_state *)alg;
    if (!s)
        return;
    stochastic_release_targets(s);
    oit_gpu_destroy(&s->gpu);
}

static oit_status stochastic_create(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err)
{
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(stochastic_state), "stochastic", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    stochastic_state *s = (stochastic_state *)gpu;
    status = oit_gpu_program(gpu, "common/geometry.vert", "stochastic/depth.frag", &s->depth_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/geometry.vert", "stochastic/accumulate.frag",
                                 &s->accumulate_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/fullscreen.vert", "wboit/compose.frag", &s->compose_program, err);
    return oit_gpu_created(&s->gpu, status, stochastic_destroy, out, err);
}

static oit_status stochastic_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    stochastic_state *s = (stochastic_state *)alg;
    stochastic_release_targets(s);
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
        stochastic_release_targets(s);
        s->gpu.output.width = s->gpu.output.height = 0;
    }
    return status;
}

/* The depth slots for S samples per pixel, made when S or the size changed. */
static oit_status stochastic_slots(stochastic_state *s, int samples, int width, int height, oit_error *err)
{
    if (s->depth_slots && s->slot_samples == samples)
        return OIT_OK;
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->depth_slots);
    s->slot_samples = 0;
    while (glGetError() != GL_NO_ERROR) {
    }
    glGenBuffers(1, &s->depth_slots);
    const uint64_t bytes = (uint64_t)width * (uint64_t)height * (uint64_t)samples * sizeof(GLuint);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_PIXELS, GL_SHADER_STORAGE_BUFFER, s->depth_slots,
                              bytes, NULL, GL_DYNAMIC_COPY);
    if (glGetError() != GL_NO_ERROR) {
        oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->depth_slots);
        return oit_fail(err, OIT_E_RUNTIME, "stochastic: out of memory for %d depth slots per pixel (%llu bytes)",
                        samples, (unsigned long long)bytes);
    }
    s->slot_samples = samples;
    return OIT_OK;
}

static oit_status stochastic_render(oit_algorithm *alg, const oit_scene *scene, const oit_frame_settings *frame,
                                    oit_error *err)
{
    stochastic_state *s = (stochastic_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, stochastic_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;
    const int samples = frame->samples > 0 ? frame->samples : OIT_STOCHASTIC_SAMPLES_DEFAULT;
    status = stochastic_slots(s, samples, frame->width, frame->height, err);
    if (status != OIT_OK)
        return oit_gpu_frame_end(&s->gpu, status, err);
    const int masks = s->gpu.config.stochastic_masks == OIT_STOCHASTIC_INDEPENDENT
                          ? OIT_STOCHASTIC_MASKS_INDEPENDENT
                          : OIT_STOCHASTIC_MASKS_STRATIFIED;

    glViewport(0, 0, frame->width, frame->height);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST); /* the slots are the depth test */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_STOCHASTIC_DEPTH, s->depth_slots);

    oit_timer_stage_begin(&s->gpu.timer, "depth");
    const GLuint empty = OIT_STOCHASTIC_EMPTY;
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulate_framebuffer);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(s->depth_program);
    glUniform1i(OIT_UNIFORM_STOCHASTIC_SAMPLES, samples);
    glUniform1ui(OIT_UNIFORM_STOCHASTIC_SEED, s->gpu.config.seed);
    glUniform1i(OIT_UNIFORM_STOCHASTIC_MASKS, masks);
    oit_gl_draw_scene(scene);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, "depth", err);

    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "accumulate");
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        static const GLfloat empty_accumulation[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        static const GLfloat empty_revealage[4] = {1.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, empty_accumulation);
        glClearBufferfv(GL_COLOR, 1, empty_revealage);
        glEnable(GL_BLEND);
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendEquationi(1, GL_FUNC_ADD);
        glBlendFunci(1, GL_ZERO, GL_ONE_MINUS_SRC_COLOR);
        glUseProgram(s->accumulate_program);
        glUniform1i(OIT_UNIFORM_STOCHASTIC_SAMPLES, samples);
        glUniform1ui(OIT_UNIFORM_STOCHASTIC_SEED, s->gpu.config.seed);
        glUniform1i(OIT_UNIFORM_STOCHASTIC_MASKS, masks);
        oit_gl_draw_scene(scene);
        glDisable(GL_BLEND);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "accumulate", err);
    }

    const oit_texture_unit composed[] = {{OIT_TEXUNIT_ACCUM, s->accumulation},
                                         {OIT_TEXUNIT_REVEALAGE, s->revealage}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed, 2, err);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static const oit_capabilities stochastic_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "stochastic transparency keeps only sample depths",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("stochastic transparency keeps no fragment, so no pixel sees "
                                                      "its neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_SEED | OIT_OPTION_SAMPLES,
};

const oit_algorithm_ops oit_algorithm_stochastic = {
    .name = "stochastic",
    .summary = "stochastic transparency (Enderton et al. 2010): random sample coverage, approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &stochastic_capabilities,
    .create = stochastic_create,
    .resize = stochastic_resize,
    .render = stochastic_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = stochastic_destroy,
};
