/*
 * alg_wavelet.c: wavelet transparency (Aizenshtein, Smal & McGuire, "Wavelet
 * Transparency", 2022). Approximate, two additive geometry passes and a
 * resolve, constant memory per pixel: mboit's shape with another basis.
 *
 * The absorbance in front of a depth, A(z) = sum over the fragments in front
 * of -ln(1 - a), is a sum of steps, one per fragment; its projection onto a
 * Haar basis of rank R (config.wavelet_rank, --wavelet-rank; N = 2^(R+1)
 * coefficients: the scaling function and the wavelets of levels 0..R) is
 * linear in it, so every fragment adds its own step's coefficients, in any
 * order (shaders/wavelet/common.glsl has the equations, W1..W5).
 * 1. "coefficients": depth test off, additive blending; every fragment adds its
 *    optical depth (opacity clamped below 1, common/optical_depth.glsl, shared
 *    with mboit) into b0 (R32F) and its step's N coefficients into N / 4
 *    RGBA32F targets (the depth: the canonical depth in [0, 1], mboit's).
 * 2. "transmittance": depth test off, additive blending; every fragment reads
 *    its pixel's coefficients, subtracts its own step's (a fragment is not in
 *    front of itself; a public implementation of the method, Flywheel's GLSL,
 *    removes the fragment's own signal the same way), reconstructs the absorbance in front of its depth
 *    (the projection's bin means, interpolated from the previous bin's at the
 *    start of its bin to its own bin's at the end) and adds (T a c, T a) into
 *    an RGBA32F target.
 * 3. "compose": mboit's (mboit/compose.frag, the same program source): C =
 *    (sum T a c) / (sum T a) * (1 - exp(-b0)) + background * exp(-b0).
 * Memory per pixel: 4 (b0) + 4 N (coefficients) + 16 (accumulation) + 4
 * (output) = 24 + 2^(R+3) bytes: rank 1 40, rank 2 56, rank 3 (the default) 88.
 * The C side shares mboit's passes in kind but not its targets, so it is its
 * own (the GL calls are gpu_algorithm.c's, shared by all).
 */
#include <stdio.h>
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"
#include "oit_shared.h"

_Static_assert(OIT_WAVELET_RANK_MAX == 3, "oit.h's OIT_WAVELET_RANK_MAX and oit_shared.h's differ");
_Static_assert(OIT_WAVELET_RANK_DEFAULT >= 1 && OIT_WAVELET_RANK_DEFAULT <= OIT_WAVELET_RANK_MAX,
               "the default rank is outside 1..OIT_WAVELET_RANK_MAX");

/* the coefficient targets at the highest rank: 2^(R+1) / 4 */
#define WAVELET_TARGETS_MAX ((2 << OIT_WAVELET_RANK_MAX) / 4)

typedef struct wavelet_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    int rank;              /* config.wavelet_rank resolved: 1..OIT_WAVELET_RANK_MAX */
    int targets;           /* coefficient targets: 2^(rank+1) / 4 */

    GLuint coefficients_program;  /* geometry.vert + wavelet/coefficients.frag, WAVELET_RANK */
    GLuint transmittance_program; /* geometry.vert + wavelet/transmittance.frag, WAVELET_RANK */
    GLuint compose_program;       /* fullscreen.vert + mboit/compose.frag */

    GLuint b0;                                /* GL_R32F: sum of optical depths */
    GLuint coefficients[WAVELET_TARGETS_MAX]; /* GL_RGBA32F: coefficients 4t..4t+3 */
    GLuint accumulation;                      /* GL_RGBA32F: (sum T a c, sum T a) */
    GLuint coefficients_framebuffer;          /* b0, then the coefficient targets */
    GLuint transmittance_framebuffer;         /* attachment 0: accumulation */
} wavelet_state;

static void wavelet_release_targets(wavelet_state *s)
{
    glDeleteFramebuffers(1, &s->coefficients_framebuffer);
    glDeleteFramebuffers(1, &s->transmittance_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->b0);
    oit_gl_memory_delete_textures(&s->gpu.memory, WAVELET_TARGETS_MAX, s->coefficients);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    s->coefficients_framebuffer = s->transmittance_framebuffer = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

static void wavelet_destroy(oit_algorithm *alg);

static oit_status wavelet_create(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err)
{
    *out = NULL;
    /* checked: oit_algorithm_create */
    int rank = config->wavelet_rank == 0 ? OIT_WAVELET_RANK_DEFAULT : config->wavelet_rank;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(wavelet_state), "wavelet", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    wavelet_state *s = (wavelet_state *)gpu;
    s->rank = rank;
    s->targets = (2 << rank) / 4;

    char defines[64];
    snprintf(defines, sizeof defines, "#define WAVELET_RANK %d\n", rank);
    status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "wavelet/coefficients.frag", defines,
                                     &s->coefficients_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "wavelet/transmittance.frag", defines,
                                         &s->transmittance_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "mboit/compose.frag", &s->compose_program,
                                 err);
    return oit_gpu_created(&s->gpu, status, wavelet_destroy, out, err);
}

static oit_status wavelet_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    wavelet_state *s = (wavelet_state *)alg;
    wavelet_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    const oit_gl_memory_use pixels = OIT_GL_MEMORY_PIXELS;
    GLuint targets[1 + WAVELET_TARGETS_MAX];
    s->b0 = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_R32F, width, height);
    targets[OIT_WAVELET_TARGET_B0] = s->b0;
    for (int t = 0; t < s->targets; ++t) {
        s->coefficients[t] = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RGBA32F, width, height);
        targets[OIT_WAVELET_TARGET_COEFFICIENTS + t] = s->coefficients[t];
    }
    s->accumulation = oit_gl_memory_texture_2d(&s->gpu.memory, pixels, GL_RGBA32F, width, height);

    status = oit_gpu_framebuffer(&s->gpu, &s->coefficients_framebuffer, "coefficients", targets, 1 + s->targets, 0,
                                 width, height, err);
    if (status == OIT_OK)
        status = oit_gpu_framebuffer(&s->gpu, &s->transmittance_framebuffer, "transmittance", &s->accumulation, 1,
                                     0, width, height, err);
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        wavelet_release_targets(s);
    return status;
}

static void wavelet_bind_texture(GLenum unit, GLuint texture)
{
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, texture);
}

static oit_status wavelet_render(oit_algorithm *alg, const oit_scene *scene, const oit_frame_settings *frame,
                                 oit_error *err)
{
    wavelet_state *s = (wavelet_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, wavelet_resize, scene, frame, err);
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

    /* 1. the Haar coefficients of the absorbance over depth, and b0 */
    oit_timer_stage_begin(&s->gpu.timer, "coefficients");
    glBindFramebuffer(GL_FRAMEBUFFER, s->coefficients_framebuffer);
    for (int target = 0; target < 1 + s->targets; ++target)
        glClearBufferfv(GL_COLOR, target, zeros);
    glUseProgram(s->coefficients_program);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, "coefficients", err);

    /* 2. every fragment weighted by the transmittance reconstructed in front of it */
    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "transmittance");
        glBindFramebuffer(GL_FRAMEBUFFER, s->transmittance_framebuffer);
        glClearBufferfv(GL_COLOR, 0, zeros);
        glUseProgram(s->transmittance_program);
        for (int t = 0; t < s->targets; ++t)
            wavelet_bind_texture(OIT_TEXUNIT_WAVELET_COEFFICIENTS + (GLenum)t, s->coefficients[t]);
        oit_gl_draw_scene(scene);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "transmittance", err);
    }
    glDisable(GL_BLEND);

    /* 3. the normalised composite over the background (mboit's) */
    const oit_texture_unit composed[] = {{OIT_TEXUNIT_MBOIT_B0, s->b0}, {OIT_TEXUNIT_MBOIT_ACCUM, s->accumulation}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed, 2, err);
    glActiveTexture(GL_TEXTURE0);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static void wavelet_destroy(oit_algorithm *alg)
{
    wavelet_state *s = (wavelet_state *)alg;
    if (!s)
        return;
    wavelet_release_targets(s);
    oit_gpu_destroy(&s->gpu);
}

static const oit_capabilities wavelet_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "wavelet transparency keeps only Haar coefficients of the absorbance, "
                                              "not the fragments",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("wavelet transparency keeps no fragment, so no pixel sees its "
                                                      "neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_WAVELET_RANK,
};

const oit_algorithm_ops oit_algorithm_wavelet = {
    .name = "wavelet",
    .summary = "wavelet transparency (Aizenshtein et al. 2022): Haar-projected absorbance, two additive passes, "
               "approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &wavelet_capabilities,
    .create = wavelet_create,
    .resize = wavelet_resize,
    .render = wavelet_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = wavelet_destroy,
};
