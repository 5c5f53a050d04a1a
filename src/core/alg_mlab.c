/*
 * alg_mlab.c: multi-layer alpha blending (Salvi & Vaidyanathan, "Multi-layer
 * Alpha Blending", I3D 2014). Approximate, one geometry pass, memory fixed by
 * the image size and k.
 *
 * The method: each pixel keeps at most k layers (k = config.layers), sorted
 * front to back, each a premultiplied colour c, a transmittance t, and the
 * sort key of the fragment it started as. A fragment (c = a * colour,
 * t = 1 - a) is inserted in (depth, triangle) order; when the pixel already
 * holds k layers, the last two of the k + 1 are merged into one,
 *     c = c_near + t_near * c_far,   t = t_near * t_far,
 * which keeps the near one's key: exactly what compositing the two would give,
 * but a later fragment that lies between them in depth can no longer go
 * between them. So mlab is exact for every pixel with at most k fragments and
 * approximate past k, where the error depends on the order in which the
 * pixel's fragments arrive (docs/algorithms.md, "mlab").
 *
 * GPU data (layouts in oit_shared.h, GLSL in shaders/mlab/mlab_layers.glsl):
 *   layers      uvec4 per layer, k per pixel, OIT_SSBO_MLAB_LAYERS (16 bytes:
 *               RGB and t at 16 bits, depth bits, triangle)
 *   count       r32ui image, OIT_IMAGE_MLAB_COUNT: fragments the pixel received
 *   lock        r32ui image, OIT_IMAGE_MLAB_LOCK: the pixel's spin lock
 *   counters    uint[OIT_MLAB_COUNTER_COUNT], OIT_SSBO_MLAB_COUNTERS
 * Memory: W x H x (16 k + 4 + 4) bytes, the RGBA8 output (4 per pixel) and the
 * counters; checked against config.max_memory_bytes before anything is allocated.
 *
 * One frame:
 *   clear    count := 0, lock := 0 (free), counters := 0. The layers are not
 *            cleared: only the first min(count, k) are ever read.
 *   insert   geometry pass, depth test and colour writes off: each fragment with
 *            alpha > 0 takes its pixel's lock (imageAtomicCompSwap; there is no
 *            fragment shader interlock on llvmpipe), inserts itself, releases.
 *            A fragment that does not get the lock within OIT_MLAB_LOCK_TRIES
 *            tries is counted, and such a frame is an error, never an image
 *            missing fragments. Insertion is atomic per pixel but happens in
 *            arrival order, not primitive order (see insert.frag and the docs).
 *   resolve  full-screen pass: C += T c_i, T *= t_i front to back, then the
 *            background times T; the RGBA8 output is written once.
 *
 * Statistics: fragments (insert's counter, 64-bit with its wraps), max_list and
 * mean_list (per-pixel counts: fragments received, not layers kept),
 * memory_bytes (the tracker), bytes_per_pixel (everything but the counters).
 * The resolve sums the pixels' counts; a sum that differs from the insert's
 * fragment count means a pixel's lock failed to exclude (an update was lost),
 * and the frame fails.
 */
#include <stdio.h>
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

#define MLAB_MEGABYTE (1024.0 * 1024.0)
/* per pixel: the layers, the count, the lock and the RGBA8 output */
#define MLAB_PIXEL_FIXED_BYTES ((uint64_t)OIT_MLAB_COUNT_BYTES + OIT_MLAB_LOCK_BYTES + 4u)

typedef struct mlab_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    int layers;                  /* k */

    GLuint insert_program;  /* geometry.vert + mlab/insert.frag */
    GLuint resolve_program; /* fullscreen.vert + mlab/resolve.frag */

    GLuint layer_buffer;  /* OIT_SSBO_MLAB_LAYERS */
    GLuint layer_texture; /* buffer texture over it (resolve) */
    GLuint count_image, lock_image;
    GLuint counter_buffer;
    uint64_t gl_layer_limit; /* most layers one SSBO binding and one buffer texture address */
} mlab_state;

static void mlab_release_targets(mlab_state *s)
{
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->count_image);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->lock_image);
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->layer_buffer);
    s->gpu.output.width = s->gpu.output.height = 0;
}

static void mlab_destroy(oit_algorithm *alg);

static oit_status mlab_create(const oit_algorithm_config *config, oit_algorithm **out,
                              oit_error *err)
{
    *out = NULL;
    int layers = config->layers ? config->layers : OIT_APPROX_LAYERS_DEFAULT; /* checked: oit_algorithm_create */
    if (!GLEW_VERSION_4_4 && !GLEW_ARB_clear_texture)
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: needs OpenGL 4.4 or GL_ARB_clear_texture to clear the counts and locks");
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(mlab_state), "mlab", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    mlab_state *s = (mlab_state *)gpu;
    s->layers = layers;

    status = oit_gpu_program(&s->gpu, "common/geometry.vert",
                                       "mlab/insert.frag", &s->insert_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert",
                                "mlab/resolve.frag", &s->resolve_program, err);
    if (status != OIT_OK) {
        mlab_destroy((oit_algorithm *)s);
        return status;
    }
    GLint64 max_block_bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    s->gl_layer_limit = (uint64_t)max_block_bytes / OIT_MLAB_LAYER_BYTES;
    if (s->gl_layer_limit > (uint64_t)max_texels)
        s->gl_layer_limit = (uint64_t)max_texels;
    if (s->gl_layer_limit > 0xFFFFFFFFu)
        s->gl_layer_limit = 0xFFFFFFFFu; /* layer indices are uint in the shaders */

    glGenTextures(1, &s->layer_texture);
    glGenBuffers(1, &s->counter_buffer);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->counter_buffer, OIT_MLAB_COUNTER_COUNT * sizeof(GLuint), NULL,
                              GL_DYNAMIC_READ);
    return oit_gpu_created(&s->gpu, status, mlab_destroy, out, err);
}

static oit_status mlab_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    mlab_state *s = (mlab_state *)alg;
    /* what the image size and k need, before anything is allocated */
    const uint64_t pixels = (uint64_t)width * (uint64_t)height;
    const uint64_t layer_count = pixels * (uint64_t)s->layers;
    const uint64_t needed = layer_count * OIT_MLAB_LAYER_BYTES + pixels * MLAB_PIXEL_FIXED_BYTES +
                            OIT_MLAB_COUNTER_COUNT * sizeof(GLuint);
    if (needed > s->gpu.config.max_memory_bytes)
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: %d layers per pixel at %dx%d need %llu bytes (%.1f MB: %d x %d bytes "
                        "of layers + %d of count, lock and output per pixel), over the --max-memory "
                        "budget of %.1f MB",
                        s->layers, width, height, (unsigned long long)needed,
                        (double)needed / MLAB_MEGABYTE, s->layers, OIT_MLAB_LAYER_BYTES,
                        (int)MLAB_PIXEL_FIXED_BYTES,
                        (double)s->gpu.config.max_memory_bytes / MLAB_MEGABYTE);
    if (layer_count > s->gl_layer_limit)
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: %d layers per pixel at %dx%d are %llu layers, more than this GL can "
                        "address in one shader storage buffer or buffer texture (%llu; "
                        "GL_MAX_SHADER_STORAGE_BLOCK_SIZE, GL_MAX_TEXTURE_BUFFER_SIZE)",
                        s->layers, width, height, (unsigned long long)layer_count,
                        (unsigned long long)s->gl_layer_limit);

    mlab_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;
    while (glGetError() != GL_NO_ERROR) {
    }
    glGenBuffers(1, &s->layer_buffer);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_PIXELS, GL_SHADER_STORAGE_BUFFER,
                              s->layer_buffer, layer_count * OIT_MLAB_LAYER_BYTES, NULL,
                              GL_DYNAMIC_COPY);
    glBindTexture(GL_TEXTURE_BUFFER, s->layer_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32UI, s->layer_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    s->count_image = oit_gpu_target(&s->gpu, GL_R32UI, width, height);
    s->lock_image = oit_gpu_target(&s->gpu, GL_R32UI, width, height);
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        mlab_release_targets(s);
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: could not allocate %d layers per pixel at %dx%d (%.1f MB): GL error "
                        "0x%04x",
                        s->layers, width, height, (double)needed / MLAB_MEGABYTE, (unsigned)error);
    }
    status = oit_gpu_resize_end(&s->gpu, OIT_OK, width, height, err);
    if (status != OIT_OK)
        mlab_release_targets(s);
    return status;
}

static oit_status mlab_render(oit_algorithm *alg, const oit_scene *scene,
                              const oit_frame_settings *frame, oit_error *err)
{
    mlab_state *s = (mlab_state *)alg;
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, mlab_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glBindFramebuffer(GL_FRAMEBUFFER, s->gpu.output.framebuffer);
    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_DEPTH_TEST); /* every fragment is inserted */
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_MLAB_LAYERS, s->layer_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_MLAB_COUNTERS, s->counter_buffer);
    glBindImageTexture(OIT_IMAGE_MLAB_COUNT, s->count_image, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(OIT_IMAGE_MLAB_LOCK, s->lock_image, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_MLAB_LAYERS);
    glBindTexture(GL_TEXTURE_BUFFER, s->layer_texture);
    glActiveTexture(GL_TEXTURE0);

    oit_timer_stage_begin(&s->gpu.timer, "clear");
    const GLuint zero = 0;
    /* tests only: every lock starts taken, as if held by a fragment outside the frame */
    const GLuint lock_start = s->gpu.config.locks_held ? 1u : 0u;
    glClearTexImage(s->count_image, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearTexImage(s->lock_image, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &lock_start);
    const GLuint zeros[OIT_MLAB_COUNTER_COUNT] = {0};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zeros, zeros);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    oit_timer_stage_end(&s->gpu.timer);
    status = oit_gpu_stage_check(&s->gpu, "clear", err);

    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "insert");
        /* the clears land before the insert's image and buffer atomics */
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(s->insert_program);
        glUniform1ui(OIT_UNIFORM_MLAB_LAYERS, (GLuint)s->layers);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        oit_gl_draw_scene(scene);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "insert", err);
    }

    glProgramUniform1ui(s->resolve_program, OIT_UNIFORM_MLAB_LAYERS, (GLuint)s->layers);
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "resolve", s->resolve_program,
                                      GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                                          GL_TEXTURE_FETCH_BARRIER_BIT, NULL, 0, err);

    GLuint counters[OIT_MLAB_COUNTER_COUNT] = {0};
    if (status == OIT_OK) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counters, counters);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    }
    status = oit_gpu_frame_end(&s->gpu, status, err);
    if (status != OIT_OK)
        return status;

    const uint64_t fragments =
        (uint64_t)counters[OIT_MLAB_COUNTER_FRAGMENTS_WRAPS] << 32 | counters[OIT_MLAB_COUNTER_FRAGMENTS];
    if (counters[OIT_MLAB_COUNTER_GAVE_UP] > 0)
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: %u of the frame's %llu fragments gave up waiting for their pixel's "
                        "lock after %d tries each%s; the image would miss them",
                        counters[OIT_MLAB_COUNTER_GAVE_UP], (unsigned long long)fragments,
                        OIT_MLAB_LOCK_TRIES,
                        s->gpu.config.locks_held ? " (config.locks_held: every lock started taken)" : "");
    if (counters[OIT_MLAB_COUNTER_RESOLVED] != counters[OIT_MLAB_COUNTER_FRAGMENTS])
        return oit_fail(err, OIT_E_RUNTIME,
                        "mlab: the pixels' counts sum to %u (mod 2^32) but the insert counted %u: a "
                        "pixel's lock did not exclude another fragment and an update was lost",
                        counters[OIT_MLAB_COUNTER_RESOLVED], counters[OIT_MLAB_COUNTER_FRAGMENTS]);

    const uint64_t non_empty = counters[OIT_MLAB_COUNTER_NONEMPTY_PIXELS];
    s->gpu.stats.fragments = (int64_t)fragments;
    s->gpu.stats.max_list = counters[OIT_MLAB_COUNTER_MAX_LIST];
    s->gpu.stats.mean_list = non_empty ? (double)fragments / (double)non_empty : 0.0;
    return OIT_OK;
}

static void mlab_destroy(oit_algorithm *alg)
{
    mlab_state *s = (mlab_state *)alg;
    if (!s)
        return;
    mlab_release_targets(s);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->layer_texture);
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->counter_buffer);
    oit_gpu_destroy(&s->gpu);
}

static const oit_capabilities mlab_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the distance to the next fragment "
                                              "along the ray, and merged layers no longer know where their "
                                              "fragments were",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("a pixel keeps k merged layers and no link to the adjacent "
                                                      "pixels' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_LAYERS | OIT_OPTION_MAX_MEMORY | OIT_OPTION_LOCKS_HELD,
};

const oit_algorithm_ops oit_algorithm_mlab = {
    .name = "mlab",
    .summary = "multi-layer alpha blending (Salvi & Vaidyanathan 2014): k merged layers per pixel, "
               "approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &mlab_capabilities,
    .create = mlab_create,
    .resize = mlab_resize,
    .render = mlab_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = mlab_destroy,
};
