/*
 * alg_ll.c: per-pixel linked lists (Yang et al. 2010; thesis 3.1.4 and 4.3.3).
 *
 * GPU data (layouts in oit_shared.h, GLSL declarations in shaders/ll/ll_nodes.glsl):
 *   head image    r32ui, one per pixel, OIT_IMAGE_LIST_HEAD: first node of the pixel's list
 *   nodes         uvec4 per node, OIT_SSBO_FRAGMENT_NODES: colour (RGBA16), depth, triangle
 *   next          uint per node, OIT_SSBO_FRAGMENT_NEXT: the list as the fill built it
 *   sorted next   uint per node, OIT_SSBO_FRAGMENT_SORTED_NEXT: the list front to back
 *   counters      uint[OIT_LL_COUNTER_COUNT], OIT_SSBO_FRAME_COUNTERS: fragments
 *                 needed (and the times that counter wrapped), longest list,
 *                 non-empty pixels, pixels the local array could not hold, psi
 *                 pixels, list-length histogram, fragments sorted
 * The nodes, next and sorted next buffers form the fragment pool; it has room
 * for pool_capacity nodes.
 *
 * One frame:
 *   clear    heads := OIT_LIST_END, counters := 0.
 *   fill     geometry pass, depth test and colour writes off. Each fragment with
 *            alpha > 0 takes a node index from the fragment counter, and only if
 *            the index is inside the pool stores its node and swaps itself into
 *            the pixel's head. The counter counts on past the pool, so after the
 *            pass it is the number of fragments the frame needs: when that is
 *            more than the pool holds, the pool grows (x1.25, within the memory
 *            budget) and clear + fill run again. No fragment is ever dropped:
 *            a frame either has all of them or fails with a message. The count
 *            is 64-bit (the counter and its wraps): past OIT_MAX_FRAME_FRAGMENTS
 *            (32-bit node indices) the frame fails (docs/algorithms.md, Limits).
 *   sort     full-screen pass: sorts each list by (depth, triangle index) into
 *            sorted next and writes the sorted list's first node into the head
 *            image. Afterwards heads + sorted next are the front-to-back lists;
 *            nodes and next are unchanged (what the Illustration Buffer reuses).
 *            Two programs: in-place insertion sort over the lists (thesis
 *            algorithm 10), or insertion sort in a local array of
 *            OIT_LOCAL_ARRAY_CAPACITY that falls back to the in-place sort for
 *            longer lists, so every pixel stays exact. Each pixel is counted
 *            into the list-length histogram (one atomic; the longest list
 *            and the open last bin's fragments as needed): fewer fragments
 *            sorted than stored (a shader loop cut short, as llvmpipe does
 *            after 65535 iterations) fails the frame.
 *   compose  full-screen pass: walks the sorted lists, composites front to back
 *            in float and writes the RGBA8 output once (or shows a buffer view:
 *            heat map, peel limit, layer). The output is cleared to the
 *            background first: sort and compose discard the empty pixels, which
 *            lets llvmpipe skip part of their work (ll_nodes.glsl).
 *
 * Statistics: fragments = fragments stored; overflow_retries = fills repeated
 * in this frame; memory_bytes = output + heads + pool (at its capacity, headroom
 * included) + counters, as allocated: every buffer and texture goes through
 * the tracker s->memory (gl_util.h). bytes_per_fragment = the pool buffers'
 * bytes / pool_capacity, bytes_per_pixel = heads + output / pixels.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* Pool bytes per fragment: the node and its two next pointers. */
#define LL_POOL_BYTES_PER_FRAGMENT ((uint64_t)OIT_LL_NODE_BYTES + 2u * OIT_LL_NEXT_BYTES)
#define LL_DEFAULT_FRAGMENTS_PER_PIXEL 4u
/* Fills per frame: the first plus retries. One retry suffices because a fill's
 * count does not depend on the pool; the rest is a guard against a loop. */
#define LL_MAX_FILLS 3
#define LL_MEGABYTE (1024.0 * 1024.0)

_Static_assert(OIT_LL_HISTOGRAM_BINS == OIT_HISTOGRAM_BINS, "oit_shared.h and oit.h disagree");

enum { LL_PLAIN, LL_GENERAL, LL_VARIANT_COUNT };
static const char *const ll_variant_defines[LL_VARIANT_COUNT] = {
    "#define OIT_VARIANT_DISTANCE 0\n#define OIT_VARIANT_VIEWS 0\n", NULL};

typedef struct ll_state {
    oit_algorithm_config config; /* config.shader_dir points at shader_dir below */
    char *shader_dir;
    oit_gl_output output;
    oit_gl_memory memory; /* every buffer and texture below and the output (gl_util.h) */
    oit_stage_timer timer;

    /* fill and compose in two variants (common/variants.glsl): [LL_PLAIN] the
     * colour image without the distance modulation, compiled at create;
     * [LL_GENERAL] every view and the distance modulation, on first use */
    GLuint fill_programs[LL_VARIANT_COUNT];
    GLuint sort_program; /* the variant config.ll_sort selects */
    GLuint compose_programs[LL_VARIANT_COUNT];

    GLuint head_image;
    GLuint node_buffer, next_buffer, sorted_next_buffer;
    /* buffer-texture views of the three (OIT_TEXUNIT_LL_*): the sort and compose read through them */
    GLuint node_texture, next_texture, sorted_next_texture;
    GLuint counter_buffer;
    uint64_t pool_capacity;  /* nodes the pool holds */
    uint64_t gl_node_limit;  /* most nodes one SSBO binding and one buffer texture can address */

    int64_t overflow_retries_total; /* since create; stats report the last frame's */
    uint32_t long_list_pixels;      /* last frame: pixels the local-array sort could not hold */
    oit_stats last_stats;
} ll_state;

static ll_state *ll_from(oit_algorithm *alg) { return (ll_state *)alg; }
static const ll_state *ll_from_const(const oit_algorithm *alg) { return (const ll_state *)alg; }

/* ------------------------------------------------------------- the pool */

static uint64_t ll_budget_nodes(const ll_state *s)
{
    return s->config.max_memory_bytes / LL_POOL_BYTES_PER_FRAGMENT;
}

static uint64_t ll_node_limit(const ll_state *s)
{
    uint64_t limit = ll_budget_nodes(s);
    if (limit > s->gl_node_limit)
        limit = s->gl_node_limit;
    return limit;
}

/* (Re)specify the three pool buffers for `capacity` nodes. The buffer names stay,
 * so bindings made earlier remain valid; the contents are undefined until the
 * next fill. */
static oit_status ll_allocate_pool(ll_state *s, uint64_t capacity, oit_error *err)
{
    if (capacity == 0)
        capacity = 1; /* zero-sized buffers cannot be bound */
    while (glGetError() != GL_NO_ERROR) {
    }
    const struct {
        GLuint buffer;
        uint64_t bytes;
    } pool[] = {{s->node_buffer, OIT_LL_NODE_BYTES},
                {s->next_buffer, OIT_LL_NEXT_BYTES},
                {s->sorted_next_buffer, OIT_LL_NEXT_BYTES}};
    for (size_t i = 0; i < sizeof pool / sizeof pool[0]; ++i)
        oit_gl_memory_buffer_data(&s->memory, OIT_GL_MEMORY_FRAGMENTS, GL_SHADER_STORAGE_BUFFER,
                                  pool[i].buffer, capacity * pool[i].bytes, NULL, GL_DYNAMIC_COPY);
    const struct {
        GLuint texture, buffer;
        GLenum format;
    } views[] = {{s->node_texture, s->node_buffer, GL_RGBA32UI},
                 {s->next_texture, s->next_buffer, GL_R32UI},
                 {s->sorted_next_texture, s->sorted_next_buffer, GL_R32UI}};
    for (size_t i = 0; i < sizeof views / sizeof views[0]; ++i) {
        glBindTexture(GL_TEXTURE_BUFFER, views[i].texture);
        glTexBuffer(GL_TEXTURE_BUFFER, views[i].format, views[i].buffer);
    }
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        s->pool_capacity = 0;
        return oit_fail(err, OIT_E_RUNTIME,
                        "ll: could not allocate a fragment pool of %llu fragments (%.1f MB): "
                        "GL error 0x%04x",
                        (unsigned long long)capacity,
                        (double)(capacity * LL_POOL_BYTES_PER_FRAGMENT) / LL_MEGABYTE,
                        (unsigned)error);
    }
    s->pool_capacity = capacity;
    return OIT_OK;
}

/* Grow the pool so that `needed` fragments fit, with headroom, or explain why not. */
static oit_status ll_grow_pool(ll_state *s, uint64_t needed, oit_error *err)
{
    if (needed > ll_budget_nodes(s))
        return oit_fail(err, OIT_E_RUNTIME,
                        "ll: the frame needs %llu fragments (%.1f MB), over the --max-memory "
                        "budget of %.1f MB",
                        (unsigned long long)needed,
                        (double)(needed * LL_POOL_BYTES_PER_FRAGMENT) / LL_MEGABYTE,
                        (double)s->config.max_memory_bytes / LL_MEGABYTE);
    if (needed > s->gl_node_limit)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ll: the frame needs %llu fragments, more than this GL can address in "
                        "one shader storage buffer or buffer texture (%llu; "
                        "GL_MAX_SHADER_STORAGE_BLOCK_SIZE, GL_MAX_TEXTURE_BUFFER_SIZE)",
                        (unsigned long long)needed, (unsigned long long)s->gl_node_limit);
    uint64_t capacity = needed + needed / 4; /* headroom, so a camera move rarely refills */
    uint64_t limit = ll_node_limit(s);
    if (capacity > limit)
        capacity = limit;
    return ll_allocate_pool(s, capacity, err);
}

/* --------------------------------------------------------------- create */

static void ll_destroy(oit_algorithm *alg)
{
    ll_state *s = ll_from(alg);
    if (!s)
        return;
    for (int variant = 0; variant < LL_VARIANT_COUNT; ++variant) {
        glDeleteProgram(s->fill_programs[variant]);
        glDeleteProgram(s->compose_programs[variant]);
    }
    glDeleteProgram(s->sort_program);
    GLuint textures[] = {s->head_image, s->node_texture, s->next_texture, s->sorted_next_texture};
    oit_gl_memory_delete_textures(&s->memory, 4, textures);
    GLuint buffers[] = {s->node_buffer, s->next_buffer, s->sorted_next_buffer, s->counter_buffer};
    oit_gl_memory_delete_buffers(&s->memory, 4, buffers);
    oit_gl_output_release(&s->output);
    oit_timer_destroy(&s->timer);
    free(s->shader_dir);
    free(s);
}

/* The fill and compose programs of `variant`, compiled on first use. */
static oit_status ll_programs(ll_state *s, int variant, GLuint *fill, GLuint *compose,
                              oit_error *err)
{
    oit_status status = OIT_OK;
    if (!s->fill_programs[variant])
        status = oit_gl_program_variant(s->shader_dir, "common/geometry.vert", "ll/fill.frag",
                                        ll_variant_defines[variant], &s->fill_programs[variant],
                                        err);
    if (status == OIT_OK && !s->compose_programs[variant])
        status = oit_gl_program_variant(s->shader_dir, "common/fullscreen.vert", "ll/compose.frag",
                                        ll_variant_defines[variant],
                                        &s->compose_programs[variant], err);
    *fill = s->fill_programs[variant];
    *compose = s->compose_programs[variant];
    return status;
}

static oit_status ll_create(const oit_algorithm_config *config, oit_algorithm **out,
                            oit_error *err)
{
    *out = NULL;
    if (!GLEW_VERSION_4_4 && !GLEW_ARB_clear_texture)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ll: needs OpenGL 4.4 or GL_ARB_clear_texture to clear the list heads");
    ll_state *s = calloc(1, sizeof *s);
    if (!s)
        return oit_fail(err, OIT_E_RUNTIME, "ll: out of memory");
    s->config = *config;
    const char *dir = config->shader_dir ? config->shader_dir : ".";
    s->shader_dir = malloc(strlen(dir) + 1);
    if (!s->shader_dir) {
        free(s);
        return oit_fail(err, OIT_E_RUNTIME, "ll: out of memory");
    }
    strcpy(s->shader_dir, dir);
    s->config.shader_dir = s->shader_dir;
    s->output.memory = &s->memory;
    oit_stats_reset(&s->last_stats);
    oit_timer_create(&s->timer);

    const char *sort_shader = config->ll_sort == OIT_LL_SORT_LOCAL_ARRAY
                                  ? "ll/sort_local_array.frag"
                                  : "ll/sort_insertion.frag";
    GLuint unused;
    oit_status status = ll_programs(s, LL_PLAIN, &unused, &unused, err);
    if (status == OIT_OK)
        status = oit_gl_program(s->shader_dir, "common/fullscreen.vert", sort_shader,
                                &s->sort_program, err);
    if (status != OIT_OK) {
        ll_destroy((oit_algorithm *)s);
        return status;
    }

    GLint64 max_block_bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    s->gl_node_limit = (uint64_t)max_block_bytes / OIT_LL_NODE_BYTES;
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    if (s->gl_node_limit > (uint64_t)max_texels)
        s->gl_node_limit = (uint64_t)max_texels;
    if (s->gl_node_limit >= OIT_LIST_END)
        s->gl_node_limit = OIT_LIST_END - 1u; /* node indices are uint, END is reserved */
    GLuint textures[3];
    glGenTextures(3, textures);
    s->node_texture = textures[0];
    s->next_texture = textures[1];
    s->sorted_next_texture = textures[2];

    GLuint buffers[4];
    glGenBuffers(4, buffers);
    s->node_buffer = buffers[0];
    s->next_buffer = buffers[1];
    s->sorted_next_buffer = buffers[2];
    s->counter_buffer = buffers[3];
    oit_gl_memory_buffer_data(&s->memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->counter_buffer, OIT_LL_COUNTER_COUNT * sizeof(GLuint), NULL,
                              GL_DYNAMIC_READ);

    status = oit_gl_check("ll create", err);
    if (status != OIT_OK) {
        ll_destroy((oit_algorithm *)s);
        return status;
    }
    *out = (oit_algorithm *)s;
    return OIT_OK;
}

static oit_status ll_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    ll_state *s = ll_from(alg);
    oit_status status = oit_gl_output_resize(&s->output, width, height, err);
    if (status != OIT_OK)
        return status;
    oit_gl_memory_delete_textures(&s->memory, 1, &s->head_image);
    s->head_image =
        oit_gl_memory_texture_2d(&s->memory, OIT_GL_MEMORY_PIXELS, GL_R32UI, width, height);

    /* The first pool: a few fragments per pixel (or what the config asks for),
     * within the budget. Frames that need more grow it in render(). */
    uint64_t initial = s->config.initial_fragment_capacity
                           ? s->config.initial_fragment_capacity
                           : LL_DEFAULT_FRAGMENTS_PER_PIXEL * (uint64_t)width * (uint64_t)height;
    uint64_t limit = ll_node_limit(s);
    if (initial > limit)
        initial = limit;
    if (s->pool_capacity < initial || s->pool_capacity == 0) {
        status = ll_allocate_pool(s, initial, err);
        if (status != OIT_OK)
            return status;
    }
    return oit_gl_check("ll resize", err);
}

/* --------------------------------------------------------------- render */

static void ll_bind_pool(const ll_state *s)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_NODES, s->node_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_NEXT, s->next_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_SORTED_NEXT,
                     s->sorted_next_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAME_COUNTERS, s->counter_buffer);
    glBindImageTexture(OIT_IMAGE_LIST_HEAD, s->head_image, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_R32UI);
    const struct {
        GLenum unit;
        GLuint texture;
    } views[] = {{OIT_TEXUNIT_LL_NODES, s->node_texture},
                 {OIT_TEXUNIT_LL_NEXT, s->next_texture},
                 {OIT_TEXUNIT_LL_SORTED_NEXT, s->sorted_next_texture}};
    for (size_t i = 0; i < sizeof views / sizeof views[0]; ++i) {
        glActiveTexture(GL_TEXTURE0 + views[i].unit);
        glBindTexture(GL_TEXTURE_BUFFER, views[i].texture);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* ll shows the colour image and the list views; the rest is the Illustration
 * Buffer's (ib). */
static oit_status ll_check_view(const oit_modulation *modulation, oit_error *err)
{
    if (modulation->view != OIT_VIEW_COLOUR && modulation->view != OIT_VIEW_HEATMAP &&
        modulation->view != OIT_VIEW_PEEL_LIMIT && modulation->view != OIT_VIEW_LAYER)
        return oit_fail(err, OIT_E_INPUT,
                        "ll: view '%s' is not supported (colour, heatmap, peel limit and layer only)",
                        oit_view_name(modulation->view));
    if (modulation->mode != OIT_MODULATE_NONE && modulation->mode != OIT_MODULATE_DISTANCE)
        return oit_fail(err, OIT_E_INPUT,
                        "ll: opacity modulation '%s' needs surface neighbours (ib only): a pixel's "
                        "list has no link to the adjacent pixels' lists, which are sorted only "
                        "inside their own compose invocation; ll does the local ones and the "
                        "distance",
                        oit_modulation_mode_name(modulation->mode));
    return OIT_OK;
}

/* In debug mode, check for GL errors after each stage. */
static oit_status ll_check(const ll_state *s, const char *stage, oit_error *err)
{
    if (s->timer.cancelled)
        return oit_timer_status(&s->timer, err);
    return s->config.debug ? oit_gl_check(stage, err) : OIT_OK;
}

/* Clear heads and counters, then draw every fragment into the lists. */
static void ll_clear_and_fill(ll_state *s, GLuint fill_program, const oit_scene *scene,
                              const oit_frame_settings *frame, int retry)
{
    oit_timer_stage_begin(&s->timer, retry ? "clear_retry" : "clear");
    const GLuint list_end = OIT_LIST_END;
    glClearTexImage(s->head_image, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &list_end);
    GLuint zeros[OIT_LL_COUNTER_COUNT] = {0};
    zeros[OIT_FRAME_COUNTER_FRAGMENTS] = s->config.fragment_counter_start; /* 0 but in tests */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zeros, zeros);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    /* the clears must land before the fill's image and buffer atomics */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);

    oit_timer_stage_begin(&s->timer, retry ? "fill_retry" : "fill");
    glUseProgram(fill_program);
    oit_gl_set_frame_uniforms(frame);
    glUniform1ui(OIT_UNIFORM_LL_POOL_CAPACITY, (GLuint)s->pool_capacity);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->timer);
}

static oit_status ll_render(oit_algorithm *alg, const oit_scene *scene,
                            const oit_frame_settings *frame, oit_error *err)
{
    ll_state *s = ll_from(alg);
    oit_status status;
    if (!scene->has_gpu)
        return oit_fail(err, OIT_E_INPUT, "ll: the scene has not been uploaded to the GPU");
    status = ll_check_view(&frame->modulation, err);
    if (status != OIT_OK)
        return status;
    if (frame->width != s->output.width || frame->height != s->output.height ||
        !s->head_image) {
        status = ll_resize(alg, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }

    /* the plain variant unless the frame needs a view or the distance modulation */
    GLuint fill_program, compose_program;
    status = ll_programs(s,
                         frame->modulation.view == OIT_VIEW_COLOUR &&
                                 frame->modulation.mode != OIT_MODULATE_DISTANCE
                             ? LL_PLAIN
                             : LL_GENERAL,
                         &fill_program, &compose_program, err);
    if (status != OIT_OK)
        return status;

    oit_stats stats;
    oit_stats_reset(&stats);
    oit_timer_frame_begin(&s->timer, frame);
    oit_gl_bind_part_alpha(scene, frame); /* per-part opacity, every part */

    glBindFramebuffer(GL_FRAMEBUFFER, s->output.framebuffer);
    glViewport(0, 0, s->output.width, s->output.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    ll_bind_pool(s);

    /* Fill until the pool holds the whole frame. */
    int retries = 0;
    uint64_t needed = 0;
    for (;;) {
        ll_clear_and_fill(s, fill_program, scene, frame, retries);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        /* the fill's 64-bit count: the counter and the times it wrapped */
        GLuint low = 0, wraps = 0;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, OIT_FRAME_COUNTER_FRAGMENTS * sizeof(GLuint),
                           sizeof low, &low);
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, OIT_LL_COUNTER_FRAGMENTS_WRAPS * sizeof(GLuint),
                           sizeof wraps, &wraps);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
        needed = (uint64_t)wraps << 32 | low;
        status = ll_check(s, "ll fill", err);
        if (status != OIT_OK)
            goto failed;
        status = oit_gl_check_frame_fragments("ll", needed, s->config.fragment_counter_start, err);
        if (status != OIT_OK)
            goto failed;
        if (needed <= s->pool_capacity)
            break;
        if (retries + 1 >= LL_MAX_FILLS) {
            status = oit_fail(err, OIT_E_RUNTIME,
                              "ll: the frame still needs %llu fragments after growing the pool to "
                              "%llu",
                              (unsigned long long)needed, (unsigned long long)s->pool_capacity);
            goto failed;
        }
        status = ll_grow_pool(s, needed, err);
        if (status != OIT_OK)
            goto failed;
        ++retries;
    }

    oit_timer_stage_begin(&s->timer, "sort");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(s->sort_program);
    oit_gl_draw_fullscreen(&s->output); /* colour writes are still off */
    status = ll_check(s, "ll sort", err);
    if (status != OIT_OK)
        goto failed;

    /* The distance modulation with an automatic region: the frame's largest
     * distance first (one more full-screen pass over the sorted lists). */
    const bool distance = frame->modulation.mode == OIT_MODULATE_DISTANCE;
    const bool auto_region = distance && !(frame->modulation.focus_region > 0.0f);
    if (auto_region) {
        oit_timer_stage_begin(&s->timer, "distance_max");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
        glUseProgram(compose_program);
        oit_gl_set_frame_uniforms(frame);
        glUniform1i(OIT_UNIFORM_LL_VIEW, (GLint)frame->modulation.view);
        glUniform1i(OIT_UNIFORM_LL_VIEW_PARAMETER, frame->modulation.view_parameter);
        glUniform1i(OIT_UNIFORM_LL_DISTANCE_PASS, 1);
        oit_gl_draw_fullscreen(&s->output); /* colour writes are still off */
        status = ll_check(s, "ll distance_max", err);
        if (status != OIT_OK)
            goto failed;
    }

    oit_timer_stage_begin(&s->timer, "compose");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(compose_program);
    oit_gl_set_frame_uniforms(frame);
    glUniform1i(OIT_UNIFORM_LL_DISTANCE_PASS, auto_region ? 2 : 0);
    glUniform1i(OIT_UNIFORM_LL_VIEW, (GLint)frame->modulation.view); /* numbers of OIT_LL_VIEW_* */
    glUniform1i(OIT_UNIFORM_LL_VIEW_PARAMETER, frame->modulation.view_parameter);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    /* compose discards the empty pixels (LL_EMPTY_PIXEL_DISCARD in ll_nodes.glsl): they keep this */
    glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    oit_gl_draw_fullscreen(&s->output);
    oit_timer_stage_end(&s->timer);
    status = ll_check(s, "ll compose", err);
    if (status != OIT_OK)
        goto failed;

    /* The figures the sort pass counted; reading them waits for it, which
     * the timer does anyway. */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counters[OIT_LL_COUNTER_COUNT];
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counters, counters);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glUseProgram(0);
    oit_timer_frame_end(&s->timer, &stats);
    /* The sort counts each pixel in the histogram only (ll_finish_sort in
     * ll_nodes.glsl): non-empty pixels, fragments sorted and psi come from it;
     * lists in the open last bin have their own fragment sum and psi count. */
    const int open_bin = OIT_HISTOGRAM_BINS - 1;
    const uint64_t longest = counters[OIT_FRAME_COUNTER_MAX_LIST];
    uint64_t non_empty = 0, sorted = counters[OIT_LL_COUNTER_SORTED_FRAGMENTS], psi_pixels = 0;
    for (uint64_t bin = 1; bin < OIT_HISTOGRAM_BINS; ++bin) {
        const uint64_t bin_pixels = counters[OIT_LL_COUNTER_HISTOGRAM + bin];
        non_empty += bin_pixels;
        if (bin < (uint64_t)open_bin) {
            sorted += bin * bin_pixels;
            if (3 * bin > 2 * longest)
                psi_pixels += bin_pixels;
        }
    }
    if (longest >= (uint64_t)open_bin)
        psi_pixels = counters[OIT_LL_COUNTER_PSI_PIXELS]; /* compose counted them */
    /* the fill stored nodes fragment_counter_start..needed - 1 (0 but in tests) */
    status = oit_gl_check_sorted_fragments("ll", needed - s->config.fragment_counter_start, sorted,
                                           err);
    if (status != OIT_OK)
        return status;

    s->overflow_retries_total += retries;
    s->long_list_pixels = counters[OIT_FRAME_COUNTER_LONG_LIST_PIXELS];
    stats.fragments = counters[OIT_FRAME_COUNTER_FRAGMENTS];
    stats.max_list = counters[OIT_FRAME_COUNTER_MAX_LIST];
    stats.overflow_retries = retries; /* this frame's */
    const uint64_t pixels = (uint64_t)s->output.width * (uint64_t)s->output.height;
    stats.mean_list = non_empty ? (double)stats.fragments / (double)non_empty : 0.0;
    stats.psi = non_empty ? (double)psi_pixels / (double)non_empty : 0.0;
    stats.histogram_bins = OIT_HISTOGRAM_BINS;
    stats.list_histogram[0] = pixels - non_empty;
    for (int bin = 1; bin < OIT_HISTOGRAM_BINS; ++bin)
        stats.list_histogram[bin] = counters[OIT_LL_COUNTER_HISTOGRAM + bin];
    /* the figures of what is allocated (oit_stats in oit.h defines them) */
    stats.memory_bytes = oit_gl_memory_total(&s->memory);
    stats.bytes_per_fragment = (double)oit_gl_memory_bytes(&s->memory, OIT_GL_MEMORY_FRAGMENTS) /
                               (double)s->pool_capacity;
    stats.bytes_per_pixel =
        (double)oit_gl_memory_bytes(&s->memory, OIT_GL_MEMORY_PIXELS) / (double)pixels;
    s->last_stats = stats;
    return oit_gl_check("ll render", err);

failed:
    oit_timer_stage_end(&s->timer);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glUseProgram(0);
    return status;
}

static oit_status ll_read_image(oit_algorithm *alg, oit_image *out, oit_error *err)
{
    return oit_gl_output_read(&ll_from(alg)->output, out, err);
}

static void ll_stats(const oit_algorithm *alg, oit_stats *out)
{
    *out = ll_from_const(alg)->last_stats;
}

const oit_algorithm_ops oit_algorithm_ll = {
    .name = "ll",
    .summary = "per-pixel linked lists: one geometry pass, then sort and compose per pixel",
    .uses_gl = true,
    .exact = true,
    .create = ll_create,
    .resize = ll_resize,
    .render = ll_render,
    .read_image = ll_read_image,
    .stats = ll_stats,
    .destroy = ll_destroy,
};
