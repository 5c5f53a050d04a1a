/*
 * closest_layers.c: the k closest layers of every pixel, kept exactly, and a
 * tail for the rest: the machinery of kbuffer (alg_kbuffer.c) and hybrid
 * (alg_hybrid.c), which differ only in the tail.
 *
 * This is the two-pass "atomic loop" k-buffer (Bavoil et al. 2007's k-buffer
 * without read-modify-write hazards, as in NVIDIA's
 * vk_order_independent_transparency "loop" variants). No fragment interlock:
 * every step is one atomic, and the result does not depend on the order in
 * which a pixel's fragments run.
 *
 * GPU data (layouts in oit_shared.h, GLSL in shaders/common/closest_layers.glsl):
 *   slots        uvec4 per pixel and layer (W x H x k), OIT_SSBO_CLOSEST_SLOTS:
 *                key (canonical depth bits), owner (triangle + 1), RGBA16 colour
 *   tail counts  uint per pixel, OIT_SSBO_CLOSEST_TAIL_COUNTS: fragments in the tail
 *   counters     uint[OIT_CLOSEST_COUNTER_COUNT]: core and tail fragments, longest
 *                list, non-empty pixels, list-length histogram
 *   tail targets float textures, the algorithm's (closest_layers_tail)
 *
 * One frame:
 *   clear    slots := (OIT_CLOSEST_EMPTY_KEY, owner 0), tail counts and counters
 *            := 0, tail targets := their clear values.
 *   select   geometry pass, depth test and colour writes off: every fragment with
 *            alpha > 0 inserts its key into its pixel's k keys with the atomicMin
 *            loop (closest_layers_insert): afterwards the keys are the pixel's k
 *            smallest, ascending, ties included.
 *   store    geometry pass, depth test off, blending into the tail targets: each
 *            fragment looks for a slot with its key and claims it with
 *            atomicCompSwap on the owner word, then stores its colour there. A
 *            fragment whose key is past the k-th, or that finds every slot with
 *            its key taken (a tie straddling the k-th place), is the tail: the
 *            store shader blends it into the tail targets (the algorithm's
 *            shader and blend factors); a core fragment adds nothing there.
 *   compose  full-screen pass: sorts the pixel's claimed slots by (key, triangle)
 *            in a local array of OIT_APPROX_LAYERS_MAX, composites them front to
 *            back in float as ll does, puts the tail (as the algorithm's compose
 *            shader resolves it) behind what the core lets through and the background
 *            behind all; writes the RGBA8 output once and counts the list lengths.
 *
 * Exact when k >= the pixel's list length: every fragment is in the core, and
 * the core is ordered by (depth, triangle) as every exact algorithm is.
 *
 * Memory: W x H x (k x OIT_CLOSEST_SLOT_BYTES + OIT_CLOSEST_TAIL_COUNT_BYTES +
 * the tail targets' texels + 4 for the RGBA8 output) + the counters, checked
 * against config.max_memory_bytes before anything is allocated.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "capabilities.h"
#include "closest_layers.h"

const oit_capabilities closest_layers_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "the fragments past the k nearest are blended into a tail with no order",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("a pixel keeps its k nearest fragments and no link to the "
                                                      "adjacent pixels'")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_LAYERS | OIT_OPTION_MAX_MEMORY,
};

_Static_assert(OIT_CLOSEST_HISTOGRAM_BINS == OIT_HISTOGRAM_BINS, "oit_shared.h and oit.h disagree");
_Static_assert(OIT_APPROX_LAYERS_DEFAULT == OIT_LAYERS_DEFAULT && OIT_APPROX_LAYERS_MAX == OIT_LAYERS_MAX,
               "oit_shared.h and oit.h disagree");
_Static_assert(OIT_CLOSEST_COUNTER_HISTOGRAM + OIT_CLOSEST_HISTOGRAM_BINS == OIT_CLOSEST_COUNTER_COUNT,
               "the histogram ends the counters");

#define CLOSEST_LAYERS_MEGABYTE (1024.0 * 1024.0)
#define CLOSEST_LAYERS_OUTPUT_BYTES 4u /* RGBA8 */

typedef struct closest_layers_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    const closest_layers_tail *tail;
    int layers; /* k */

    GLuint select_program;  /* geometry.vert + closest_layers/select.frag */
    GLuint store_program;   /* geometry.vert + tail->store_shader */
    GLuint compose_program; /* fullscreen.vert + tail->compose_shader */

    GLuint slot_buffer, tail_count_buffer, counter_buffer;
    GLuint tail_textures[CLOSEST_LAYERS_MAX_TAIL_TARGETS];
    GLuint tail_framebuffer;
    uint64_t max_block_bytes; /* GL_MAX_SHADER_STORAGE_BLOCK_SIZE */
} closest_layers_state;

static closest_layers_state *closest_from(oit_algorithm *alg) { return (closest_layers_state *)alg; }

/* ------------------------------------------------------------ create */

static void closest_release_targets(closest_layers_state *s)
{
    glDeleteFramebuffers(1, &s->tail_framebuffer);
    s->tail_framebuffer = 0;
    oit_gl_memory_delete_textures(&s->gpu.memory, s->tail->target_count, s->tail_textures);
    GLuint buffers[2] = {s->slot_buffer, s->tail_count_buffer};
    oit_gl_memory_delete_buffers(&s->gpu.memory, 2, buffers);
    s->slot_buffer = s->tail_count_buffer = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

void closest_layers_destroy(oit_algorithm *alg)
{
    closest_layers_state *s = closest_from(alg);
    if (!s)
        return;
    closest_release_targets(s);
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->counter_buffer);
    oit_gpu_destroy(&s->gpu);
}

oit_status closest_layers_create(const closest_layers_tail *tail, const oit_algorithm_config *config,
                                 oit_algorithm **out, oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(closest_layers_state), tail->algorithm, config, &gpu, err);
    if (status != OIT_OK)
        return status;
    closest_layers_state *s = (closest_layers_state *)gpu;
    s->tail = tail;
    s->layers = config->layers ? config->layers : OIT_APPROX_LAYERS_DEFAULT;

    status = oit_gpu_program(gpu, "common/geometry.vert", "closest_layers/select.frag", &s->select_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/geometry.vert", tail->store_shader, &s->store_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(gpu, "common/fullscreen.vert", tail->compose_shader, &s->compose_program, err);
    if (status == OIT_OK) {
        GLint64 max_block_bytes = 0;
        glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
        s->max_block_bytes = max_block_bytes > 0 ? (uint64_t)max_block_bytes : 0;
        glGenBuffers(1, &s->counter_buffer);
        oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                                  s->counter_buffer, OIT_CLOSEST_COUNTER_COUNT * sizeof(GLuint), NULL,
                                  GL_DYNAMIC_READ);
    }
    return oit_gpu_created(&s->gpu, status, closest_layers_destroy, out, err);
}

/* ------------------------------------------------------------ resize */

/* The bytes a frame of width x height holds, by the formula (the tracker
 * records what is then allocated, the same). */
static uint64_t closest_bytes_needed(const closest_layers_state *s, int width, int height)
{
    uint64_t per_pixel = (uint64_t)s->layers * OIT_CLOSEST_SLOT_BYTES + OIT_CLOSEST_TAIL_COUNT_BYTES +
                         CLOSEST_LAYERS_OUTPUT_BYTES;
    for (int t = 0; t < s->tail->target_count; ++t)
        per_pixel += oit_gl_texel_bytes(s->tail->targets[t].format);
    return (uint64_t)width * (uint64_t)height * per_pixel + OIT_CLOSEST_COUNTER_COUNT * sizeof(GLuint);
}

oit_status closest_layers_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    closest_layers_state *s = closest_from(alg);
    const char *name = s->tail->algorithm;
    const uint64_t needed = closest_bytes_needed(s, width, height);
    if (needed > s->gpu.config.max_memory_bytes)
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: %dx%d with k = %d layers needs %llu bytes (%.1f MB), over the --max-memory "
                        "budget of %llu bytes (%.1f MB)",
                        name, width, height, s->layers, (unsigned long long)needed,
                        (double)needed / CLOSEST_LAYERS_MEGABYTE,
                        (unsigned long long)s->gpu.config.max_memory_bytes,
                        (double)s->gpu.config.max_memory_bytes / CLOSEST_LAYERS_MEGABYTE);
    const uint64_t pixels = (uint64_t)width * (uint64_t)height;
    const uint64_t slot_bytes = pixels * (uint64_t)s->layers * OIT_CLOSEST_SLOT_BYTES;
    if (slot_bytes > s->max_block_bytes)
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: %dx%d with k = %d layers needs %llu bytes of slots, more than this GL "
                        "binds as one shader storage block (%llu, GL_MAX_SHADER_STORAGE_BLOCK_SIZE)",
                        name, width, height, s->layers, (unsigned long long)slot_bytes,
                        (unsigned long long)s->max_block_bytes);

    closest_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;
    while (glGetError() != GL_NO_ERROR) {
    }
    GLuint buffers[2];
    glGenBuffers(2, buffers);
    s->slot_buffer = buffers[0];
    s->tail_count_buffer = buffers[1];
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_PIXELS, GL_SHADER_STORAGE_BUFFER, s->slot_buffer,
                              slot_bytes, NULL, GL_DYNAMIC_COPY);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_PIXELS, GL_SHADER_STORAGE_BUFFER,
                              s->tail_count_buffer, pixels * OIT_CLOSEST_TAIL_COUNT_BYTES, NULL,
                              GL_DYNAMIC_COPY);
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        closest_release_targets(s);
        return oit_fail(err, OIT_E_RUNTIME, "%s: could not allocate %llu bytes of slots: GL error 0x%04x",
                        name, (unsigned long long)slot_bytes, (unsigned)error);
    }

    for (int t = 0; t < s->tail->target_count; ++t)
        s->tail_textures[t] = oit_gl_memory_texture_2d(&s->gpu.memory, OIT_GL_MEMORY_PIXELS,
                                                       s->tail->targets[t].format, width, height);
    status = oit_gpu_framebuffer(&s->gpu, &s->tail_framebuffer, "tail", s->tail_textures, s->tail->target_count, 0,
                                 width, height, err);
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        closest_release_targets(s);
    return status;
}

/* ------------------------------------------------------------ render */

static void closest_bind(const closest_layers_state *s, const oit_scene *scene)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_CLOSEST_SLOTS, s->slot_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_CLOSEST_TAIL_COUNTS, s->tail_count_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_CLOSEST_COUNTERS, s->counter_buffer);
}

static void closest_clear(const closest_layers_state *s)
{
    const GLuint empty_slot[4] = {OIT_CLOSEST_EMPTY_KEY, 0u, 0u, 0u};
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->slot_buffer);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, empty_slot);
    const GLuint zero = 0u;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->tail_count_buffer);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, s->tail_framebuffer);
    for (int t = 0; t < s->tail->target_count; ++t)
        glClearBufferfv(GL_COLOR, t, s->tail->targets[t].clear);
    /* the clears must land before the select pass's atomics */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The store pass blends into the tail targets with the tail's factors. */
static void closest_set_tail_blending(const closest_layers_state *s)
{
    glEnable(GL_BLEND);
    for (int t = 0; t < s->tail->target_count; ++t) {
        glBlendEquationi((GLuint)t, GL_FUNC_ADD);
        glBlendFunci((GLuint)t, s->tail->targets[t].source, s->tail->targets[t].destination);
    }
}

static void closest_finish_stats(closest_layers_state *s, oit_stats *stats)
{
    GLuint counters[OIT_CLOSEST_COUNTER_COUNT];
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counters, counters);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    const uint64_t pixels = (uint64_t)s->gpu.output.width * (uint64_t)s->gpu.output.height;
    const uint64_t non_empty = counters[OIT_CLOSEST_COUNTER_NONEMPTY_PIXELS];
    /* every fragment with alpha > 0: those in the core and those in the tail */
    stats->fragments = (int64_t)counters[OIT_CLOSEST_COUNTER_CORE] + counters[OIT_CLOSEST_COUNTER_TAIL];
    stats->max_list = counters[OIT_CLOSEST_COUNTER_MAX_LIST];
    stats->mean_list = non_empty ? (double)stats->fragments / (double)non_empty : 0.0;
    stats->histogram_bins = OIT_HISTOGRAM_BINS;
    stats->list_histogram[0] = pixels - non_empty;
    for (int bin = 1; bin < OIT_HISTOGRAM_BINS; ++bin)
        stats->list_histogram[bin] = counters[OIT_CLOSEST_COUNTER_HISTOGRAM + bin];
}

oit_status closest_layers_render(oit_algorithm *alg, const oit_scene *scene,
                                 const oit_frame_settings *frame, oit_error *err)
{
    closest_layers_state *s = closest_from(alg);
    oit_status status = oit_gpu_frame_begin_sized(&s->gpu, closest_layers_resize, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST); /* every fragment counts, in any order */
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    closest_bind(s, scene);

    oit_timer_stage_begin(&s->gpu.timer, "clear");
    closest_clear(s);
    status = oit_gpu_stage_check(&s->gpu, "clear", err);

    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "select");
        glBindFramebuffer(GL_FRAMEBUFFER, s->gpu.output.framebuffer);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glUseProgram(s->select_program);
        glUniform1i(OIT_UNIFORM_CLOSEST_LAYERS, s->layers);
        oit_gl_draw_scene(scene);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        status = oit_gpu_stage_check(&s->gpu, "select", err);
    }
    if (status == OIT_OK) {
        oit_timer_stage_begin(&s->gpu.timer, "store");
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); /* the keys are final */
        glBindFramebuffer(GL_FRAMEBUFFER, s->tail_framebuffer);
        closest_set_tail_blending(s);
        glUseProgram(s->store_program);
        glUniform1i(OIT_UNIFORM_CLOSEST_LAYERS, s->layers);
        oit_gl_draw_scene(scene);
        glDisable(GL_BLEND);
        status = oit_gpu_stage_check(&s->gpu, "store", err);
    }
    oit_texture_unit tail[CLOSEST_LAYERS_MAX_TAIL_TARGETS];
    for (int t = 0; t < s->tail->target_count; ++t)
        tail[t] = (oit_texture_unit){s->tail->targets[t].texture_unit, s->tail_textures[t]};
    glProgramUniform1i(s->compose_program, OIT_UNIFORM_CLOSEST_LAYERS, s->layers);
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program,
                                      GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                                          GL_FRAMEBUFFER_BARRIER_BIT, tail, s->tail->target_count, err);
    if (status == OIT_OK)
        closest_finish_stats(s, &s->gpu.stats);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

/* ------------------------------------------------------------ the rest */

