/*
 * absorbance_passes.c: the passes mboit and wavelet share (absorbance_passes.h).
 * 1. the projection ("moments", "coefficients"): depth test off, additive
 *    blending; every fragment adds its optical depth into b0 (R32F, attachment
 *    0) and its step's projection into the projection's targets (attachments
 *    1..n).
 * 2. "transmittance": depth test off, additive blending; every fragment reads
 *    its pixel's sums, reconstructs the transmittance T in front of its depth
 *    and adds (T a c, T a) into an RGBA32F target.
 * 3. "compose" (mboit/compose.frag): C = (sum T a c) / (sum T a) * (1 - exp(-b0))
 *    + background * exp(-b0): the coverage 1 - exp(-b0) is exact.
 * Memory per pixel: 4 (b0) + the projection's targets + 16 (accumulation) + 4
 * (output).
 */
#include "absorbance_passes.h"

#include "oit_shared.h"

_Static_assert(OIT_MBOIT_TARGET_B0 == 0 && OIT_WAVELET_TARGET_B0 == 0, "b0 is attachment 0 of the first pass");
_Static_assert(OIT_MBOIT_TARGET_MOMENTS == 1 && OIT_WAVELET_TARGET_COEFFICIENTS == 1,
               "the projection's targets follow b0");

typedef struct absorbance_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    absorbance_projection projection;

    GLuint projection_program;    /* geometry.vert + the projection shader */
    GLuint transmittance_program; /* geometry.vert + the transmittance shader */
    GLuint compose_program;       /* fullscreen.vert + mboit/compose.frag */

    GLuint b0;                                         /* GL_R32F: sum of optical depths */
    GLuint targets[ABSORBANCE_PROJECTION_TARGETS_MAX]; /* the projection's sums */
    GLuint accumulation;                               /* GL_RGBA32F: (sum T a c, sum T a) */
    GLuint projection_framebuffer;                     /* b0, then the projection's targets */
    GLuint transmittance_framebuffer;                  /* attachment 0: accumulation */
} absorbance_state;

static void absorbance_release_targets(absorbance_state *s)
{
    glDeleteFramebuffers(1, &s->projection_framebuffer);
    glDeleteFramebuffers(1, &s->transmittance_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->b0);
    oit_gl_memory_delete_textures(&s->gpu.memory, ABSORBANCE_PROJECTION_TARGETS_MAX, s->targets);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    s->projection_framebuffer = s->transmittance_framebuffer = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

oit_status absorbance_passes_create(const absorbance_projection *projection, const oit_algorithm_config *config,
                                    oit_algorithm **out, oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(absorbance_state), projection->algorithm, config, &gpu, err);
    if (status != OIT_OK)
        return status;
    absorbance_state *s = (absorbance_state *)gpu;
    s->projection = *projection;

    status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", projection->projection_shader,
                                     projection->defines, &s->projection_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", projection->transmittance_shader,
                                         projection->defines, &s->transmittance_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "mboit/compose.frag", &s->compose_program,
                                 err);
    return oit_gpu_created(&s->gpu, status, absorbance_passes_destroy, out, err);
}

oit_status absorbance_passes_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    absorbance_state *s = (absorbance_state *)alg;
    const absorbance_projection *p = &s->projection;
    absorbance_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    const oit_gl_memory_use pixels = OIT_GL_MEMORY_PIXELS;
    GLuint attachments[1 + ABSORBANCE_PROJECTION_TARGETS_MAX];
    s->b0 = attachments[0] = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_R32F, width, height);
    for (int t = 0; t < p->target_count; ++t)
        s->targets[t] = attachments[1 + t] =
            oit_gl_memory_texture_2d(&s->gpu.memory, pixels, p->target_formats[t], width, height);
    s->accumulation = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RGBA32F, width, height);

    status = oit_gpu_framebuffer(&s->gpu, &s->projection_framebuffer, p->stage, attachments, 1 + p->target_count,
                                 0, width, height, err);
    if (status == OIT_OK)
        status = oit_gpu_framebuffer(&s->gpu, &s->transmittance_framebuffer, "transmittance", &s->accumulation, 1,
                                     0, width, height, err);
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        absorbance_release_targets(s);
    return status;
}

static void absorbance_bind_texture(GLenum unit, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, texture);
}

oit_status absorbance_passes_render(oit_algorithm *alg, const oit_scene *scene, const oit_frame_settings *frame,
                                    oit_error *err)
{
    absorbance_state *s = (absorbance_state *)alg;
    const absorbance_projection *p = &s->projection;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, absorbance_passes_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST); /* every fragment counts, in any order */
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    static const GLfloat zeros[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD); /* every target of both passes: plain sums */
    glBlendFunc(GL_ONE, GL_ONE);

    /* 1. b0 and the projection of the absorbance over depth */
    oit_timer_stage_begin(&s->gpu.timer, p->stage);
    glBindFramebuffer(GL_FRAMEBUFFER, s->projection_framebuffer);
    for (int attachment = 0; attachment < 1 + p->target_count; ++attachment)
        glClearBufferfv(GL_COLOR, attachment, zeros);
    glUseProgram(s->projection_program);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, p->stage, err);

    /* 2. every fragment weighted by the transmittance reconstructed in front of it */
    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "transmittance");
        glBindFramebuffer(GL_FRAMEBUFFER, s->transmittance_framebuffer);
        glClearBufferfv(GL_COLOR, 0, zeros);
        glUseProgram(s->transmittance_program);
        if (p->transmittance_reads_b0)
            absorbance_bind_texture(OIT_TEXUNIT_MBOIT_B0, s->b0);
        for (int t = 0; t < p->target_count; ++t)
            absorbance_bind_texture(p->target_units[t], s->targets[t]);
        oit_gl_draw_scene(scene);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "transmittance", err);
    }
    glDisable(GL_BLEND);

    /* 3. the normalised composite over the background */
    const oit_texture_unit composed[] = {{OIT_TEXUNIT_MBOIT_B0, s->b0}, {OIT_TEXUNIT_MBOIT_ACCUM, s->accumulation}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed, 2, err);
    glActiveTexture(GL_TEXTURE0);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

void absorbance_passes_destroy(oit_algorithm *alg)
{
    absorbance_state *s = (absorbance_state *)alg;
    if (!s)
        return;
    absorbance_release_targets(s);
    oit_gpu_destroy(&s->gpu);
}
