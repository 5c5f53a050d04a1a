/*
 * alg_ib.c: the Illustration Buffer (Carnecky et al. 2013; thesis 3.1.5, 3.3,
 * 4.3-4.6): per-pixel fragment lists whose fragments also know their surface
 * neighbours, and the opacity modulations that use them.
 * docs/illustration-buffer.md describes the layout, stages and choices.
 *
 * GPU data (bindings in oit_shared.h, GLSL in shaders/ib/ib_common.glsl):
 *   per pixel (8 bytes, and 4 for the RGBA8 output)
 *     head image   r32ui: list head during the fill, the run's start afterwards
 *     count image  r32ui: the run's length
 *   per fragment (40 bytes)
 *     nodes        uvec4: the fill's node (depth, triangle, normal, next); after
 *                  the sort the two ping-pong copies of the transparency fields
 *     run core     uvec4: depth, triangle, octahedral normal, curvature | distance
 *     run links    uvec2: the four neighbours' layer indices, 16 bit each (so a
 *                  run may hold OIT_IB_MAX_RUN_LENGTH fragments; a longer one
 *                  fails the frame, as do a fill count past 32 bits and a sort
 *                  that walked fewer fragments than the fill stored:
 *                  docs/algorithms.md, "Limits")
 *   The triangle's vertices, welded ids, component and eye-space plane come from
 *   the scene's own index and vertex buffers, bound as storage buffers.
 *
 * One frame (each a timed stage; modulation passes that are off do not run):
 *   fill        geometry pass into linked lists (as ll); overflow: grow, fill again
 *   sort        each list becomes a contiguous run sorted front to back
 *   neighbours  the four surface neighbours of every fragment (--neighbours):
 *               the triangle table and the index / welded search
 *   neighbours_epsilon  the epsilon search for the fragments queued (welded, epsilon)
 *   neighbour_stats  link quality, summed on the GPU (config.neighbour_quality)
 *   fields, diffusion, blur   transparency fields (modulation fields / view fields)
 *   curvature_distance        (curvature, distance, dist-curv / their views)
 *   compose     composite front to back in float, or show a view
 *
 * A frame whose fragments exceed what one pool holds (what one storage buffer
 * addresses, or the --max-memory budget) is drawn in bands of rows (bands.h),
 * each storing its rows and the rows either side that its neighbour passes
 * read (ib_band_overlap) and composing only its own; a first sweep finds the
 * whole frame's longest list and largest distance where a view or the
 * distance modulation needs them (ib_render_bands; docs/illustration-buffer.md,
 * "Bands").
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bands.h"
#include "fragment_pool.h"
#include "gpu_algorithm.h"
#include "ib_plan.h"

/* The pool's buffers per fragment: its node, its run's core and links; the
 * figures in the stats come from what the tracker recorded (ib_fill_stats). */
enum { IB_NODES, IB_CORE, IB_LINKS, IB_POOL_BUFFERS };
/* Its buffer-texture views: the core as records and as words, the links, the nodes. */
enum { IB_VIEW_CORE, IB_VIEW_LINKS, IB_VIEW_CORE_WORDS, IB_VIEW_NODES, IB_POOL_VIEWS };
#define IB_DEFAULT_FRAGMENTS_PER_PIXEL 4u
#define IB_MAX_FILLS 3

_Static_assert(OIT_IB_HISTOGRAM_BINS == OIT_HISTOGRAM_BINS, "histogram bins differ");
_Static_assert(OIT_IB_COUNTER_HISTOGRAM + OIT_IB_HISTOGRAM_BINS <= OIT_IB_COUNTER_COUNT,
               "counter buffer too small");
_Static_assert(OIT_IB_MODE_FIELDS == OIT_MODULATE_FIELDS && OIT_IB_MODE_EDGES == OIT_MODULATE_EDGES &&
                   OIT_IB_MODE_DIST_CURV == OIT_MODULATE_DIST_CURV,
               "modes differ");
_Static_assert(OIT_IB_VIEW_FIELDS == OIT_VIEW_FIELDS && OIT_IB_VIEW_NEIGHBOURS == OIT_VIEW_NEIGHBOURS,
               "views differ");
_Static_assert(OIT_IB_SEARCH_EPSILON == OIT_NEIGHBOURS_EPSILON &&
                   OIT_IB_SEARCH_WELDED == OIT_NEIGHBOURS_WELDED,
               "searches differ");
_Static_assert(OIT_IB_DISTANCE_FAR_END == OIT_DISTANCE_FAR_END, "distance modes differ");

enum ib_program {
    IB_FILL,
    IB_SORT,
    IB_TRIANGLES,
    IB_NEIGHBOURS,
    IB_NEIGHBOURS_EPSILON,
    IB_EPSILON_DISPATCH,
    IB_TILES_DISPATCH,
    IB_NEIGHBOUR_STATS,
    IB_FIELDS,
    IB_DIFFUSION,
    IB_BLUR,
    IB_CURVATURE_DISTANCE,
    IB_DISTANCE_MAX,  /* the first sweep of a banded frame: the largest distance only */
    IB_COMPOSE,       /* every view and modulation */
    IB_COMPOSE_PLAIN, /* the colour image without modulation (common/variants.glsl) */
    IB_PROGRAM_COUNT
};

/* fill and compose are drawn (geometry pass, full-screen pass); the passes
 * between are compute shaders with one invocation per pixel. (Full-screen
 * fragment passes lost some storage-buffer writes made in data-dependent loops
 * on llvmpipe; compute invocations have no quad or helper semantics.) */
static const char *const ib_shaders[IB_PROGRAM_COUNT] = {
    "ib/fill.frag",      "ib/sort.comp",      "ib/triangles.comp", "ib/neighbours.comp",
    "ib/neighbours_epsilon.comp", "ib/epsilon_dispatch.comp", "ib/tiles_dispatch.comp",
    "ib/neighbour_stats.comp", "ib/fields_init.comp", "ib/diffusion.comp",
    "ib/blur.comp",      "ib/curvature_distance.comp", "ib/distance_max.comp",
    "ib/compose.frag",   "ib/compose.frag",
};

typedef struct ib_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */
    GLuint programs[IB_PROGRAM_COUNT];
    /* which programs declare the band (ib_band) and the pass parameter (item_count,
     * pass_parameter, source_copy or fields_copy at OIT_UNIFORM_IB_PASS): asked
     * once at create, not by name on every pass */
    bool uses_band[IB_PROGRAM_COUNT], uses_pass_parameter[IB_PROGRAM_COUNT];

    GLuint head_image, count_image;
    oit_fragment_pool pool;
    GLuint counter_buffer, param_buffer;
    /* the triangle table (ib/triangles.comp): 2 uvec4 per triangle */
    GLuint triangle_buffer;
    /* the tiles with fragments (ib/tiles.glsl): one uint per tile of the image */
    GLuint tile_buffer;
    uint64_t triangle_capacity;
    /* read-only buffer-texture views of core, links and the triangle table */
    GLuint triangle_texture, components_texture;
    /* view of the scene's triangle reach (oit_model.triangle_reach): the id search's window */
    GLuint triangle_reach_texture;
    uint64_t gl_texel_limit; /* GL_MAX_TEXTURE_BUFFER_SIZE */
    /* frames drawn in bands: the runs of the histogram's open bin by length
     * (OIT_SSBO_IB_LONG_RUNS), allocated with the first such frame */
    GLuint long_run_buffer;
    /* the band of rows the passes work on: stored [0], [1), composed [2], [3)
     * (ib_band in ib_common.glsl); the whole image in a frame drawn whole */
    GLint band[4];
    /* the bands the last frame was drawn in, and the overlap they had: the next
     * frame at the size with the same overlap starts from them (bands.h) */
    oit_band_plan band_plan;
    int band_plan_overlap;
} ib_state;

static ib_state *ib_from(oit_algorithm *alg) { return (ib_state *)alg; }

/* --------------------------------------------------------------- create */

static void ib_destroy(oit_algorithm *alg)
{
    ib_state *s = ib_from(alg);
    if (!s)
        return;
    GLuint textures[] = {s->head_image, s->count_image, s->triangle_texture,
                         s->components_texture, s->triangle_reach_texture};
    oit_gl_memory_delete_textures(&s->gpu.memory, 5, textures);
    oit_gl_memory_delete_textures(&s->gpu.memory, IB_POOL_VIEWS, s->pool.views);
    oit_gl_memory_delete_buffers(&s->gpu.memory, IB_POOL_BUFFERS, s->pool.buffers);
    GLuint buffers[] = {s->counter_buffer, s->param_buffer, s->triangle_buffer, s->tile_buffer,
                        s->long_run_buffer};
    oit_gl_memory_delete_buffers(&s->gpu.memory, 5, buffers);
    oit_band_plan_free(&s->band_plan);
    oit_gpu_destroy(&s->gpu);
}

static oit_status ib_create(const oit_algorithm_config *config, oit_algorithm **out,
                            oit_error *err)
{
    *out = NULL;
    if (!GLEW_VERSION_4_4 && !GLEW_ARB_clear_texture)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ib: needs OpenGL 4.4 or GL_ARB_clear_texture to clear the list heads");
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(ib_state), "ib", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    ib_state *s = (ib_state *)gpu;

    for (int p = 0; p < IB_PROGRAM_COUNT && status == OIT_OK; ++p) {
        if (p == IB_FILL)
            status = oit_gpu_program(gpu, "common/geometry.vert", ib_shaders[p], &s->programs[p], err);
        else if (p == IB_COMPOSE || p == IB_COMPOSE_PLAIN)
            status = oit_gpu_program_variant(
                gpu, "ib/compose.vert", ib_shaders[p],
                p == IB_COMPOSE_PLAIN ? "#define OIT_VARIANT_VIEWS 0\n#define OIT_VARIANT_IB_MODES 0\n"
                                      : NULL,
                &s->programs[p], err);
        else
            status = oit_gpu_compute_program(gpu, ib_shaders[p], &s->programs[p], err);
        if (status == OIT_OK) {
            static const char *const pass_parameters[] = {"item_count", "pass_parameter", "source_copy",
                                                          "fields_copy"};
            s->uses_band[p] = glGetUniformLocation(s->programs[p], "ib_band") == OIT_UNIFORM_IB_BAND;
            for (size_t k = 0; k < sizeof pass_parameters / sizeof pass_parameters[0]; ++k)
                s->uses_pass_parameter[p] |=
                    glGetUniformLocation(s->programs[p], pass_parameters[k]) == OIT_UNIFORM_IB_PASS;
        }
    }
    if (status != OIT_OK) {
        ib_destroy((oit_algorithm *)s);
        return status;
    }

    s->pool = (oit_fragment_pool){
        .algorithm = "ib",
        .gl_binding = "one shader storage buffer",
        .gl_binding_note = "",
        .memory = &s->gpu.memory,
        .budget_bytes = config->max_memory_bytes,
        .buffer_count = IB_POOL_BUFFERS,
        .buffer_bytes = {[IB_NODES] = OIT_IB_NODE_BYTES, [IB_CORE] = OIT_IB_RUN_CORE_BYTES,
                         [IB_LINKS] = OIT_IB_RUN_LINKS_BYTES},
        .view_count = IB_POOL_VIEWS,
        .view_buffer = {[IB_VIEW_CORE] = IB_CORE, [IB_VIEW_LINKS] = IB_LINKS,
                        [IB_VIEW_CORE_WORDS] = IB_CORE, [IB_VIEW_NODES] = IB_NODES},
        .view_format = {[IB_VIEW_CORE] = GL_RGBA32UI, [IB_VIEW_LINKS] = GL_RG32UI,
                        [IB_VIEW_CORE_WORDS] = GL_R32UI, [IB_VIEW_NODES] = GL_RGBA32UI},
    };
    GLint64 max_block_bytes = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block_bytes);
    s->pool.gl_limit = (uint64_t)max_block_bytes / OIT_IB_NODE_BYTES;
    if (s->pool.gl_limit >= OIT_LIST_END)
        s->pool.gl_limit = OIT_LIST_END - 1u;
    /* the run core is also read as buffer textures, up to 4 texels per fragment */
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    s->gl_texel_limit = max_texels > 0 ? (uint64_t)max_texels : 0;
    if (s->pool.gl_limit > s->gl_texel_limit / 4u)
        s->pool.gl_limit = s->gl_texel_limit / 4u;
    if (config->buffer_fragment_limit && s->pool.gl_limit > config->buffer_fragment_limit)
        s->pool.gl_limit = config->buffer_fragment_limit; /* tests: bands without 8M fragments */

    glGenBuffers(IB_POOL_BUFFERS, s->pool.buffers);
    glGenTextures(IB_POOL_VIEWS, s->pool.views);
    GLuint buffers[4];
    glGenBuffers(4, buffers);
    s->counter_buffer = buffers[0];
    s->param_buffer = buffers[1];
    s->triangle_buffer = buffers[2];
    s->tile_buffer = buffers[3];
    GLuint buffer_textures[3];
    glGenTextures(3, buffer_textures);
    s->triangle_texture = buffer_textures[0];
    s->components_texture = buffer_textures[1];
    s->triangle_reach_texture = buffer_textures[2];
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->counter_buffer, OIT_IB_COUNTER_COUNT * sizeof(GLuint), NULL,
                              GL_DYNAMIC_READ);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->param_buffer, sizeof(ib_params), NULL, GL_DYNAMIC_DRAW);

    return oit_gpu_created(&s->gpu, status, ib_destroy, out, err);
}

static oit_status ib_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    ib_state *s = ib_from(alg);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;
    s->band_plan.count = 0; /* bands of the old size */
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->head_image);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->count_image);
    s->head_image =
        oit_gpu_target(&s->gpu, GL_R32UI, width, height);
    s->count_image =
        oit_gpu_target(&s->gpu, GL_R32UI, width, height);
    const uint64_t tiles = (uint64_t)((width + OIT_IB_TILE_SIZE - 1) / OIT_IB_TILE_SIZE) *
                           (uint64_t)((height + OIT_IB_TILE_SIZE - 1) / OIT_IB_TILE_SIZE);
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_PIXELS, GL_SHADER_STORAGE_BUFFER,
                              s->tile_buffer, (GLsizeiptr)(tiles * sizeof(GLuint)), NULL,
                              GL_DYNAMIC_COPY);

    uint64_t initial = s->gpu.config.initial_fragment_capacity
                           ? s->gpu.config.initial_fragment_capacity
                           : IB_DEFAULT_FRAGMENTS_PER_PIXEL * (uint64_t)width * (uint64_t)height;
    uint64_t limit = oit_pool_limit(&s->pool);
    if (initial > limit)
        initial = limit;
    if (s->pool.capacity < initial || s->pool.capacity == 0) {
        status = oit_pool_allocate(&s->pool, initial, err);
        if (status != OIT_OK)
            return status;
    }
    return oit_gl_check("ib resize", err);
}

/* --------------------------------------------------------------- render */

static void ib_bind(const ib_state *s, const oit_scene *scene)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_NODES, s->pool.buffers[IB_NODES]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_RUN_CORE, s->pool.buffers[IB_CORE]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_RUN_LINKS, s->pool.buffers[IB_LINKS]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_COUNTERS, s->counter_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_PARAMS, s->param_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_TILES, s->tile_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_INDICES, scene->index_buffer);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_POSITIONS, scene->vertex_buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_VERTEX_COMPONENT,
                     scene->vertex_buffers[2]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_WELDED, scene->vertex_buffers[3]);
    glBindImageTexture(OIT_IMAGE_LIST_HEAD, s->head_image, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_R32UI);
    glBindImageTexture(OIT_IMAGE_LIST_COUNT, s->count_image, 0, GL_FALSE, 0, GL_READ_WRITE,
                       GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_TRIANGLES, s->triangle_buffer);
    const struct {
        GLenum unit;
        GLuint texture;
    } views[] = {{OIT_TEXUNIT_IB_RUN_CORE, s->pool.views[IB_VIEW_CORE]},
                 {OIT_TEXUNIT_IB_RUN_LINKS, s->pool.views[IB_VIEW_LINKS]},
                 {OIT_TEXUNIT_IB_TRIANGLES, s->triangle_texture},
                 {OIT_TEXUNIT_IB_RUN_WORDS, s->pool.views[IB_VIEW_CORE_WORDS]},
                 {OIT_TEXUNIT_IB_NODES, s->pool.views[IB_VIEW_NODES]},
                 {OIT_TEXUNIT_IB_COMPONENTS, s->components_texture},
                 {OIT_TEXUNIT_IB_TRIANGLE_REACH, s->triangle_reach_texture}};
    glBindTexture(GL_TEXTURE_BUFFER, s->components_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, scene->component_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, s->triangle_reach_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, scene->triangle_reach_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    for (size_t i = 0; i < sizeof views / sizeof views[0]; ++i) {
        glActiveTexture(GL_TEXTURE0 + views[i].unit);
        glBindTexture(GL_TEXTURE_BUFFER, views[i].texture);
    }
    glActiveTexture(GL_TEXTURE0);
}

/* The triangle table holds 2 rows per triangle; grown to the scene's size. */
static oit_status ib_reserve_triangles(ib_state *s, uint64_t triangles, oit_error *err)
{
    if (triangles == 0)
        triangles = 1;
    if (triangles <= s->triangle_capacity)
        return OIT_OK;
    if (2u * triangles > s->gl_texel_limit)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ib: the scene's %llu triangles do not fit in one buffer texture (%llu "
                        "texels)",
                        (unsigned long long)triangles, (unsigned long long)s->gl_texel_limit);
    while (glGetError() != GL_NO_ERROR) {
    }
    oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                              s->triangle_buffer, triangles * OIT_IB_TRIANGLE_BYTES, NULL,
                              GL_DYNAMIC_COPY);
    glBindTexture(GL_TEXTURE_BUFFER, s->triangle_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32UI, s->triangle_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        s->triangle_capacity = 0;
        return oit_fail(err, OIT_E_RUNTIME,
                        "ib: could not allocate the triangle table for %llu triangles: GL error "
                        "0x%04x",
                        (unsigned long long)triangles, (unsigned)error);
    }
    s->triangle_capacity = triangles;
    return OIT_OK;
}


static void ib_barrier(void)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_TEXTURE_FETCH_BARRIER_BIT);
}

/* glUseProgram(p) with the band of rows (ib_band); the frame block is bound for every pass. */
static void ib_use_program(ib_state *s, enum ib_program p)
{
    glUseProgram(s->programs[p]);
    if (s->uses_band[p])
        glUniform4iv(OIT_UNIFORM_IB_BAND, 1, s->band);
}

/* The passes work on the rows [stored_first, stored_end) (the fill drew those
 * only) and count the figures of [first, end) only. */
static void ib_set_band(ib_state *s, int stored_first, int stored_end, int first, int end)
{
    s->band[0] = stored_first;
    s->band[1] = stored_end;
    s->band[2] = first;
    s->band[3] = end;
}

/* A pass of program p with one invocation per item (work groups of
 * OIT_IB_ITEMS_PER_GROUP, in rows past the work-group count limit); the shader
 * skips those past the end. */
static void ib_item_pass(ib_state *s, enum ib_program p, GLuint items)
{
    GLuint groups = (items + OIT_IB_ITEMS_PER_GROUP - 1u) / OIT_IB_ITEMS_PER_GROUP;
    GLuint rows = 1;
    while (groups > OIT_IB_MAX_GROUPS_X) {
        groups = (groups + 1u) / 2u;
        rows *= 2u;
    }
    ib_barrier();
    ib_use_program(s, p);
    if (s->uses_pass_parameter[p])
        glUniform1i(OIT_UNIFORM_IB_PASS, (GLint)items);
    if (items > 0)
        glDispatchCompute(groups, rows, 1);
}

/* Program `counts` (one invocation: epsilon_dispatch, tiles_dispatch) turns a
 * count a GPU pass made into work-group counts in the counters. */
static void ib_count_groups(ib_state *s, enum ib_program counts)
{
    ib_barrier();
    glUseProgram(s->programs[counts]);
    glDispatchCompute(1, 1, 1);
}

/* Program p with the work-group counts at counter `slot` that ib_count_groups
 * wrote: exactly the groups its items or tiles need. */
static void ib_indirect_pass(ib_state *s, enum ib_program p, int slot)
{
    ib_barrier();
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
    ib_use_program(s, p);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, s->counter_buffer);
    glDispatchComputeIndirect((GLintptr)(slot * sizeof(GLuint)));
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
}

/* One per-pixel pass of program p (compute over the rows of tiles that hold the
 * band's stored rows, or the full-screen compose), with the band and
 * the pass parameter. */
static void ib_pass(ib_state *s, enum ib_program p, const oit_frame_settings *frame,
                    int pass_parameter)
{
    ib_barrier();
    ib_use_program(s, p);
    if (s->uses_pass_parameter[p])
        glUniform1i(OIT_UNIFORM_IB_PASS, pass_parameter);
    if (p == IB_COMPOSE || p == IB_COMPOSE_PLAIN) {
        oit_gl_draw_fullscreen(&s->gpu.output);
    } else {
        /* the work groups are tiles (ib_band_pixel in ib_common.glsl) */
        const int first_tile_row = s->band[0] / OIT_IB_TILE_SIZE;
        const int end_tile_row = (s->band[1] + OIT_IB_TILE_SIZE - 1) / OIT_IB_TILE_SIZE;
        glDispatchCompute((GLuint)(s->gpu.output.width + OIT_IB_TILE_SIZE - 1) / OIT_IB_TILE_SIZE,
                          (GLuint)(end_tile_row - first_tile_row), 1);
    }
}

/* A stage of the frame; a band's are named as the whole frame's with "band_"
 * in front (as ll's), the first sweep's with "sweep_". */
static void ib_stage(ib_state *s, const char *prefix, const char *name)
{
    char full[OIT_STAGE_NAME_SIZE];
    snprintf(full, sizeof full, "%s%s", prefix, name);
    oit_timer_stage_begin(&s->gpu.timer, full);
}

/* The whole frame's figures a banded frame's compose reads before every band
 * has been drawn: its longest list (the heat map) and its largest distance
 * (the distance modulation's automatic region), as float bits. Zero: not
 * known, the band's own. */
typedef struct ib_frame_figures {
    GLuint longest, largest_distance;
} ib_frame_figures;

/* Clear the heads of the band's stored rows and the counters (with the frame's
 * figures in place, if known), then draw every fragment of those rows (the
 * scissor lets only them through in a band) into the lists. */
static void ib_clear_and_fill(ib_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                              const char *prefix, int retry, const ib_frame_figures *figures)
{
    ib_stage(s, prefix, retry ? "clear_retry" : "clear");
    const GLuint list_end = OIT_LIST_END;
    if (s->band[0] == 0 && s->band[1] == s->gpu.output.height)
        glClearTexImage(s->head_image, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &list_end);
    else /* the passes read no row outside the band (ib_inside) */
        glClearTexSubImage(s->head_image, 0, 0, s->band[0], 0, s->gpu.output.width,
                           s->band[1] - s->band[0], 1, GL_RED_INTEGER, GL_UNSIGNED_INT, &list_end);
    GLuint zeros[OIT_IB_COUNTER_COUNT] = {0};
    zeros[OIT_FRAME_COUNTER_FRAGMENTS] = s->gpu.config.fragment_counter_start; /* 0 but in tests */
    if (figures) { /* the passes only raise these with atomicMax */
        zeros[OIT_FRAME_COUNTER_MAX_LIST] = figures->longest;
        zeros[OIT_IB_COUNTER_MAX_DISTANCE] = figures->largest_distance;
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zeros, zeros);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    ib_barrier();

    ib_stage(s, prefix, retry ? "fill_retry" : "fill");
    glUseProgram(s->programs[IB_FILL]);
    glUniform1ui(OIT_UNIFORM_IB_POOL_CAPACITY, (GLuint)s->pool.capacity);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    oit_gl_draw_scene(scene);
    oit_timer_stage_end(&s->gpu.timer);
}

/* Clear, fill and read the fill's 64-bit count (the counter and its wraps). */
static oit_status ib_fill_and_count(ib_state *s, const oit_scene *scene,
                                    const oit_frame_settings *frame, const char *prefix, int retry,
                                    const ib_frame_figures *figures, uint64_t *needed,
                                    oit_error *err)
{
    ib_clear_and_fill(s, scene, frame, prefix, retry, figures);
    *needed = oit_gl_read_frame_fragments(s->counter_buffer, OIT_IB_COUNTER_FRAGMENTS_WRAPS);
    oit_status status = oit_gpu_stage_check(&s->gpu, "fill", err);
    if (status != OIT_OK)
        return status;
    return oit_gl_check_frame_fragments("ib", *needed, s->gpu.config.fragment_counter_start, err);
}

/* Sort through compose, on the band's rows (the whole image in a frame drawn
 * whole): the runs, the triangle table (`triangles`: once a frame), the
 * neighbours, the modulation's passes and the compose. A band composes its own
 * rows only (the scissor) on an output cleared once for the frame. */
static oit_status ib_resolve(ib_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                             const ib_plan *plan, bool band, bool triangles, oit_error *err)
{
    const char *prefix = band ? "band_" : "";
    ib_stage(s, prefix, "sort");
    ib_pass(s, IB_SORT, frame, 0);
    ib_count_groups(s, IB_TILES_DISPATCH); /* for the passes over the tile list */
    /* the triangle table, the index / welded search, then epsilon for the
     * fragments the first search queued (at most all of them) */
    ib_stage(s, prefix, "neighbours");
    if (triangles)
        ib_item_pass(s, IB_TRIANGLES, scene->index_count / 3u);
    ib_indirect_pass(s, IB_NEIGHBOURS, OIT_IB_COUNTER_TILE_DISPATCH);
    if (plan->params.search != OIT_NEIGHBOURS_INDEX) {
        /* a stage of its own: how much of the search the fallback costs is worth seeing */
        ib_stage(s, prefix, "neighbours_epsilon");
        ib_count_groups(s, IB_EPSILON_DISPATCH);
        ib_indirect_pass(s, IB_NEIGHBOURS_EPSILON, OIT_IB_COUNTER_EPSILON_DISPATCH);
    }
    if (s->gpu.config.neighbour_quality) {
        /* diagnostics, not part of the frame: oit bench and oit measure turn it off */
        ib_stage(s, prefix, "neighbour_stats");
        ib_indirect_pass(s, IB_NEIGHBOUR_STATS, OIT_IB_COUNTER_TILE_DISPATCH);
    }
    oit_status status = oit_gpu_stage_check(&s->gpu, "neighbours", err);
    if (status != OIT_OK)
        return status;

    int fields_copy = 0;
    if (plan->fields) {
        ib_stage(s, prefix, "fields");
        ib_pass(s, IB_FIELDS, frame, 0);
        if (plan->diffusion_iterations > 0) {
            ib_stage(s, prefix, "diffusion");
            for (int k = 0; k < plan->diffusion_iterations; ++k) {
                ib_pass(s, IB_DIFFUSION, frame, fields_copy);
                fields_copy = 1 - fields_copy;
            }
        }
        if (plan->blur_iterations > 0 && (plan->params.fields & OIT_FIELD_BETA)) {
            ib_stage(s, prefix, "blur");
            for (int k = 0; k < plan->blur_iterations; ++k)
                for (int axis = 0; axis < 2; ++axis) {
                    ib_pass(s, IB_BLUR, frame, fields_copy | (axis << 1));
                    fields_copy = 1 - fields_copy;
                }
        }
        status = oit_gpu_stage_check(&s->gpu, "fields", err);
        if (status != OIT_OK)
            return status;
    }
    if (plan->curvature_distance) {
        ib_stage(s, prefix, "curvature_distance");
        ib_pass(s, IB_CURVATURE_DISTANCE, frame, 0);
        status = oit_gpu_stage_check(&s->gpu, "curvature_distance", err);
        if (status != OIT_OK)
            return status;
    }

    ib_stage(s, prefix, "compose");
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (band) {
        glScissor(0, s->band[2], s->gpu.output.width, s->band[3] - s->band[2]);
    } else {
        /* compose discards the empty pixels: they keep this */
        glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    ib_pass(s,
            plan->params.mode == OIT_MODULATE_NONE && plan->params.view == OIT_VIEW_COLOUR
                ? IB_COMPOSE_PLAIN
                : IB_COMPOSE,
            frame, fields_copy);
    oit_timer_stage_end(&s->gpu.timer);
    return oit_gpu_stage_check(&s->gpu, "compose", err);
}

/* The figures of a frame's counters, summed over its bands. */
typedef struct ib_counts {
    uint64_t longest;
    uint64_t histogram[OIT_HISTOGRAM_BINS]; /* bin 0 unused: empty pixels are the rest */
    uint64_t four, links, symmetric, same_component; /* neighbour_stats */
} ib_counts;

/* Read the counters after a compose, check them (the runs hold every fragment
 * the fill stored, none longer than a link addresses) and add them to `sum`.
 * `counters` receives them. */
static oit_status ib_add_counts(ib_state *s, uint64_t needed, ib_counts *sum,
                                GLuint counters[OIT_IB_COUNTER_COUNT], oit_error *err)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->counter_buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, OIT_IB_COUNTER_COUNT * sizeof(GLuint), counters);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    /* the runs hold what the sort walked; the fill stored nodes
     * fragment_counter_start..needed - 1 (0 but in tests) */
    oit_status status = oit_gl_check_sorted_fragments("ib", needed - s->gpu.config.fragment_counter_start,
                                                      counters[OIT_IB_COUNTER_RUN_ALLOCATOR], err);
    if (status != OIT_OK)
        return status;
    /* A run longer than a 16-bit link can address: its layers past 65534 had
     * no neighbour links and the search ignored them, so the frame is refused.
     * Checked here, where the counters are read anyway: the passes in between
     * stay inside the runs (a link is below min(length, 65535)). */
    if (counters[OIT_FRAME_COUNTER_MAX_LIST] > OIT_IB_MAX_RUN_LENGTH)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ib: a pixel's list has %u fragments, more than the %d a neighbour link "
                        "can address (16-bit layer indices)",
                        (unsigned)counters[OIT_FRAME_COUNTER_MAX_LIST], OIT_IB_MAX_RUN_LENGTH);
    if (counters[OIT_FRAME_COUNTER_MAX_LIST] > sum->longest)
        sum->longest = counters[OIT_FRAME_COUNTER_MAX_LIST];
    for (int b = 1; b < OIT_HISTOGRAM_BINS; ++b)
        sum->histogram[b] += counters[OIT_IB_COUNTER_HISTOGRAM + b];
    /* up to 4 links per fragment: 64-bit counts (neighbour_stats.comp) */
#define IB_COUNT64(low, high) ((uint64_t)counters[high] << 32 | counters[low])
    sum->four += counters[OIT_IB_COUNTER_FOUR_NEIGHBOURS];
    sum->links += IB_COUNT64(OIT_IB_COUNTER_LINKS, OIT_IB_COUNTER_LINKS_WRAPS);
    sum->symmetric +=
        IB_COUNT64(OIT_IB_COUNTER_SYMMETRIC_LINKS, OIT_IB_COUNTER_SYMMETRIC_LINKS_WRAPS);
    sum->same_component += IB_COUNT64(OIT_IB_COUNTER_SAME_COMPONENT_LINKS,
                                      OIT_IB_COUNTER_SAME_COMPONENT_LINKS_WRAPS);
#undef IB_COUNT64
    return OIT_OK;
}

/* The frame's statistics from its summed counts: `fragments` stored, and
 * `psi_pixels`, the non-empty pixels whose list is longer than 2/3 of the
 * longest. */
static void ib_frame_stats(const ib_state *s, const ib_counts *sum, uint64_t fragments,
                           uint64_t psi_pixels, int retries, int bands, oit_stats *stats)
{
    stats->fragments = (int64_t)fragments;
    stats->max_list = (int64_t)sum->longest;
    stats->overflow_retries = retries;
    stats->bands = bands;
    uint64_t pixels = (uint64_t)s->gpu.output.width * (uint64_t)s->gpu.output.height;
    /* the pool's share of what is allocated (oit_stats in oit.h defines it; the
     * rest, head, count and output images, counters, parameters and the
     * triangle table, oit_gpu_frame_end counted) */
    stats->bytes_per_fragment =
        (double)oit_gl_memory_bytes(&s->gpu.memory, OIT_GL_MEMORY_FRAGMENTS) / (double)s->pool.capacity;
    /* the sort counts non-empty pixels only (sort.comp): bin 0 is the rest */
    uint64_t nonempty = 0;
    for (int b = 1; b < OIT_HISTOGRAM_BINS; ++b)
        nonempty += sum->histogram[b];
    stats->mean_list = nonempty ? (double)stats->fragments / (double)nonempty : 0.0;
    stats->psi = nonempty ? (double)psi_pixels / (double)nonempty : 0.0;
    stats->histogram_bins = OIT_HISTOGRAM_BINS;
    stats->list_histogram[0] = pixels - nonempty;
    for (int b = 1; b < OIT_HISTOGRAM_BINS; ++b)
        stats->list_histogram[b] = sum->histogram[b];
    if (!s->gpu.config.neighbour_quality)
        return; /* the neighbours_* figures stay n/a */
    stats->neighbours_four_share = fragments ? (double)sum->four / (double)fragments : 0.0;
    stats->neighbours_symmetric_share =
        sum->links ? (double)sum->symmetric / (double)sum->links : 0.0;
    stats->neighbours_same_component_share =
        sum->links ? (double)sum->same_component / (double)sum->links : 0.0;
}

static oit_status ib_row_error(const ib_state *s, int row, int overlap, uint64_t needed,
                               oit_error *err)
{
    char limit[128];
    oit_pool_limit_text(&s->pool, limit, sizeof limit);
    if (overlap == 0)
        return oit_fail(err, OIT_E_RUNTIME,
                        "ib: row %d of the image alone needs %llu fragments, more than %s", row,
                        (unsigned long long)needed, limit);
    return oit_fail(err, OIT_E_RUNTIME,
                    "ib: row %d of the image, with the %d row%s either side that its neighbour "
                    "passes read, needs %llu fragments, more than %s",
                    row, overlap, overlap == 1 ? "" : "s", (unsigned long long)needed, limit);
}

/* The first sweep of a banded frame whose compose needs the whole frame's
 * figures: bands without overlap (a run and its distances are the pixel's
 * own), each filled and sorted and, for the distances, the distance pass;
 * the largest of the bands' longest lists and distances. */
static oit_status ib_sweep(ib_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                           const ib_plan *plan, uint64_t frame_needed, ib_frame_figures *figures,
                           oit_error *err)
{
    const int width = s->gpu.output.width, height = s->gpu.output.height;
    oit_band_walk walk;
    oit_status status = oit_bands_begin(&walk, &s->band_plan, height, 0, frame_needed,
                                        s->pool.capacity, "ib", err);
    if (status != OIT_OK)
        return status;
    figures->longest = figures->largest_distance = 0;
    oit_band band;
    while (status == OIT_OK && oit_bands_next(&walk, &band)) {
        ib_set_band(s, band.first, band.first + band.rows, band.first, band.first + band.rows);
        glScissor(0, band.first, width, band.rows);
        uint64_t needed = 0;
        status = ib_fill_and_count(s, scene, frame, "sweep_", 0, NULL, &needed, err);
        if (status != OIT_OK)
            break;
        if (needed > s->pool.capacity) {
            if (!oit_bands_halve(&walk, &band))
                status = ib_row_error(s, band.first, 0, needed, err);
            continue;
        }
        ib_stage(s, "sweep_", "sort");
        ib_pass(s, IB_SORT, frame, 0);
        if (ib_needs_largest_distance(plan)) {
            ib_stage(s, "sweep_", "distance");
            ib_pass(s, IB_DISTANCE_MAX, frame, 0);
        }
        oit_timer_stage_end(&s->gpu.timer);
        ib_counts unused;
        memset(&unused, 0, sizeof unused);
        GLuint counters[OIT_IB_COUNTER_COUNT];
        status = ib_add_counts(s, needed, &unused, counters, err);
        if (status != OIT_OK)
            break;
        /* float bits of distances >= 0 order like the values */
        if (counters[OIT_FRAME_COUNTER_MAX_LIST] > figures->longest)
            figures->longest = counters[OIT_FRAME_COUNTER_MAX_LIST];
        if (counters[OIT_IB_COUNTER_MAX_DISTANCE] > figures->largest_distance)
            figures->largest_distance = counters[OIT_IB_COUNTER_MAX_DISTANCE];
    }
    oit_bands_end(&walk, NULL, false);
    return status;
}

/* A frame whose fragments exceed what one pool holds (oit_pool_limit: one
 * storage buffer's reach or the memory budget) is drawn in bands of rows under
 * the scissor test (bands.h): each band clears, fills and resolves the rows it
 * composes and ib_band_overlap rows either side, in a pool at the largest size
 * allowed, and composes its own rows; the statistics count those only. Where
 * the compose needs the whole frame's longest list or largest distance, a
 * first sweep finds them (ib_sweep). Ψ and the fragments come from the
 * histogram, the open bin's runs counted by length (OIT_SSBO_IB_LONG_RUNS).
 * frame_needed: the frame's count, or 0 to start from the last frame's bands. */
static oit_status ib_render_bands(ib_state *s, const oit_scene *scene,
                                  const oit_frame_settings *frame, const ib_plan *plan,
                                  uint64_t frame_needed, ib_counts *sum, uint64_t *fragments,
                                  uint64_t *psi_pixels, int *band_count, oit_error *err)
{
    oit_status status = OIT_OK;
    const int width = s->gpu.output.width, height = s->gpu.output.height;
    if (s->pool.capacity < oit_pool_limit(&s->pool)) {
        status = oit_pool_allocate(&s->pool, oit_pool_limit(&s->pool), err);
        if (status != OIT_OK)
            return status;
        ib_bind(s, scene);
    }
    if (!s->long_run_buffer) {
        glGenBuffers(1, &s->long_run_buffer);
        oit_gl_memory_buffer_data(&s->gpu.memory, OIT_GL_MEMORY_FIXED, GL_SHADER_STORAGE_BUFFER,
                                  s->long_run_buffer, OIT_IB_LONG_RUN_LENGTHS * sizeof(GLuint),
                                  NULL, GL_DYNAMIC_READ);
    }
    const GLint banded = 1;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->param_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, offsetof(ib_params, banded), sizeof banded, &banded);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_IB_LONG_RUNS, s->long_run_buffer);
    status = oit_gl_check("ib bands", err);
    if (status != OIT_OK)
        return status;

    glEnable(GL_SCISSOR_TEST);
    ib_frame_figures figures = {0, 0};
    const bool sweep = ib_needs_frame_figures(plan);
    if (sweep) {
        status = ib_sweep(s, scene, frame, plan, frame_needed, &figures, err);
        if (status != OIT_OK) {
            glDisable(GL_SCISSOR_TEST);
            return status;
        }
    }

    /* the long runs of the bands' composed rows (the sweep's sorts count theirs too) */
    const GLuint zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->long_run_buffer);
    glClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);

    const int overlap = ib_band_overlap(plan);
    oit_band_walk walk; /* from the last frame's bands when frame_needed is 0 */
    status = oit_bands_begin(&walk, &s->band_plan, height, overlap, frame_needed, s->pool.capacity,
                             "ib", err);
    if (status != OIT_OK) {
        glDisable(GL_SCISSOR_TEST);
        return status;
    }
    /* the output is cleared once; each band's compose keeps the background of its empty pixels */
    glScissor(0, 0, width, height);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearColor(frame->background[0], frame->background[1], frame->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    *band_count = 0;
    oit_band band;
    while (oit_bands_next(&walk, &band)) {
        ib_set_band(s, band.stored_first, band.stored_first + band.stored_rows, band.first,
                    band.first + band.rows);
        glScissor(0, band.stored_first, width, band.stored_rows);
        uint64_t needed = 0;
        status = ib_fill_and_count(s, scene, frame, "band_", 0, sweep ? &figures : NULL, &needed,
                                   err);
        if (status != OIT_OK)
            break;
        if (needed > s->pool.capacity) {
            if (!oit_bands_halve(&walk, &band)) {
                status = ib_row_error(s, band.first, overlap, needed, err);
                break;
            }
            continue;
        }
        status = ib_resolve(s, scene, frame, plan, true, *band_count == 0, err);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        GLuint counters[OIT_IB_COUNTER_COUNT];
        if (status == OIT_OK)
            status = ib_add_counts(s, needed, sum, counters, err);
        if (status != OIT_OK)
            break;
        ++*band_count;
        oit_bands_fitted(&walk, &band);
    }
    glDisable(GL_SCISSOR_TEST);

    /* the frame's fragments and psi from the histogram: bins below the open
     * one, then the open bin's runs by length */
    *fragments = 0;
    uint64_t psi = 0;
    const uint64_t open_bin = OIT_HISTOGRAM_BINS - 1;
    for (uint64_t bin = 1; bin < open_bin; ++bin) {
        *fragments += bin * sum->histogram[bin];
        if (3 * bin > 2 * sum->longest)
            psi += sum->histogram[bin];
    }
    if (status == OIT_OK && sum->longest >= open_bin) {
        const uint64_t lengths = sum->longest - open_bin + 1;
        GLuint *by_length = malloc(lengths * sizeof *by_length);
        if (!by_length) {
            status = oit_fail(err, OIT_E_RUNTIME, "ib: out of memory reading the long runs");
        } else {
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->long_run_buffer);
            glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)(open_bin * sizeof(GLuint)),
                               (GLsizeiptr)(lengths * sizeof(GLuint)), by_length);
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
            for (uint64_t i = 0; i < lengths; ++i) {
                const uint64_t length = open_bin + i;
                *fragments += length * by_length[i];
                if (3 * length > 2 * sum->longest)
                    psi += by_length[i];
            }
            free(by_length);
        }
    }
    *psi_pixels = psi;
    /* the next frame at this size starts from the bands that fitted, unless this
     * one failed or would have fitted whole with room to spare (the camera moved away) */
    oit_bands_end(&walk, &s->band_plan,
                  status == OIT_OK && *fragments + *fragments / 4 > oit_pool_limit(&s->pool));
    s->band_plan_overlap = overlap;
    return status;
}

static oit_status ib_render(oit_algorithm *alg, const oit_scene *scene,
                            const oit_frame_settings *frame, oit_error *err)
{
    ib_state *s = ib_from(alg);
    oit_status status;
    if (!scene->has_gpu) /* before the triangle table: its size is the scene's */
        return oit_fail(err, OIT_E_INPUT, "ib: the scene has no GPU buffers");
    ib_plan plan;
    status = ib_make_plan(frame, scene, &plan, err);
    if (status != OIT_OK)
        return status;
    if (frame->width != s->gpu.output.width || frame->height != s->gpu.output.height || !s->head_image) {
        status = ib_resize(alg, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }

    status = ib_reserve_triangles(s, scene->index_count / 3u, err);
    if (status != OIT_OK)
        return status;

    status = oit_gpu_frame_begin(&s->gpu, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glBindFramebuffer(GL_FRAMEBUFFER, s->gpu.output.framebuffer);
    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, s->param_buffer);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof plan.params, &plan.params);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    ib_bind(s, scene);
    ib_set_band(s, 0, s->gpu.output.height, 0, s->gpu.output.height);

    /* Fill until the pool holds the whole frame, or draw it in bands of rows
     * when no pool may (straight away when the last frame was banded with the
     * same overlap). */
    int retries = 0, bands = 1;
    uint64_t needed = 0, fragments = 0, psi_pixels = 0;
    ib_counts sum;
    memset(&sum, 0, sizeof sum);
    const bool planned = s->band_plan.count > 0 && s->band_plan_overlap == ib_band_overlap(&plan);
    while (!planned) {
        status = ib_fill_and_count(s, scene, frame, "", retries, NULL, &needed, err);
        if (status != OIT_OK)
            goto failed;
        if (needed <= s->pool.capacity)
            break;
        if (retries + 1 >= IB_MAX_FILLS) {
            status = oit_fail(err, OIT_E_RUNTIME,
                              "ib: the frame still needs %llu fragments after growing the pool to "
                              "%llu",
                              (unsigned long long)needed, (unsigned long long)s->pool.capacity);
            goto failed;
        }
        if (needed > oit_pool_limit(&s->pool)) {
            /* bands, unless even one row per band would be over the pool on average */
            if (needed > (uint64_t)s->gpu.output.height * oit_pool_limit(&s->pool)) {
                char limit[128];
                oit_pool_limit_text(&s->pool, limit, sizeof limit);
                status = oit_fail(err, OIT_E_RUNTIME,
                                  "ib: the frame needs %llu fragments, more than bands of rows "
                                  "can hold: its %d rows need more on average than %s",
                                  (unsigned long long)needed, s->gpu.output.height, limit);
                goto failed;
            }
            break;
        }
        status = oit_pool_grow(&s->pool, needed, err);
        if (status != OIT_OK)
            goto failed;
        ++retries;
    }

    if (planned || needed > s->pool.capacity) {
        status = ib_render_bands(s, scene, frame, &plan, planned ? 0 : needed, &sum, &fragments,
                                 &psi_pixels, &bands, err);
        if (status != OIT_OK)
            goto failed;
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        status = oit_gpu_frame_end(&s->gpu, status, err);
    } else {
        s->band_plan.count = 0;
        status = ib_resolve(s, scene, frame, &plan, false, true, err);
        if (status != OIT_OK)
            goto failed;
        GLuint counters[OIT_IB_COUNTER_COUNT];
        status = oit_gpu_frame_end(&s->gpu, status, err);
        if (status == OIT_OK)
            status = ib_add_counts(s, needed, &sum, counters, err);
        if (status != OIT_OK)
            return status;
        fragments = counters[OIT_FRAME_COUNTER_FRAGMENTS];
        psi_pixels = counters[OIT_IB_COUNTER_PSI_PIXELS]; /* compose counted them */
    }
    ib_frame_stats(s, &sum, fragments, psi_pixels, retries, bands, &s->gpu.stats);
    return status;

failed:
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    return oit_gpu_frame_end(&s->gpu, status, err);
}

/* ib renders every view, modulation and distance. */
static const oit_capabilities ib_capabilities = {
    .options = OIT_OPTION_FRAGMENT_POOL | OIT_OPTION_MAX_MEMORY,
};

const oit_algorithm_ops oit_algorithm_ib = {
    .name = "ib",
    .summary = "Illustration Buffer: sorted runs with surface neighbours; opacity modulation",
    .uses_gl = true,
    .exact = true,
    .capabilities = &ib_capabilities,
    .create = ib_create,
    .resize = ib_resize,
    .render = ib_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = ib_destroy,
};
