/*
 * alg_dp.c: depth peeling (Everitt 2001), front to back.
 *
 * Every layer costs one geometry pass. The peel shader discards fragments at
 * or before the previous layer in (depth, triangle) order (see "Equal depths"
 * below); the ordinary depth test (LESS) then keeps the nearest of the rest,
 * whose colour lands in the layer target. A full-screen pass blends the layer under the float
 * accumulation (rgb = premultiplied colour so far, a = transmittance T). The
 * loop ends when an occlusion query sees no samples or at the layer limit;
 * a final pass adds T * background and writes the RGBA8 output. By default
 * there is no layer limit; with an explicit cap (config.max_layers) a pass
 * that reaches it probes once more and marks the frame truncated if any
 * fragment was left.
 *
 * Distance modulation (docs/modulation.md): a layer's opacity is its distance
 * along the ray to the next layer, known only once that layer is peeled. So the
 * peel writes the straight colour and the local factor, and blending is delayed
 * by one layer: after peeling layer k, blend_distance blends layer k-1 (a second
 * layer-colour target keeps it). Same number of geometry passes; the last layer
 * of a pixel gets distance 0. Only the adjacent distance: skip and far-end
 * distances need more than one layer behind (lists: ll, ib). With an automatic
 * focus region the frame's largest distance must be known before anything is
 * blended, so a first sweep peels every layer and MAX-blends the distances into
 * an R32F target: twice the geometry passes.
 *
 * Curvature (docs/modulation.md, "Non-local modulations"): the approximation
 * peeling allows. The Illustration Buffer finds a fragment's neighbours through
 * the surface in the adjacent pixels' lists; a peeled layer has one fragment
 * per pixel, so the neighbour here is the same layer's fragment in the adjacent
 * pixel, if it is on the same component. The peel (dp/peel.frag with DP_NEIGHBOURS)
 * also writes the layer's octahedral normal and component into an RG32UI
 * target, and the layer's blend pass becomes dp/blend_curvature.frag, which
 * computes the curvature exactly as ib does from those neighbours: same passes,
 * + two RG32UI targets. dist-curv combines it with the delayed blending above
 * (each layer is blended after the next one is peeled; after the last peel the
 * last layer is blended too, as its curvature may make it visible). Edges
 * (opaque where a fragment has fewer than four neighbours) use the same
 * neighbours in the same pass. Transparency fields are refused: they diffuse
 * over the whole surface, across layers.
 *
 * Equal depths: layers follow (depth, triangle index), the order of every
 * exact algorithm and the reference, so coincident faces are not lost as in
 * plain depth peeling, whose strict "behind the previous layer" test keeps
 * one of them. Depth is oit_canonical_depth() (common/canonical_depth.glsl:
 * each coplanar cluster's plane at the pixel centre), so faces in one plane
 * tie exactly. The peel also writes the winner's triangle index into a tie
 * target (R32UI, two in turn like the depth textures), and a fragment is a
 * candidate when it comes after the previous layer's (depth, triangle). Among
 * candidates at equal depth the depth test LESS keeps the first drawn, which
 * is the lowest triangle (GL applies per-fragment tests in primitive order;
 * the model is one draw call), so one geometry pass per layer still suffices.
 * (The z-fighting-aware variants of Vasilakis & Fudos 2011 count coplanar
 * fragments instead; this needs no counter and handles any number of them.)
 */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

_Static_assert(OIT_IB_MODE_CURVATURE == OIT_MODULATE_CURVATURE &&
                   OIT_IB_MODE_DIST_CURV == OIT_MODULATE_DIST_CURV &&
                   OIT_IB_MODE_EDGES == OIT_MODULATE_EDGES,
               "blend_curvature.frag's modes differ from oit_modulation_mode");

typedef struct dp_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */

    GLuint peel_program;    /* geometry.vert + dp/peel.frag */
    GLuint blend_program;   /* fullscreen.vert + dp/blend_layer.frag */
    GLuint compose_program; /* fullscreen.vert + dp/compose.frag */
    GLuint samples_query;   /* GL_ANY_SAMPLES_PASSED of the peel pass */
    GLuint blend_distance_program; /* fullscreen.vert + dp/blend_distance.frag */
    GLuint distance_max_program;   /* fullscreen.vert + dp/blend_distance.frag, DISTANCE_MAX */
    GLuint peel_neighbours_program; /* geometry.vert + dp/peel.frag, DP_NEIGHBOURS */
    GLuint blend_curvature_program; /* fullscreen.vert + dp/blend_curvature.frag */

    /* Two (depth, triangle) pairs used in turn: one is read (previous layer)
     * while the other is written by the current peel: depth[i] its depth
     * attachment, tie[i] its colour attachment OIT_DP_TIE_LOCATION. */
    GLuint depth[2];          /* GL_DEPTH_COMPONENT32F */
    GLuint tie[2];            /* GL_R32UI: the layer's triangle index */
    GLuint layer_colour;      /* GL_RGBA32F, premultiplied layer colour, in both peel FBOs */
    GLuint peel_framebuffer[2];
    /* distance modulation only (allocated on first use): peel FBO i writes
     * distance_colour[i], so layer k-1 is still there after peeling layer k;
     * distance_max (R32F) collects the largest distance of the first sweep */
    bool distance_targets;
    GLuint distance_colour[2];
    GLuint distance_peel_framebuffer[2];
    GLuint distance_max;
    GLuint distance_max_framebuffer;
    /* curvature and dist-curv only (allocated on first use): each layer's
     * octahedral normal and component + 1 (RG32UI, one per peel FBO), written
     * beside layer_colour (curvature) or distance_colour[i] (dist-curv) */
    bool normal_targets;
    GLuint layer_normal[2];
    GLuint curvature_peel_framebuffer[2]; /* layer_colour, layer_normal[i], tie[i], depth[i] */
    GLuint dist_curv_peel_framebuffer[2]; /* distance_colour[i], layer_normal[i], tie[i], depth[i] */
    GLuint accumulation;      /* GL_RGBA32F: rgb = sum T*a*c, a = T */
    GLuint accumulation_framebuffer;
} dp_state;

/* A screen-sized target, recorded in s->gpu.memory. Per pixel: 2 depth and 2 tie
 * (4 each), the layer colour and the accumulation (16 each), the RGBA8 output
 * (4); with the distance modulation two layer colours (16 each) and the R32F
 * maximum; with curvature two RG32UI normal + component targets (8 each). */
static void dp_release_targets(dp_state *s)
{
    glDeleteFramebuffers(2, s->peel_framebuffer);
    glDeleteFramebuffers(1, &s->accumulation_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->depth);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->tie);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->layer_colour);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->accumulation);
    glDeleteFramebuffers(2, s->distance_peel_framebuffer);
    glDeleteFramebuffers(1, &s->distance_max_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->distance_colour);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->distance_max);
    glDeleteFramebuffers(2, s->curvature_peel_framebuffer);
    glDeleteFramebuffers(2, s->dist_curv_peel_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->layer_normal);
    for (int i = 0; i < 2; ++i)
        s->peel_framebuffer[i] = s->depth[i] = s->tie[i] = s->distance_peel_framebuffer[i] =
            s->distance_colour[i] = s->layer_normal[i] = s->curvature_peel_framebuffer[i] =
                s->dist_curv_peel_framebuffer[i] = 0;
    s->distance_max = s->distance_max_framebuffer = 0;
    s->layer_colour = s->accumulation_framebuffer = s->accumulation = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

static void dp_destroy(oit_algorithm *alg);

static oit_status dp_create(const oit_algorithm_config *config, oit_algorithm **out,
                            oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(dp_state), "dp", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    dp_state *s = (dp_state *)gpu;
    glGenQueries(1, &s->samples_query);

    status =
        oit_gpu_program(&s->gpu, "common/geometry.vert", "dp/peel.frag",
                       &s->peel_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert",
                                "dp/blend_layer.frag", &s->blend_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "dp/compose.frag",
                                &s->compose_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert",
                                "dp/blend_distance.frag", &s->blend_distance_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/fullscreen.vert", "dp/blend_distance.frag",
                                         "#define DISTANCE_MAX 1\n", &s->distance_max_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/geometry.vert", "dp/peel.frag",
                                         "#define DP_NEIGHBOURS 1\n", &s->peel_neighbours_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert",
                                "dp/blend_curvature.frag", &s->blend_curvature_program, err);
    return oit_gpu_created(&s->gpu, status, dp_destroy, out, err);
}

static oit_status dp_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    dp_state *s = (dp_state *)alg;
    dp_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    /* every peel framebuffer: colour 0, (normal 1,) tie OIT_DP_TIE_LOCATION */
    _Static_assert(OIT_DP_TIE_LOCATION == 2, "the target lists below put the tie at 2");
    s->layer_colour = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    for (int i = 0; i < 2 && status == OIT_OK; ++i) {
        s->depth[i] = oit_gpu_target(&s->gpu, GL_DEPTH_COMPONENT32F, width, height);
        s->tie[i] = oit_gpu_target(&s->gpu, GL_R32UI, width, height);
        const GLuint peel[3] = {s->layer_colour, 0, s->tie[i]};
        status = oit_gpu_framebuffer(&s->gpu, &s->peel_framebuffer[i], "peel", peel, 3, s->depth[i], width,
                                     height, err);
    }
    if (status == OIT_OK) {
        s->accumulation = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
        status = oit_gpu_framebuffer(&s->gpu, &s->accumulation_framebuffer, "accumulation", &s->accumulation, 1,
                                     0, width, height, err);
    }
    for (int i = 0; status == OIT_OK && s->distance_targets && i < 2; ++i) {
        s->distance_colour[i] = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
        const GLuint distance_peel[3] = {s->distance_colour[i], 0, s->tie[i]};
        status = oit_gpu_framebuffer(&s->gpu, &s->distance_peel_framebuffer[i], "distance peel", distance_peel, 3,
                                     s->depth[i], width, height, err);
    }
    if (status == OIT_OK && s->distance_targets) {
        s->distance_max = oit_gpu_target(&s->gpu, GL_R32F, width, height);
        status = oit_gpu_framebuffer(&s->gpu, &s->distance_max_framebuffer, "distance maximum", &s->distance_max,
                                     1, 0, width, height, err);
    }
    for (int i = 0; status == OIT_OK && s->normal_targets && i < 2; ++i) {
        s->layer_normal[i] = oit_gpu_target(&s->gpu, GL_RG32UI, width, height);
        const GLuint curvature_peel[3] = {s->layer_colour, s->layer_normal[i], s->tie[i]};
        status = oit_gpu_framebuffer(&s->gpu, &s->curvature_peel_framebuffer[i], "curvature peel", curvature_peel,
                                     3, s->depth[i], width, height, err);
        if (status != OIT_OK || !s->distance_targets)
            continue;
        const GLuint dist_curv_peel[3] = {s->distance_colour[i], s->layer_normal[i], s->tie[i]};
        status = oit_gpu_framebuffer(&s->gpu, &s->dist_curv_peel_framebuffer[i], "dist-curv peel", dist_curv_peel,
                                     3, s->depth[i], width, height, err);
    }
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        dp_release_targets(s);
    return status;
}

/* What one peeling sweep does with each layer. */
typedef enum dp_sweep {
    DP_SWEEP_PLAIN,          /* blend layer k after peeling it */
    DP_SWEEP_CURVATURE,      /* curvature: blend layer k after peeling it, opacity from its neighbours */
    DP_SWEEP_DISTANCE_MAX,   /* distance modulation, first sweep: largest distance only */
    DP_SWEEP_DISTANCE_BLEND  /* distance (or dist-curv): blend layer k-1 after peeling layer k */
} dp_sweep;

/* Whether the frame's modulation needs each layer's neighbours (normal targets). */
static bool dp_needs_neighbours(const oit_frame_settings *frame)
{
    return frame->modulation.mode == OIT_MODULATE_CURVATURE ||
           frame->modulation.mode == OIT_MODULATE_DIST_CURV ||
           frame->modulation.mode == OIT_MODULATE_EDGES;
}

/* Blend a peeled layer (straight colour and local factor in target `colour`,
 * normals in `normal`) under the accumulation with blend_curvature.frag. With
 * dist-curv, `next_colour`/`next_depth` hold the layer peeled after it and
 * `depth` its own depth. */
static void dp_blend_curvature(dp_state *s, const oit_frame_settings *frame, GLuint colour,
                               GLuint normal, GLuint depth, GLuint next_colour, GLuint next_depth,
                               float distance_norm)
{
    const oit_modulation *m = &frame->modulation;
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulation_framebuffer);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(s->blend_curvature_program);
    const oit_modulation resolved = oit_modulation_defaults(m);
    glUniform1f(OIT_UNIFORM_DP_CURVATURE_EFFECT, resolved.curvature_effect);
    glUniform1i(OIT_UNIFORM_DP_CURVATURE_NEIGHBOURS, resolved.curvature_neighbours);
    const bool dist_curv = m->mode == OIT_MODULATE_DIST_CURV;
    /* oit_modulation_mode and OIT_IB_MODE_* share their values */
    glUniform1i(OIT_UNIFORM_DP_NEIGHBOUR_MODE, (GLint)m->mode);
    if (dist_curv)
        oit_gpu_set_distance_norm(&s->gpu, distance_norm);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_LAYER);
    glBindTexture(GL_TEXTURE_2D, colour);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_NORMAL);
    glBindTexture(GL_TEXTURE_2D, normal);
    /* curvature alone: the dist-curv samplers are unused but must not be the
     * target being drawn, so they get the layer's own textures */
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_PREVIOUS);
    glBindTexture(GL_TEXTURE_2D, dist_curv ? depth : s->depth[0]);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_NEXT_LAYER);
    glBindTexture(GL_TEXTURE_2D, dist_curv ? next_colour : colour);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_NEXT);
    glBindTexture(GL_TEXTURE_2D, dist_curv ? next_depth : s->depth[1]);
    oit_gl_draw_fullscreen(&s->gpu.output);
    glDisable(GL_BLEND);
}

/* The peel of layer `layer` into the bound framebuffer (depth test LESS,
 * after the previous layer in (depth, triangle) order); waits for and
 * returns whether any fragment passed. Waiting is inherent to the algorithm:
 * the next pass depends on it. */
static bool dp_draw_peel(dp_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                         GLuint program, int layer)
{
    const int previous = (layer & 1) ^ 1;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(program);
    glUniform1i(OIT_UNIFORM_DP_HAS_PREVIOUS, layer > 0);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_PREVIOUS);
    glBindTexture(GL_TEXTURE_2D, s->depth[previous]);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_TIE_PREVIOUS);
    glBindTexture(GL_TEXTURE_2D, s->tie[previous]);
    glBeginQuery(GL_ANY_SAMPLES_PASSED, s->samples_query);
    oit_gl_draw_scene(scene);
    glEndQuery(GL_ANY_SAMPLES_PASSED);
    glDisable(GL_DEPTH_TEST);
    GLuint any_samples = 0;
    glGetQueryObjectuiv(s->samples_query, GL_QUERY_RESULT, &any_samples);
    return any_samples != 0;
}

/* After the cap: is any fragment left behind layer `layers - 1`? One more
 * peel test with colour and depth writes off, only when the cap was reached. */
static bool dp_fragments_left(dp_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                              int layers)
{
    static const GLfloat far_depth = 1.0f;
    glBindFramebuffer(GL_FRAMEBUFFER, s->peel_framebuffer[layers & 1]);
    glDepthMask(GL_TRUE);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    bool left = dp_draw_peel(s, scene, frame, s->peel_program, layers);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    return left;
}

static oit_status dp_peel_sweep(dp_state *s, const oit_scene *scene, const oit_frame_settings *frame,
                                dp_sweep sweep, float distance_norm, int *layers_out,
                                bool *truncated, oit_error *err)
{
    static const GLfloat empty_layer[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    static const GLuint no_normal[4] = {0u, 0u, 0u, 0u}; /* component + 1 = 0: no fragment */
    static const GLfloat far_depth = 1.0f;
    static const GLuint no_triangle[4] = {UINT32_MAX, 0u, 0u, 0u}; /* after every triangle */
    const bool distance = sweep == DP_SWEEP_DISTANCE_MAX || sweep == DP_SWEEP_DISTANCE_BLEND;
    const bool neighbours = dp_needs_neighbours(frame);
    const char *prefix = sweep == DP_SWEEP_DISTANCE_MAX ? "distance_peel" : "peel";
    /* no cap: every pass peels one more layer of some pixel, so the loop ends
     * after the deepest pixel's last layer */
    const int limit = s->gpu.config.max_layers > 0 ? s->gpu.config.max_layers : INT_MAX;
    int layers = 0;
    bool last_had_samples = false;
    oit_status status = OIT_OK;
    for (int layer = 0; layer < limit; ++layer) {
        char stage[OIT_STAGE_NAME_SIZE];
        snprintf(stage, sizeof stage, "%s_%d", prefix, layer);
        oit_timer_stage_begin(&s->gpu.timer, stage);
        const int current = layer & 1, previous = current ^ 1;

        /* Peel: the next fragment after the previous layer in (depth, triangle) order. */
        GLuint framebuffer = s->peel_framebuffer[current];
        if (sweep == DP_SWEEP_CURVATURE)
            framebuffer = s->curvature_peel_framebuffer[current];
        else if (distance)
            framebuffer = neighbours ? s->dist_curv_peel_framebuffer[current]
                                     : s->distance_peel_framebuffer[current];
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glDepthMask(GL_TRUE); /* before the clears: a mask left false by another algorithm blocks them */
        glClearBufferfv(GL_COLOR, 0, empty_layer);
        if (neighbours)
            glClearBufferuiv(GL_COLOR, 1, no_normal);
        glClearBufferuiv(GL_COLOR, OIT_DP_TIE_LOCATION, no_triangle);
        glClearBufferfv(GL_DEPTH, 0, &far_depth);
        const bool any_samples = dp_draw_peel(
            s, scene, frame, neighbours ? s->peel_neighbours_program : s->peel_program, layer);
        if (any_samples)
            ++layers;
        last_had_samples = any_samples;
        if (any_samples && sweep == DP_SWEEP_PLAIN) {
            /* Blend the layer under the accumulation: rgb += T * (a c), T *= 1 - a. */
            glBindFramebuffer(GL_FRAMEBUFFER, s->accumulation_framebuffer);
            glEnable(GL_BLEND);
            glBlendEquation(GL_FUNC_ADD);
            glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
            glUseProgram(s->blend_program);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_LAYER);
            glBindTexture(GL_TEXTURE_2D, s->layer_colour);
            oit_gl_draw_fullscreen(&s->gpu.output);
            glDisable(GL_BLEND);
        } else if (any_samples && sweep == DP_SWEEP_CURVATURE) {
            /* The whole layer is peeled: each fragment's neighbours are known. */
            dp_blend_curvature(s, frame, s->layer_colour, s->layer_normal[current], 0, 0, 0,
                               distance_norm);
        } else if (sweep == DP_SWEEP_DISTANCE_BLEND && neighbours && layer > 0) {
            /* dist-curv: layer k-1 now knows its distance and its neighbours; blended
             * even when layer k is empty, as its curvature may still show it */
            dp_blend_curvature(s, frame, s->distance_colour[previous], s->layer_normal[previous],
                               s->depth[previous], s->distance_colour[current], s->depth[current],
                               distance_norm);
        } else if (any_samples && layer > 0) {
            /* Layer k-1 now knows its distance to layer k: blend it (or take the maximum). */
            glEnable(GL_BLEND);
            if (sweep == DP_SWEEP_DISTANCE_MAX) {
                glBindFramebuffer(GL_FRAMEBUFFER, s->distance_max_framebuffer);
                glBlendEquation(GL_MAX);
                glBlendFunc(GL_ONE, GL_ONE);
                glUseProgram(s->distance_max_program);
            } else {
                glBindFramebuffer(GL_FRAMEBUFFER, s->accumulation_framebuffer);
                glBlendEquation(GL_FUNC_ADD);
                glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
                glUseProgram(s->blend_distance_program);
            }
            oit_gpu_set_distance_norm(&s->gpu, distance_norm);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_LAYER);
            glBindTexture(GL_TEXTURE_2D, s->distance_colour[previous]);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_PREVIOUS);
            glBindTexture(GL_TEXTURE_2D, s->depth[previous]);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_NEXT_LAYER);
            glBindTexture(GL_TEXTURE_2D, s->distance_colour[current]);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_NEXT);
            glBindTexture(GL_TEXTURE_2D, s->depth[current]);
            oit_gl_draw_fullscreen(&s->gpu.output);
            glBlendEquation(GL_FUNC_ADD);
            glDisable(GL_BLEND);
        }
        /* With no layer k, every layer k-1 was its pixel's last: distance 0, nothing to blend. */
        oit_timer_stage_end(&s->gpu.timer);
        if ((status = oit_gpu_stage_check(&s->gpu, stage, err)) != OIT_OK)
            break;
        if (!any_samples)
            break;
    }
    if (status == OIT_OK && layers == limit && last_had_samples) {
        oit_timer_stage_begin(&s->gpu.timer, "cap_probe");
        *truncated = *truncated || dp_fragments_left(s, scene, frame, layers);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "cap_probe", err);
    }
    if (status == OIT_OK && sweep == DP_SWEEP_DISTANCE_BLEND && neighbours && last_had_samples) {
        /* dist-curv stopped by the layer limit: the last layer peeled still has to
         * be blended, with no next layer (the other colour target, cleared) */
        oit_timer_stage_begin(&s->gpu.timer, "blend_last_layer");
        const int last = (layers - 1) & 1, other = last ^ 1;
        glBindFramebuffer(GL_FRAMEBUFFER, s->dist_curv_peel_framebuffer[other]);
        glClearBufferfv(GL_COLOR, 0, empty_layer);
        dp_blend_curvature(s, frame, s->distance_colour[last], s->layer_normal[last],
                           s->depth[last], s->distance_colour[other], s->depth[other],
                           distance_norm);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, "blend_last_layer", err);
    }
    *layers_out = layers;
    return status;
}

/* The distance modulation's normalising length: the focus region, or the
 * frame's largest distance (a first sweep; 1 if there is none). */
static oit_status dp_distance_norm(dp_state *s, const oit_scene *scene,
                                   const oit_frame_settings *frame, float *norm, oit_error *err)
{
    *norm = frame->modulation.focus_region;
    if (*norm > 0.0f)
        return OIT_OK;
    static const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glBindFramebuffer(GL_FRAMEBUFFER, s->distance_max_framebuffer);
    glClearBufferfv(GL_COLOR, 0, zero);
    int layers = 0;
    oit_status status = dp_peel_sweep(s, scene, frame, DP_SWEEP_DISTANCE_MAX, 1.0f, &layers,
                                      &s->gpu.stats.truncated, err);
    if (status != OIT_OK)
        return status;
    return oit_gpu_read_largest(&s->gpu, s->distance_max_framebuffer, norm, err);
}

static oit_status dp_render(oit_algorithm *alg, const oit_scene *scene,
                            const oit_frame_settings *frame, oit_error *err)
{
    dp_state *s = (dp_state *)alg;
    const oit_modulation *m = &frame->modulation;
    /* dist-curv needs the distance (delayed blending) and the neighbours */
    const bool distance = m->mode == OIT_MODULATE_DISTANCE || m->mode == OIT_MODULATE_DIST_CURV;
    const bool neighbours = dp_needs_neighbours(frame);
    if (frame->width != s->gpu.output.width || frame->height != s->gpu.output.height ||
        (distance && !s->distance_targets) || (neighbours && !s->normal_targets)) {
        s->distance_targets = s->distance_targets || distance;
        s->normal_targets = s->normal_targets || neighbours;
        oit_status status = dp_resize(alg, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }
    oit_status status = oit_gpu_frame_begin(&s->gpu, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_CULL_FACE); /* both sides of every surface are layers */
    glDisable(GL_BLEND);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);

    float distance_norm = 1.0f;
    if (distance)
        status = dp_distance_norm(s, scene, frame, &distance_norm, err);

    static const GLfloat empty_accumulation[4] = {0.0f, 0.0f, 0.0f, 1.0f}; /* C = 0, T = 1 */
    glBindFramebuffer(GL_FRAMEBUFFER, s->accumulation_framebuffer);
    glClearBufferfv(GL_COLOR, 0, empty_accumulation);

    int layers = 0;
    if (status == OIT_OK)
        status = dp_peel_sweep(s, scene, frame,
                               distance     ? DP_SWEEP_DISTANCE_BLEND
                               : neighbours ? DP_SWEEP_CURVATURE
                                            : DP_SWEEP_PLAIN,
                               distance_norm, &layers, &s->gpu.stats.truncated, err);

    const oit_texture_unit composed[] = {{OIT_TEXUNIT_ACCUM_FRONT, s->accumulation}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed,
                                      1, err);

    s->gpu.stats.layers = layers;
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static void dp_destroy(oit_algorithm *alg)
{
    dp_state *s = (dp_state *)alg;
    if (!s)
        return;
    dp_release_targets(s);
    glDeleteQueries(1, &s->samples_query);
    oit_gpu_destroy(&s->gpu);
}

/* dp knows the previous layer's depth (the adjacent distance) and, in a
 * layer, the neighbouring pixels' fragments of that layer (curvature, edges);
 * nothing further along the ray nor across layers. */
static const oit_capabilities dp_capabilities = {
    .modulations = {[OIT_MODULATE_FIELDS] = OIT_NEEDS_NEIGHBOURS(
                        "the fields diffuse over the whole surface, across layers, and a peeled layer is gone once "
                        "blended; dp does the local ones, the adjacent distance, and curvature and edges from "
                        "neighbours in the same layer")},
    .distances = {OIT_ADJACENT_DISTANCE_ONLY("skip and far-end distances need layers further behind than the last "
                                             "one peeled (use ll, ib or reference)")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_MAX_LAYERS,
};

const oit_algorithm_ops oit_algorithm_dp = {
    .name = "dp",
    .summary = "depth peeling (Everitt 2001): one geometry pass per layer, front to back",
    .uses_gl = true,
    .exact = true,
    .capabilities = &dp_capabilities,
    .create = dp_create,
    .resize = dp_resize,
    .render = dp_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = dp_destroy,
};
