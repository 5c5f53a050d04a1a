/*
 * alg_mboit.c: moment-based order-independent transparency (Muenstermann,
 * Krumpen, Klein & Peters, "Moment-Based Order-Independent Transparency",
 * Proc. ACM CGIT 1(1), i3D 2018). Approximate, two additive geometry passes
 * and a resolve, constant memory per pixel.
 *
 * The transmittance in front of a fragment, prod (1 - a) over the fragments
 * in front, is the exponential of minus the absorbance, a sum of optical
 * depths -ln(1 - a): additive, so the moments of its distribution over depth
 * can be summed in any order. config.moments picks which moments
 * (shaders/mboit/common.glsl has the equations, E1..E5):
 *   power4 (the default): b0 and 4 power moments of the depth warped to [-1, 1]
 *   power6: b0 and 6 power moments
 *   trig3:  b0 and 3 trigonometric (complex) moments of the depth as a phase
 * 1. "moments": depth test off, additive blending; every fragment adds its
 *    optical depth (opacity clamped below 1) into b0 (R32F) and that times its
 *    moment vector into an RGBA32F target (moments 1..4) and, for power6 and
 *    trig3, an RG32F one (moments 5, 6 / the third complex moment).
 * 2. "transmittance": depth test off, additive blending; every fragment
 *    reconstructs T, the transmittance in front of its depth, from its pixel's
 *    moments (the bounds of the Hamburger problem for power moments, of the
 *    trigonometric problem for trig3, biased and interpolated between the
 *    bounds by the overestimation, as the paper) and adds (T a c, T a) into an
 *    RGBA32F target.
 * 3. "compose": C = (sum T a c) / (sum T a) * (1 - exp(-b0)) + background *
 *    exp(-b0), the paper's normalisation: the coverage 1 - exp(-b0) is exact.
 * Memory per pixel: power4 4 + 16 + 16 + 4 (output) = 40 bytes; power6 and
 * trig3 8 more (the RG32F target): 48.
 */
#include <stdio.h>
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

typedef struct mboit_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    oit_moments moments; /* config.moments resolved: never OIT_MOMENTS_DEFAULT */

    GLuint moments_program;       /* geometry.vert + mboit/moments.frag, MBOIT_VARIANT */
    GLuint transmittance_program; /* geometry.vert + mboit/transmittance.frag, MBOIT_VARIANT */
    GLuint compose_program;       /* fullscreen.vert + mboit/compose.frag */

    GLuint b0;           /* GL_R32F: sum of optical depths */
    GLuint moment_sums;  /* GL_RGBA32F: moments 1..4 (trig3: re, im of moments 1, 2) */
    GLuint extra_sums;   /* GL_RG32F: power6 moments 5, 6; trig3 moment 3; 0 for power4 */
    GLuint accumulation; /* GL_RGBA32F: (sum T a c, sum T a) */
    GLuint moments_framebuffer;       /* attachments OIT_MBOIT_TARGET_* */
    GLuint transmittance_framebuffer; /* attachment 0: accumulation */
} mboit_state;

/* The moments other than power4 need the third target. */
static bool mboit_has_extra(oit_moments moments)
{
    return moments != OIT_MOMENTS_POWER4;
}

static void mboit_release_targets(mboit_state *s)
{
    glDeleteFramebuffers(1, &s->moments_framebuffer);
    glDeleteFramebuffers(1, &s->transmittance_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->b0);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->moment_sums);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->extra_sums);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    s->moments_framebuffer = s->transmittance_framebuffer = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

static void mboit_destroy(oit_algorithm *alg);

static oit_status mboit_create(const oit_algorithm_config *config, oit_algorithm **out,
                               oit_error *err)
{
    *out = NULL;
    /* checked: oit_algorithm_create */
    oit_moments moments = config->moments == OIT_MOMENTS_DEFAULT ? OIT_MOMENTS_POWER4 : config->moments;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(mboit_state), "mboit", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    mboit_state *s = (mboit_state *)gpu;
    s->moments = moments;

    /* the shaders' variant: OIT_MBOIT_POWER4, _POWER6 or _TRIG3 (oit_shared.h) */
    const int variant = moments == OIT_MOMENTS_POWER4   ? OIT_MBOIT_POWER4
                        : moments == OIT_MOMENTS_POWER6 ? OIT_MBOIT_POWER6
                                                        : OIT_MBOIT_TRIG3;
    char defines[64];
    snprintf(defines, sizeof defines, "#define MBOIT_VARIANT %d\n", variant);
    status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "mboit/moments.frag", defines,
                                     &s->moments_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "mboit/transmittance.frag",
                                         defines, &s->transmittance_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "mboit/compose.frag",
                                &s->compose_program, err);
    return oit_gpu_created(&s->gpu, status, mboit_destroy, out, err);
}

/* A framebuffer over count colour textures (attachment i = textures[i]). */
static oit_status mboit_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    mboit_state *s = (mboit_state *)alg;
    mboit_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    const oit_gl_memory_use pixels = OIT_GL_MEMORY_PIXELS;
    s->b0 = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_R32F, width, height);
    s->moment_sums = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RGBA32F, width, height);
    if (mboit_has_extra(s->moments))
        s->extra_sums = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RG32F, width, height);
    s->accumulation = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RGBA32F, width, height);

    GLuint targets[3];
    targets[OIT_MBOIT_TARGET_B0] = s->b0;
    targets[OIT_MBOIT_TARGET_MOMENTS] = s->moment_sums;
    targets[OIT_MBOIT_TARGET_EXTRA] = s->extra_sums;
    status = oit_gpu_framebuffer(&s->gpu, &s->moments_framebuffer, "moments", targets,
                                 mboit_has_extra(s->moments) ? 3 : 2, 0, width, height, err);
    if (status == OIT_OK)
        status = oit_gpu_framebuffer(&s->gpu, &s->transmittance_framebuffer, "transmittance", &s->accumulation, 1,
                                     0, width, height, err);
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        mboit_release_targets(s);
    return status;
}

static void mboit_bind_texture(GLenum unit, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, texture);
}

static oit_status mboit_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err)
{
    mboit_state *s = (mboit_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, mboit_resize, scene, frame, err);
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

    /* 1. the moments of the optical depth over depth */
    oit_timer_stage_begin(&s->gpu.timer, "moments");
    glBindFramebuffer(GL_FRAMEBUFFER, s->moments_framebuffer);
    glClearBufferfv(GL_COLOR, OIT_MBOIT_TARGET_B0, zeros);
    glClearBufferfv(GL_COLOR, OIT_MBOIT_TARGET_MOMENTS, zeros);
    if (mboit_has_extra(s->moments))
        glClearBufferfv(GL_COLOR, OIT_MBOIT_TARGET_EXTRA, zeros);
    glUseProgram(s->moments_program);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, "moments", err);

    /* 2. every fragment weighted by the transmittance reconstructed in front of it */
    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "transmittance");
        glBindFramebuffer(GL_FRAMEBUFFER, s->transmittance_framebuffer);
        glClearBufferfv(GL_COLOR, 0, zeros);
        glUseProgram(s->transmittance_program);
        mboit_bind_texture(OIT_TEXUNIT_MBOIT_B0, s->b0);
        mboit_bind_texture(OIT_TEXUNIT_MBOIT_MOMENTS, s->moment_sums);
        if (mboit_has_extra(s->moments))
            mboit_bind_texture(OIT_TEXUNIT_MBOIT_EXTRA, s->extra_sums);
        oit_gl_draw_scene(scene);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "transmittance", err);
    }
    glDisable(GL_BLEND);

    /* 3. the normalised composite over the background */
    const oit_texture_unit composed[] = {{OIT_TEXUNIT_MBOIT_B0, s->b0},
                                         {OIT_TEXUNIT_MBOIT_ACCUM, s->accumulation}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed,
                                      2, err);
    glActiveTexture(GL_TEXTURE0);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static void mboit_destroy(oit_algorithm *alg)
{
    mboit_state *s = (mboit_state *)alg;
    if (!s)
        return;
    mboit_release_targets(s);
    oit_gpu_destroy(&s->gpu);
}

static const oit_capabilities mboit_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "moment-based OIT keeps only moments of the depths, not the fragments",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("moment-based OIT keeps no fragment, so no pixel sees its "
                                                      "neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_MOMENTS,
};

const oit_algorithm_ops oit_algorithm_mboit = {
    .name = "mboit",
    .summary = "moment-based OIT (Muenstermann et al. 2018): two additive passes, approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &mboit_capabilities,
    .create = mboit_create,
    .resize = mboit_resize,
    .render = mboit_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = mboit_destroy,
};
