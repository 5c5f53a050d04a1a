/*
 * alg_ll.c: per-pixel linked lists (Yang et al. 2010; thesis 3.1.4 and 4.3.3).
 *
 * The lists are a family (linked_lists.h): everything below but the last pass
 * is shared with adaptive (alg_adaptive.c), whose member sorts each list into
 * primitive order and resolves it with its own shader; "compose" below is
 * ll's resolve, and the messages name the member.
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
 * the tracker s->gpu.memory (gl_util.h). bytes_per_fragment = the pool buffers'
 * bytes / pool_capacity, bytes_per_pixel = heads + output / pixels.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bands.h"
#include "capabilities.h"
#include "fragment_pool.h"
#include "gpu_algorithm.h"
#include "linked_lists.h"

/* The pool's buffers: the node and its two next pointers per fragment. */
enum { LL_NODES, LL_NEXT, LL_SORTED_NEXT, LL_POOL_BUFFERS };
#define LL_DEFAULT_FRAGMENTS_PER_PIXEL 4u
/* Fills per frame: the first plus retries. One retry suffices because a fill's
 * count does not depend on the pool; the rest is a guard against a loop. */
#define LL_MAX_FILLS 3

_Static_assert(OIT_LL_HISTOGRAM_BINS == OIT_HISTOGRAM_BINS, "oit_shared.h and oit.h disagree");

enum { LL_PLAIN, LL_GENERAL, LL_VARIANT_COUNT };
static const char *const ll_variant_defines[LL_VARIANT_COUNT] = {
    "#define OIT_VARIANT_DISTANCE 0\n#define OIT_VARIANT_VIEWS 0\n", NULL};

typedef struct ll_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    const linked_lists_resolve *resolve; /* the member: ll's own, or adaptive's (linked_lists.h) */
    char resolve_defines[LL_VARIANT_COUNT][160]; /* the variants' defines and the member's */

    /* fill and compose in two variants (common/variants.glsl): [LL_PLAIN] the
     * colour image without the distance modulation, compiled at create;
     * [LL_GENERAL] every view and the distance modulation, on first use */
    GLuint fill_programs[LL_VARIANT_COUNT];
    GLuint sort_program; /* the variant config.ll_sort selects */
    GLuint compose_programs[LL_VARIANT_COUNT];

    GLuint head_image;
    /* the nodes, the fill's next pointers and the sort's, and buffer-texture
     * views of the three (OIT_TEXUNIT_LL_*) the sort and compose read through */
    oit_fragment_pool pool;
    GLuint counter_buffer;
    /* the bands of rows the last frame was drawn in (count 0: it was whole): the next
     * frame at the size starts from them instead of from a fill that only counts */
    oit_band_plan band_plan;

    int64_t overflow_retries_total; /* since create; stats report the last frame's */
    uint32_t long_list_pixels;      /* last frame: pixels the local-array sort could not hold */
} ll_state;

static ll_state *ll_from(oit_algorithm *alg) { return (ll_state *)alg; }

/* --------------------------------------------------------------- create */

void linked_lists_destroy(oit_algorithm *alg)
{
    ll_state *s = ll_from(alg);
    if (!s)
        return;
    oit_band_plan_free(&s->band_plan);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->head_image);
    oit_gl_memory_delete_textures(&s->gpu.memory, LL_POOL_BUFFERS, s->pool.views);
    oit_gl_memory_delete_buffers(&s->gpu.memory, LL_POOL_BUFFERS, s->pool.buffers);
    oit_gl_memory_delete_buffers(&s->gpu.memory, 1, &s->counter_buffer);
    oit_gpu_destroy(&s->gpu);
}

/* The fill and compose programs of `variant`, compiled on first use. */
static oit_status ll_programs(ll_state *s, int variant, GLuint *fill, GLuint *compose,
                              oit_error *err)
{
    oit_status status = OIT_OK;
    if (!s->fill_programs[variant])
        status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "ll/fill.frag",
                                        ll_variant_defines[variant], &s->fill_programs[variant],
                                        err);
    if (status == OIT_OK && !s->compose_programs[variant])
        status = oit_gpu_program_variant(&s->gpu, "common/fullscreen.vert", s->resolve->resolve_shader,
                                        s->resolve_defines[variant][0] ? s->resolve_defines[variant] : NULL,
                                        &s->compose_programs[variant], err);
    *fill = s->fill_programs[variant];
    *compose = s->compose_programs[variant];
    return status;
}

oit_status linked_lists_create(const linked_lists_resolve *resolve, const oit_algorithm_config *config,
                               oit_algorithm **out, oit_error *err)
{
    *out = NULL;
    if (!GLEW_VERSION_4_4 && !GLEW_ARB_clear_texture)
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: needs OpenGL 4.4 or GL_ARB_clear_texture to clear the list heads",
                        resolve->algorithm);
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(ll_state), resolve->algorithm, config, &gpu, err);
    if (status != OIT_OK)
        return status;
    ll_state *s = (ll_state *)gpu;
    s->resolve = resolve;
    for (int variant = 0; variant < LL_VARIANT_COUNT; ++variant) {
        int n = snprintf(s->resolve_defines[variant], sizeof s->resolve_defines[variant], "%s",
                         ll_variant_defines[variant] ? ll_variant_defines[variant] : "");
        if (resolve->layers)
            snprintf(s->resolve_defines[variant] + n, sizeof s->resolve_defines[variant] - (size_t)n,
                     "#define LL_RESOLVE_LAYERS %d\n",
                     config->layers ? config->layers : OIT_APPROX_LAYERS_DEFAULT); /* checked: oit_algorithm_create */
    }

    const oit_ll_sort sort = resolve->sort_option ? config->ll_sort : OIT_LL_SORT_MERGE;
    const char *sort_shader = sort == OIT_LL_SORT_LOCAL_ARRAY ? "ll/sort_local_array.frag"
                              : sort == OIT_LL_SORT_BMA || sort == OIT_LL_SORT_MERGE
                                  ? "ll/sort_bma.frag"
                                  : "ll/sort_insertion.frag";
    char sort_defines[96];
    snprintf(sort_defines, sizeof sort_defines, "%s%s",
             sort == OIT_LL_SORT_MERGE ? "#define LL_BMA_NO_ARRAYS 1\n" : "",
             resolve->depth_order ? "" : "#define LL_ORDER_PRIMITIVE 1\n");
    GLuint unused;
    status = ll_programs(s, LL_PLAIN, &unused, &unused, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/fullscreen.vert", sort_shader,
                                         sort_defines[0] ? sort_defines : NULL, &s->sort_program, err);
    if (status != OIT_OK) {
        linked_lists_destroy((oit_algorithm *)s);
        return status;
    }

    s->pool = (oit_fragment_pool){
        .algorithm = resolve->algorithm,
        .gl_binding = "one shader storage buffer or buffer texture",
        .gl_binding_note = "; GL_MAX_SHADER_STORAGE_BLOCK_SIZE, GL_MAX_TEXTURE_BUFFER_SIZE",
        .memory = &s->gpu.memory,
        .budget_bytes = config->max_memory_bytes,
        .buffer_count = LL_POOL_BUFFERS,
        .buffer_bytes = {[LL_NODES] = OIT_LL_NODE_BYTES, [LL_NEXT] = OIT_LL_NEXT_BYTES,
                         [LL_SORTED_NEXT] = OIT_LL_NEXT_BYTES},
        .view_count = LL_POOL_BUFFERS,
        .view_buffer = {LL_NODES, LL_NEXT, LL_SORTED_NEXT},
        .view_format = {GL_RGBA32UI, GL_R32UI, GL_R32UI},
    };
    GLint64 max_block_bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    s->pool.gl_limit = (uint64_t)max_block_bytes / OIT_LL_NODE_BYTES;
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    if (s->pool.gl_limit > (uint64_t)max_texels)
        s->pool.gl_limit = (uint64_t)max_texels;
    if (s->pool.gl_limit >= OIT_LIST_END)
        s->pool.gl_limit = OIT_LIST_END - 1u; /* node indices are uint, END is reserved */
    if (config->buffer_fragment_limit && s->pool.gl_limit > config->buffer_fragment_limit)
        s->pool.gl_limit = config->buffer_fragment_limit; /* tests: bands without 8M fragments */
    glGenTextures(LL_POOL_BUFFERS, s->pool.views); /* one view over each buffer */
    glGenBuffers(LL_POOL_BUFFERS, s->pool.buffers);
    glGenBuffers(1, &s->counter_buffer);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->counter_buffer, OIT_LL_COUNTER_COUNT * sizeof(GLuint), NULL,
                              GL_DYNAMIC_READ);

    return oit_gpu_created(&s->gpu, status, linked_lists_destroy, out, err);
}

oit_status linked_lists_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    ll_state *s = ll_from(alg);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;
    s->band_plan.count = 0; /* bands of the old size */
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->head_image);
    s->head_image =
        oit_gpu_target(&s->gpu, GL_R32UI, width, height);

    /* The first pool: a few fragments per pixel (or what the config asks for),
     * within the budget. Frames that need more grow it in render(). */
    uint64_t initial = s->gpu.config.initial_fragment_capacity
                           ? s->gpu.config.initial_fragment_capacity
                           : LL_DEFAULT_FRAGMENTS_PER_PIXEL * (uint64_t)width * (uint64_t)height;
    uint64_t limit = oit_pool_limit(&s->pool);
    if (initial > limit)
        initial = limit;
    if (s->pool.capacity < initial || s->pool.capacity == 0) {
        status = oit_pool_allocate(&s->pool, initial, err);
        if (status != OIT_OK)
            return status;
    }
    char what[64];
    snprintf(what, sizeof what, "%s resize", s->resolve->algorithm);
    return oit_gl_check(what, err);
}

/* --------------------------------------------------------------- render */

static void ll_bind_pool(const ll_state *s)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_NODES, s->pool.buffers[LL_NODES]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_NEXT, s->pool.buffers[LL_NEXT]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAGMENT_SORTED_NEXT,
                     s->pool.buffers[LL_SORTED_NEXT]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_FRAME_COUNTERS, s->counter_buffer);
    glBindImageTexture(OIT_IMAGE_LIST_HEAD, s->head_image, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_R32UI);
    const struct {
        GLenum unit;
        GLuint texture;
    } views[] = {{OIT_TEXUNIT_LL_NODES, s->pool.views[LL_NODES]},
                 {OIT_TEXUNIT_LL_NEXT, s->pool.views[LL_NEXT]},
                 {OIT_TEXUNIT_LL_SORTED_NEXT, s->pool.views[LL_SORTED_NEXT]}};
    for (size_t i = 0; i < sizeof views / sizeof views[0]; ++i) {
        glActiveTexture(GL_TEXTURE0 + views[i].unit);
        glBindTexture(GL_TEXTURE_BUFFER, views[i].texture);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* Clear heads and counters, then draw every fragment into the lists. */
static void ll_clear_and_fill(ll_state *s, GLuint fill_program, const oit_scene *scene,
                              const oit_frame_settings *frame, const char *const names[2])
{
    oit_timer_stage_begin(&s->gpu.timer, names[0]);
    const GLuint list_end = OIT_LIST_END;
    glClearTexImage(s->head_image, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &list_end);
    GLuint zeros[OIT_LL_COUNTER_COUNT] = {0};
    zeros[OIT_FRAME_COUNTER_FRAGMENTS] = s->gpu.config.fragment_counter_start; /* 0 but in tests */
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zeros, zeros);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    /* the clears must land before the fill's image and buffer atomics */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);

    oit_timer_stage_begin(&s->gpu.timer, names[1]);
    glUseProgram(fill_program);
    glUniform1ui(OIT_UNIFORM_LL_POOL_CAPACITY, (GLuint)s->pool.capacity);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->gpu.timer);
}

/* The figures one sort (and compose) counted, summed over the bands of a frame. */
typedef struct ll_counts {
    uint64_t counted; /* the fills' counts (config.fragment_counter_start included, as tests expect) */
    uint64_t sorted, non_empty, psi_pixels, longest, long_list_pixels;
    uint64_t histogram[OIT_HISTOGRAM_BINS]; /* bin 0 unused: empty pixels are pixels - non_empty */
} ll_counts;

/* Read the counters of the last sort and compose and add them to `sum`. The sort
 * counts each pixel in the histogram only (ll_finish_sort in ll_nodes.glsl):
 * non-empty pixels, fragments sorted and psi come from it; lists in the open last
 * bin have their own fragment sum and psi count. Fails if the sort walked fewer
 * fragments than the fill stored. */
static oit_status ll_add_counts(ll_state *s, uint64_t needed, ll_counts *sum, oit_error *err)
{
    /* reading them waits for the passes, which the timer does anyway */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint counters[OIT_LL_COUNTER_COUNT];
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counters, counters);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    const int open_bin = OIT_HISTOGRAM_BINS - 1;
    const uint64_t longest = counters[OIT_FRAME_COUNTER_MAX_LIST];
    uint64_t sorted = counters[OIT_LL_COUNTER_SORTED_FRAGMENTS], psi_pixels = 0;
    for (uint64_t bin = 1; bin < OIT_HISTOGRAM_BINS; ++bin) {
        const uint64_t bin_pixels = counters[OIT_LL_COUNTER_HISTOGRAM + bin];
        sum->histogram[bin] += bin_pixels;
        sum->non_empty += bin_pixels;
        if (bin < (uint64_t)open_bin) {
            sorted += bin * bin_pixels;
            if (3 * bin > 2 * longest)
                psi_pixels += bin_pixels;
        }
    }
    if (longest >= (uint64_t)open_bin)
        psi_pixels = counters[OIT_LL_COUNTER_PSI_PIXELS]; /* compose counted them */
    /* the fill stored nodes fragment_counter_start..needed - 1 (0 but in tests) */
    const uint64_t stored = needed - s->gpu.config.fragment_counter_start;
    oit_status status = oit_gl_check_sorted_fragments(s->resolve->algorithm, stored, sorted, err);
    if (status != OIT_OK)
        return status;
    sum->counted += needed;
    sum->sorted += sorted;
    sum->psi_pixels += psi_pixels;
    sum->long_list_pixels += counters[OIT_FRAME_COUNTER_LONG_LIST_PIXELS];
    if (longest > sum->longest)
        sum->longest = longest;
    return OIT_OK;
}

/* Sort, the distance pass if the frame needs one, and compose, on the pixels the
 * scissor lets through. `clear`: clear the output to the background first (the
 * compose discards empty pixels: they keep it). */
static oit_status ll_sort_and_compose(ll_state *s, GLuint compose_program,
                                      const oit_frame_settings *frame, bool clear,
                                      const char *const names[2], oit_error *err)
{
    oit_timer_stage_begin(&s->gpu.timer, names[0]);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(s->sort_program);
    oit_gl_draw_fullscreen(&s->gpu.output); /* colour writes are still off */
    oit_status status = oit_gpu_stage_check(&s->gpu, "sort", err);
    if (status != OIT_OK)
        return status;

    /* The distance modulation with an automatic region: the frame's largest
     * distance first (one more full-screen pass over the sorted lists). */
    const bool distance = frame->modulation.mode == OIT_MODULATE_DISTANCE;
    const bool auto_region = distance && !(frame->modulation.focus_region > 0.0f);
    if (auto_region) {
        oit_timer_stage_begin(&s->gpu.timer, "distance_max");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
        glUseProgram(compose_program);
        glUniform1i(OIT_UNIFORM_LL_VIEW, (GLint)frame->modulation.view);
        glUniform1i(OIT_UNIFORM_LL_VIEW_PARAMETER, frame->modulation.view_parameter);
        glUniform1i(OIT_UNIFORM_LL_DISTANCE_PASS, 1);
        oit_gl_draw_fullscreen(&s->gpu.output); /* colour writes are still off */
        status = oit_gpu_stage_check(&s->gpu, "distance_max", err);
        if (status != OIT_OK)
            return status;
    }

    oit_timer_stage_begin(&s->gpu.timer, names[1]);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(compose_program);
    if (s->resolve->views) { /* a member's own resolve has none of these (linked_lists.h) */
        glUniform1i(OIT_UNIFORM_LL_DISTANCE_PASS, auto_region ? 2 : 0);
        glUniform1i(OIT_UNIFORM_LL_VIEW, (GLint)frame->modulation.view); /* numbers of OIT_LL_VIEW_* */
        glUniform1i(OIT_UNIFORM_LL_VIEW_PARAMETER, frame->modulation.view_parameter);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (clear) {
        /* compose discards the empty pixels (LL_EMPTY_PIXEL_DISCARD in ll_nodes.glsl) */
        glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    oit_gl_draw_fullscreen(&s->gpu.output);
    oit_timer_stage_end(&s->gpu.timer);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    return oit_gpu_stage_check(&s->gpu, "compose", err);
}

/* Clear, fill and read the fill's 64-bit count (the counter and the times it wrapped). */
static oit_status ll_fill_and_count(ll_state *s, GLuint fill_program, const oit_scene *scene,
                                    const oit_frame_settings *frame, const char *const names[2],
                                    uint64_t *needed, oit_error *err)
{
    ll_clear_and_fill(s, fill_program, scene, frame, names);
    *needed = oit_gl_read_frame_fragments(s->counter_buffer, OIT_LL_COUNTER_FRAGMENTS_WRAPS);
    oit_status status = oit_gpu_stage_check(&s->gpu, "fill", err);
    if (status != OIT_OK)
        return status;
    return oit_gl_check_frame_fragments(s->resolve->algorithm, *needed, s->gpu.config.fragment_counter_start, err);
}

static bool ll_bands_allowed(const oit_frame_settings *frame)
{
    const bool auto_region = frame->modulation.mode == OIT_MODULATE_DISTANCE &&
                             !(frame->modulation.focus_region > 0.0f);
    return frame->modulation.view != OIT_VIEW_HEATMAP && !auto_region;
}

/* A frame that needs more fragments than one storage-buffer binding or buffer
 * texture can address (llvmpipe: 128 MiB, 8M nodes; s->pool.gl_limit) but fits
 * the memory budget is rendered in bands of rows under the scissor test: each
 * band clears, fills, sorts and composes alone in a pool at the largest size the
 * GL addresses. Every band draws the whole scene again, so a frame of B bands
 * costs about B fills (B + 1 when a fill that only counted came first). The
 * bands start as equal shares of the frame's count with a quarter of headroom,
 * or as the last frame's bands (frame_needed 0); a band whose fill still
 * overflows (fragments are not spread evenly over the rows) is halved and done
 * again. Only the colour image and the views that read one pixel's list: the
 * heat map and the automatic distance region need the whole frame's figures. */
static oit_status ll_render_bands(ll_state *s, GLuint fill_program, GLuint compose_program,
                                  const oit_scene *scene, const oit_frame_settings *frame,
                                  uint64_t frame_needed, ll_counts *sum, int *band_count,
                                  oit_error *err)
{
    const bool auto_region = frame->modulation.mode == OIT_MODULATE_DISTANCE &&
                             !(frame->modulation.focus_region > 0.0f);
    if (!ll_bands_allowed(frame))
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: the frame needs %llu fragments, more than this GL can address in "
                        "one shader storage buffer or buffer texture (%llu); it could be drawn in "
                        "bands of rows, but not with %s, which needs the whole frame's figures",
                        s->resolve->algorithm, (unsigned long long)frame_needed, (unsigned long long)s->pool.gl_limit,
                        auto_region ? "the distance modulation's automatic region"
                                    : "the heat map view");
    oit_status status = OIT_OK;
    if (s->pool.capacity < s->pool.gl_limit) {
        status = oit_pool_allocate(&s->pool, oit_pool_limit(&s->pool), err);
        if (status != OIT_OK)
            return status;
        ll_bind_pool(s);
    }
    const int height = s->gpu.output.height, width = s->gpu.output.width;
    oit_band_walk walk; /* from the last frame's bands when frame_needed is 0 */
    status = oit_bands_begin(&walk, &s->band_plan, height, 0, frame_needed, s->pool.capacity, s->resolve->algorithm,
                             err);
    if (status != OIT_OK)
        return status;
    static const char *const band_names[2] = {"band_sort", "band_compose"};
    glEnable(GL_SCISSOR_TEST);
    /* the output is cleared once; each band's compose keeps the background of its empty pixels */
    glScissor(0, 0, width, height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    *band_count = 0;
    oit_band band;
    while (oit_bands_next(&walk, &band)) {
        glScissor(0, band.first, width, band.rows);
        uint64_t needed = 0;
        static const char *const band_fill_names[2] = {"band_clear", "band_fill"};
        status = ll_fill_and_count(s, fill_program, scene, frame, band_fill_names, &needed, err);
        if (status != OIT_OK)
            break;
        if (needed > s->pool.capacity) {
            if (!oit_bands_halve(&walk, &band)) {
                status = oit_fail(err, OIT_E_RUNTIME,
                                  "%s: row %d of the image alone needs %llu fragments, more than "
                                  "this GL can address in one buffer (%llu)",
                                  s->resolve->algorithm, band.first, (unsigned long long)needed,
                                  (unsigned long long)s->pool.capacity);
                break;
            }
            continue;
        }
        status = ll_sort_and_compose(s, compose_program, frame, false, band_names, err);
        if (status == OIT_OK)
            status = ll_add_counts(s, needed, sum, err);
        if (status != OIT_OK)
            break;
        ++*band_count;
        oit_bands_fitted(&walk, &band);
    }
    /* the next frame at this size starts from the bands that fitted, unless this
     * one failed or would have fitted whole with room to spare (the camera moved away) */
    oit_bands_end(&walk, &s->band_plan,
                  status == OIT_OK && sum->counted + sum->counted / 4 > s->pool.gl_limit);
    glDisable(GL_SCISSOR_TEST);
    return status;
}

oit_status linked_lists_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err)
{
    ll_state *s = ll_from(alg);
    oit_status status;
    if (frame->width != s->gpu.output.width || frame->height != s->gpu.output.height ||
        !s->head_image) {
        status = linked_lists_resize(alg, frame->width, frame->height, err);
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

    status = oit_gpu_frame_begin(&s->gpu, scene, frame, err);
    if (status != OIT_OK)
        return status;
    oit_stats *stats = &s->gpu.stats;

    glBindFramebuffer(GL_FRAMEBUFFER, s->gpu.output.framebuffer);
    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    ll_bind_pool(s);

    /* Fill until the pool holds the whole frame, or draw it in bands of rows
     * when no one buffer can (straight away when the last frame was banded). */
    int retries = 0, bands = 1;
    uint64_t needed = 0;
    ll_counts sum;
    memset(&sum, 0, sizeof sum);
    const bool planned = s->band_plan.count > 0 && ll_bands_allowed(frame);
    if (planned) {
        status = ll_render_bands(s, fill_program, compose_program, scene, frame, 0, &sum, &bands,
                                 err);
        if (status != OIT_OK)
            goto failed;
    }
    while (!planned) {
        static const char *const fill_names[2][2] = {{"clear", "fill"}, {"clear_retry", "fill_retry"}};
        status = ll_fill_and_count(s, fill_program, scene, frame, fill_names[retries > 0], &needed,
                                   err);
        if (status != OIT_OK)
            goto failed;
        if (needed <= s->pool.capacity)
            break;
        if (retries + 1 >= LL_MAX_FILLS) {
            status = oit_fail(err, OIT_E_RUNTIME,
                              "%s: the frame still needs %llu fragments after growing the pool to "
                              "%llu",
                              s->resolve->algorithm, (unsigned long long)needed, (unsigned long long)s->pool.capacity);
            goto failed;
        }
        if (needed > s->pool.gl_limit && needed <= oit_pool_budget(&s->pool))
            break; /* bands */
        status = oit_pool_grow(&s->pool, needed, err);
        if (status != OIT_OK)
            goto failed;
        ++retries;
    }

    if (planned) {
        /* drawn above */
    } else if (needed > s->pool.capacity) {
        status = ll_render_bands(s, fill_program, compose_program, scene, frame, needed, &sum,
                                 &bands, err);
    } else {
        s->band_plan.count = 0;
        static const char *const names[2] = {"sort", "compose"};
        status = ll_sort_and_compose(s, compose_program, frame, true, names, err);
        if (status == OIT_OK)
            status = ll_add_counts(s, needed, &sum, err);
    }
    if (status != OIT_OK)
        goto failed;
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    status = oit_gpu_frame_end(&s->gpu, status, err);

    s->overflow_retries_total += retries;
    s->long_list_pixels = (uint32_t)sum.long_list_pixels;
    stats->fragments = (int64_t)sum.counted;
    stats->max_list = (int64_t)sum.longest;
    stats->overflow_retries = retries; /* this frame's */
    stats->bands = bands;
    const uint64_t pixels = (uint64_t)s->gpu.output.width * (uint64_t)s->gpu.output.height;
    stats->mean_list = sum.non_empty ? (double)stats->fragments / (double)sum.non_empty : 0.0;
    /* A banded frame: psi from the summed histogram against the frame's longest
     * list, unless that list is in the open last bin; then each band's compose
     * counted psi against the band's own longest list (docs/algorithms.md, Limits). */
    uint64_t psi_pixels = sum.psi_pixels;
    if (bands > 1 && sum.longest < OIT_HISTOGRAM_BINS - 1) {
        psi_pixels = 0;
        for (uint64_t bin = 1; bin < OIT_HISTOGRAM_BINS - 1; ++bin)
            if (3 * bin > 2 * sum.longest)
                psi_pixels += sum.histogram[bin];
    }
    stats->psi = sum.non_empty ? (double)psi_pixels / (double)sum.non_empty : 0.0;
    stats->histogram_bins = OIT_HISTOGRAM_BINS;
    stats->list_histogram[0] = pixels - sum.non_empty;
    for (int bin = 1; bin < OIT_HISTOGRAM_BINS; ++bin)
        stats->list_histogram[bin] = sum.histogram[bin];
    /* the pool's share of what is allocated (oit_stats in oit.h defines it) */
    stats->bytes_per_fragment = (double)oit_gl_memory_bytes(&s->gpu.memory, OIT_GL_MEMORY_FRAGMENTS) /
                                (double)s->pool.capacity;
    return status;

failed:
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

/* ll shows the colour image and the list views, and every local modulation
 * and distance; the rest is the Illustration Buffer's (ib). */
#define LL_VIEW_REASON "view '%s' is not supported (colour, heatmap, peel limit and layer only)"
static const oit_capabilities ll_capabilities = {
    .views = {[OIT_VIEW_NEIGHBOURS] = LL_VIEW_REASON, [OIT_VIEW_CURVATURE] = LL_VIEW_REASON,
              [OIT_VIEW_DISTANCE] = LL_VIEW_REASON, [OIT_VIEW_FIELDS] = LL_VIEW_REASON},
    .modulations = {OIT_REFUSES_NEIGHBOUR_MODULATIONS("a pixel's list has no link to the adjacent pixels' lists, "
                                                      "which are sorted only inside their own compose invocation; "
                                                      "ll does the local ones and the distance")},
    .options = OIT_OPTION_SORT | OIT_OPTION_FRAGMENT_POOL | OIT_OPTION_MAX_MEMORY,
};

static const linked_lists_resolve ll_resolve = {
    .algorithm = "ll",
    .resolve_shader = "ll/compose.frag",
    .depth_order = true,
    .sort_option = true,
    .views = true,
};

static oit_status ll_create(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err)
{
    return linked_lists_create(&ll_resolve, config, out, err);
}

const oit_algorithm_ops oit_algorithm_ll = {
    .name = "ll",
    .summary = "per-pixel linked lists: one geometry pass, then sort and compose per pixel",
    .uses_gl = true,
    .exact = true,
    .capabilities = &ll_capabilities,
    .create = ll_create,
    .resize = linked_lists_resize,
    .render = linked_lists_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = linked_lists_destroy,
};
