/*
 * alg_ddp.c: dual depth peeling (Bavoil & Myers 2008).
 *
 * A min-max target (RG32F, MAX blending of (-z, z)) holds the nearest and the
 * farthest depth not yet peeled. The "init" pass fills it from all fragments.
 * Each peel pass reads it (ping-pong between two targets) and, per fragment:
 * - outside [near, far]: already peeled, discarded;
 * - strictly inside: passed on into the next min-max target;
 * - equal to near: shaded and blended under the front accumulation;
 * - otherwise equal to far: shaded and blended under this pass's back layer,
 *   which a full-screen pass then puts over the back accumulation.
 * So one geometry pass peels two layers: N layers take N/2 + 1 passes with the
 * init pass. A tiny full-screen probe with occlusion queries after each pass
 * tells whether any pixel has layers left (and whether any has two distinct
 * depths left, for the layer count), so no extra empty geometry pass is needed.
 * There is no layer limit by default; with an explicit cap (config.max_layers)
 * the same probe says whether the cap left layers behind (stats.truncated).
 * "compose" joins front, back and background.
 *
 * Distance modulation (docs/modulation.md), the "delayed blending" variant: a
 * layer's opacity needs the next fragment along the ray. A front layer's next
 * is the nearest fragment left for later (known once the pass has written the
 * next min-max target), a back layer's is the previous pass's back layer. So
 * the peel pass stores both layers unblended (straight colour, local factor)
 * and a full-screen pass after it (ddp/blend_distance.frag) computes their
 * opacities and blends them, keeping the far depth for the next pass (R32F,
 * ping-pong). Coplanar fragments peeled together are merged in drawing order
 * (an approximation; the reference gives all but the last of them distance 0).
 * With an automatic focus region a first sweep finds the largest distance.
 *
 * Equal depths, as in the original: every fragment whose depth equals the near
 * (or far) depth is peeled in the same pass. Unlike the original, which keeps
 * the MAX of the front colours, these fragments are blended (front layer and
 * the per-pass back layer both under, in drawing order = triangle order), so
 * coplanar fragments are all composited in (depth, triangle index) order, like
 * the reference. Plain depth peeling (dp) keeps only one of them.
 */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>

#include "capabilities.h"
#include "gpu_algorithm.h"

typedef struct ddp_state {
    oit_gpu_algorithm gpu; /* first: configuration, output, memory, timer, statistics, programs */

    GLuint init_program;    /* geometry.vert + ddp/init.frag */
    GLuint peel_program;    /* geometry.vert + ddp/peel.frag */
    GLuint back_program;    /* fullscreen.vert + ddp/blend_back.frag */
    GLuint probe_program;   /* fullscreen.vert + ddp/probe.frag */
    GLuint compose_program; /* fullscreen.vert + ddp/compose.frag */
    GLuint probe_queries[2]; /* GL_ANY_SAMPLES_PASSED: layers left, two depths left */

    /* Min-max targets used in turn: a pass reads one and writes the other. */
    GLuint minmax[2];       /* GL_RG32F: (-near, far) */
    GLuint front;           /* GL_RGBA32F: rgb = sum T*a*c front to back, a = T */
    GLuint back_layer;      /* GL_RGBA32F: this pass's back layer, same layout */
    GLuint back;            /* GL_RGBA32F: the back layers so far, same layout */
    /* colour attachments: 0 = minmax[i], 1 = front, 2 = back_layer */
    GLuint peel_framebuffer[2];
    GLuint back_framebuffer; /* back */
    /* distance modulation only (allocated on first use) */
    GLuint distance_programs[2]; /* ddp/blend_distance.frag, the same with DISTANCE_MAX */
    bool distance_targets;
    GLuint front_layer;          /* GL_RGBA32F: this pass's front layer, rgb + local factor */
    GLuint previous_far[2];      /* GL_R32F: far depth of the last back layer, < 0: none */
    GLuint distance_max;         /* GL_R32F: largest distance (MAX) */
    GLuint distance_peel_framebuffer[2]; /* minmax[i], front_layer, back_layer */
    GLuint distance_blend_framebuffer[2]; /* front, back, previous_far[i] */
    GLuint distance_max_framebuffer[2];   /* distance_max, previous_far[i] */
} ddp_state;

/* A screen-sized target, recorded in s->gpu.memory. Per pixel: 2 min-max (8
 * each), front, back layer and back (16 each), the RGBA8 output (4); with the
 * distance modulation the front layer (16), two far depths and the maximum (4
 * each). */
/* Cleared min-max: nothing left (near > far); loses every MAX. */
#define DDP_EMPTY_DEPTH (-1.0e30f)

static void ddp_release_targets(ddp_state *s)
{
    glDeleteFramebuffers(2, s->peel_framebuffer);
    glDeleteFramebuffers(1, &s->back_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->minmax);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->front);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->back_layer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->back);
    for (int i = 0; i < 2; ++i)
        s->peel_framebuffer[i] = s->minmax[i] = 0;
    s->back_framebuffer = s->front = s->back_layer = s->back = 0;
    glDeleteFramebuffers(2, s->distance_peel_framebuffer);
    glDeleteFramebuffers(2, s->distance_blend_framebuffer);
    glDeleteFramebuffers(2, s->distance_max_framebuffer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 2, s->previous_far);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->front_layer);
    oit_gl_memory_delete_textures(&s->gpu.memory, 1, &s->distance_max);
    for (int i = 0; i < 2; ++i)
        s->distance_peel_framebuffer[i] = s->distance_blend_framebuffer[i] =
            s->distance_max_framebuffer[i] = s->previous_far[i] = 0;
    s->front_layer = s->distance_max = 0;
    s->gpu.output.width = s->gpu.output.height = 0;
}

static void ddp_destroy(oit_algorithm *alg);

static oit_status ddp_create(const oit_algorithm_config *config, oit_algorithm **out,
                             oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu;
    oit_status status = oit_gpu_create(sizeof(ddp_state), "ddp", config, &gpu, err);
    if (status != OIT_OK)
        return status;
    ddp_state *s = (ddp_state *)gpu;
    glGenQueries(2, s->probe_queries);

    status =
        oit_gpu_program(&s->gpu, "common/geometry.vert", "ddp/init.frag", &s->init_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/geometry.vert", "ddp/peel.frag", &s->peel_program,
                                err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "ddp/blend_back.frag",
                                &s->back_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "ddp/probe.frag",
                                &s->probe_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "ddp/compose.frag",
                                &s->compose_program, err);
    if (status == OIT_OK)
        status = oit_gpu_program(&s->gpu, "common/fullscreen.vert", "ddp/blend_distance.frag",
                                &s->distance_programs[0], err);
    if (status == OIT_OK)
        status = oit_gpu_program_variant(&s->gpu, "common/fullscreen.vert", "ddp/blend_distance.frag",
                                         "#define DISTANCE_MAX 1\n", &s->distance_programs[1], err);
    return oit_gpu_created(&s->gpu, status, ddp_destroy, out, err);
}

static oit_status ddp_resize(oit_algorithm *alg, int width, int height, oit_error *err)
{
    ddp_state *s = (ddp_state *)alg;
    ddp_release_targets(s);
    oit_status status = oit_gl_output_resize(&s->gpu.output, width, height, err);
    if (status != OIT_OK)
        return status;

    s->front = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    s->back_layer = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    s->back = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
    for (int i = 0; i < 2 && status == OIT_OK; ++i) {
        s->minmax[i] = oit_gpu_target(&s->gpu, GL_RG32F, width, height);
        const GLuint peel[3] = {s->minmax[i], s->front, s->back_layer};
        status = oit_gpu_framebuffer(&s->gpu, &s->peel_framebuffer[i], "peel", peel, 3, 0, width, height, err);
    }
    if (status == OIT_OK)
        status = oit_gpu_framebuffer(&s->gpu, &s->back_framebuffer, "back", &s->back, 1, 0, width, height, err);
    if (status == OIT_OK && s->distance_targets) {
        s->front_layer = oit_gpu_target(&s->gpu, GL_RGBA32F, width, height);
        s->distance_max = oit_gpu_target(&s->gpu, GL_R32F, width, height);
        for (int i = 0; i < 2 && status == OIT_OK; ++i) {
            s->previous_far[i] = oit_gpu_target(&s->gpu, GL_R32F, width, height);
            const GLuint distance_peel[3] = {s->minmax[i], s->front_layer, s->back_layer};
            const GLuint distance_blend[3] = {s->front, s->back, s->previous_far[i]};
            const GLuint distance_max[2] = {s->distance_max, s->previous_far[i]};
            status = oit_gpu_framebuffer(&s->gpu, &s->distance_peel_framebuffer[i], "distance peel",
                                         distance_peel, 3, 0, width, height, err);
            if (status == OIT_OK)
                status = oit_gpu_framebuffer(&s->gpu, &s->distance_blend_framebuffer[i], "distance blend",
                                             distance_blend, 3, 0, width, height, err);
            if (status == OIT_OK)
                status = oit_gpu_framebuffer(&s->gpu, &s->distance_max_framebuffer[i], "distance maximum",
                                             distance_max, 2, 0, width, height, err);
        }
    }
    status = oit_gpu_resize_end(&s->gpu, status, width, height, err);
    if (status != OIT_OK)
        ddp_release_targets(s);
    return status;
}

/* The blending of the peel framebuffer's three targets, for init and peel. */
static void ddp_enable_peel_blending(void)
{
    glEnable(GL_BLEND);
    glBlendEquationi(0, GL_MAX); /* (-near, far) */
    for (GLuint target = 1; target <= 2; ++target) {
        /* under: rgb += T * (a c), T *= 1 - a; the shader writes 0 to leave it alone */
        glBlendEquationi(target, GL_FUNC_ADD);
        glBlendFuncSeparatei(target, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    }
}

/* Probe min-max target `index`: any pixel with layers left, any with two
 * distinct depths left. Waits for the answers. */
static void ddp_probe(ddp_state *s, int index, bool *any_left, bool *two_left)
{
    /* The back framebuffer is bound only to have a target; nothing is written. */
    glBindFramebuffer(GL_FRAMEBUFFER, s->back_framebuffer);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(s->probe_program);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_MINMAX);
    glBindTexture(GL_TEXTURE_2D, s->minmax[index]);
    for (int two = 0; two < 2; ++two) {
        glUniform1i(OIT_UNIFORM_DDP_PROBE_TWO, two);
        glBeginQuery(GL_ANY_SAMPLES_PASSED, s->probe_queries[two]);
        oit_gl_draw_fullscreen(&s->gpu.output);
        glEndQuery(GL_ANY_SAMPLES_PASSED);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    GLuint result[2] = {0, 0};
    glGetQueryObjectuiv(s->probe_queries[0], GL_QUERY_RESULT, &result[0]);
    glGetQueryObjectuiv(s->probe_queries[1], GL_QUERY_RESULT, &result[1]);
    *any_left = result[0] != 0;
    *two_left = result[1] != 0;
}

/* What one peeling sweep does with the layers. */
typedef enum ddp_sweep {
    DDP_SWEEP_PLAIN,         /* blend in the peel pass */
    DDP_SWEEP_DISTANCE_MAX,  /* distance modulation, first sweep: the largest distance only */
    DDP_SWEEP_DISTANCE_BLEND /* distance modulation: blend after each peel pass */
} ddp_sweep;

/* The peel framebuffer's blending. Plain: front and back layers under-blended.
 * Distance: the layers are stored (rgb, local factor); 0 from a fragment that
 * is not the layer leaves the target alone. */
static void ddp_enable_sweep_blending(ddp_sweep sweep)
{
    ddp_enable_peel_blending();
    if (sweep != DDP_SWEEP_PLAIN)
        for (GLuint target = 1; target <= 2; ++target)
            glBlendFuncSeparatei(target, GL_ONE, GL_ONE_MINUS_SRC_ALPHA, GL_ONE,
                                 GL_ONE_MINUS_SRC_ALPHA);
}

/* After peel pass `pass` (read minmax[current], wrote minmax[next]): the
 * distance pass blends (or measures) this pass's two layers. */
static void ddp_distance_pass(ddp_state *s, const oit_frame_settings *frame, ddp_sweep sweep,
                              int current, int next, int pass, float distance_norm)
{
    /* previous_far ping-pong: pass p reads [p & 1] and writes [(p + 1) & 1] */
    const int read = pass & 1, write = read ^ 1;
    if (sweep == DDP_SWEEP_DISTANCE_MAX) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->distance_max_framebuffer[write]);
        glEnablei(GL_BLEND, 0);
        glBlendEquationi(0, GL_MAX);
        glBlendFunci(0, GL_ONE, GL_ONE);
        glDisablei(GL_BLEND, 1);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, s->distance_blend_framebuffer[write]);
        glEnablei(GL_BLEND, 0); /* front: under */
        glBlendEquationi(0, GL_FUNC_ADD);
        glBlendFuncSeparatei(0, GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        glEnablei(GL_BLEND, 1); /* back: this layer over the back layers so far */
        glBlendEquationi(1, GL_FUNC_ADD);
        glBlendFuncSeparatei(1, GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);
        glDisablei(GL_BLEND, 2);
    }
    glUseProgram(s->distance_programs[sweep == DDP_SWEEP_DISTANCE_MAX ? 1 : 0]);
    oit_gpu_set_distance_norm(&s->gpu, distance_norm);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_NEXT_LAYER);
    glBindTexture(GL_TEXTURE_2D, s->front_layer);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_LAYER);
    glBindTexture(GL_TEXTURE_2D, s->back_layer);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_MINMAX);
    glBindTexture(GL_TEXTURE_2D, s->minmax[current]);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_NEXT);
    glBindTexture(GL_TEXTURE_2D, s->minmax[next]);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_PREVIOUS);
    glBindTexture(GL_TEXTURE_2D, s->previous_far[read]);
    oit_gl_draw_fullscreen(&s->gpu.output);
    glDisable(GL_BLEND);
}

static oit_status ddp_sweep_layers(ddp_state *s, const oit_scene *scene,
                                   const oit_frame_settings *frame, ddp_sweep sweep,
                                   float distance_norm, int *layers_out, bool *truncated,
                                   oit_error *err)
{
    static const GLfloat empty_minmax[4] = {DDP_EMPTY_DEPTH, DDP_EMPTY_DEPTH, 0.0f, 0.0f};
    static const GLfloat empty_colour[4] = {0.0f, 0.0f, 0.0f, 1.0f}; /* C = 0, T = 1 */
    static const GLfloat empty_layer[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    static const GLfloat no_far[4] = {-1.0f, 0.0f, 0.0f, 0.0f};
    const bool distance = sweep != DDP_SWEEP_PLAIN;
    GLuint *peel_framebuffer = distance ? s->distance_peel_framebuffer : s->peel_framebuffer;

    /* init: the nearest and farthest depth of all fragments. */
    oit_timer_stage_begin(&s->gpu.timer, sweep == DDP_SWEEP_DISTANCE_MAX ? "distance_init" : "init");
    glBindFramebuffer(GL_FRAMEBUFFER, s->back_framebuffer);
    glClearBufferfv(GL_COLOR, 0, empty_colour);
    glBindFramebuffer(GL_FRAMEBUFFER, peel_framebuffer[0]);
    glClearBufferfv(GL_COLOR, 0, empty_minmax);
    glClearBufferfv(GL_COLOR, 1, distance ? empty_layer : empty_colour);
    glClearBufferfv(GL_COLOR, 2, distance ? empty_layer : empty_colour);
    if (distance) {
        glBindFramebuffer(GL_FRAMEBUFFER, s->distance_blend_framebuffer[0]);
        glClearBufferfv(GL_COLOR, 0, empty_colour); /* the front accumulation */
        glClearBufferfv(GL_COLOR, 2, no_far);       /* previous_far[0] */
        glBindFramebuffer(GL_FRAMEBUFFER, peel_framebuffer[0]);
    }
    ddp_enable_sweep_blending(sweep);
    glUseProgram(s->init_program);
    oit_gl_draw_scene(scene);
    glDisable(GL_BLEND);
    bool any_left = false, two_left = false;
    ddp_probe(s, 0, &any_left, &two_left);
    oit_timer_stage_end(&s->gpu.timer);
    oit_status status = oit_gpu_stage_check(&s->gpu, "init", err);

    /* no cap: every pass peels at least one more layer of some pixel */
    const int limit = s->gpu.config.max_layers > 0 ? s->gpu.config.max_layers : INT_MAX;
    int layers = 0;
    for (int pass = 0; status == OIT_OK && any_left && layers < limit; ++pass) {
        char stage[OIT_STAGE_NAME_SIZE];
        snprintf(stage, sizeof stage, "%s_%d", sweep == DDP_SWEEP_DISTANCE_MAX ? "distance_peel" : "peel",
                 pass);
        oit_timer_stage_begin(&s->gpu.timer, stage);
        const int current = pass & 1, next = current ^ 1;
        /* With one layer left under the limit, peel only the front one. */
        const bool peel_back = limit - layers >= 2;
        layers += two_left && peel_back ? 2 : 1;

        glBindFramebuffer(GL_FRAMEBUFFER, peel_framebuffer[next]);
        glClearBufferfv(GL_COLOR, 0, empty_minmax);
        glClearBufferfv(GL_COLOR, 2, distance ? empty_layer : empty_colour);
        if (distance)
            glClearBufferfv(GL_COLOR, 1, empty_layer);
        ddp_enable_sweep_blending(sweep);
        glUseProgram(s->peel_program);
        glUniform1i(OIT_UNIFORM_DDP_PEEL_BACK, peel_back);
        glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_DEPTH_MINMAX);
        glBindTexture(GL_TEXTURE_2D, s->minmax[current]);
        oit_gl_draw_scene(scene);
        glDisable(GL_BLEND);

        if (distance) {
            ddp_distance_pass(s, frame, sweep, current, next, pass, distance_norm);
        } else {
            /* This pass's back layer lies in front of the back layers so far:
             * back.rgb = layer.rgb + T_layer * back.rgb, back.T *= T_layer. */
            glBindFramebuffer(GL_FRAMEBUFFER, s->back_framebuffer);
            glEnable(GL_BLEND);
            glBlendEquation(GL_FUNC_ADD);
            glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);
            glUseProgram(s->back_program);
            glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PEEL_LAYER);
            glBindTexture(GL_TEXTURE_2D, s->back_layer);
            oit_gl_draw_fullscreen(&s->gpu.output);
            glDisable(GL_BLEND);
        }

        ddp_probe(s, next, &any_left, &two_left);
        oit_timer_stage_end(&s->gpu.timer);
        status = oit_gpu_stage_check(&s->gpu, stage, err);
    }
    /* the probe after the last pass already says whether the cap left any */
    if (status == OIT_OK && any_left)
        *truncated = true;
    *layers_out = layers;
    return status;
}

/* The distance modulation's normalising length: the focus region, or the
 * frame's largest distance (a first sweep; 1 if there is none). */
static oit_status ddp_distance_norm(ddp_state *s, const oit_scene *scene,
                                    const oit_frame_settings *frame, float *norm, oit_error *err)
{
    *norm = frame->modulation.focus_region;
    if (*norm > 0.0f)
        return OIT_OK;
    static const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glBindFramebuffer(GL_FRAMEBUFFER, s->distance_max_framebuffer[0]);
    glClearBufferfv(GL_COLOR, 0, zero);
    int layers = 0;
    oit_status status = ddp_sweep_layers(s, scene, frame, DDP_SWEEP_DISTANCE_MAX, 1.0f, &layers,
                                         &s->gpu.stats.truncated, err);
    if (status != OIT_OK)
        return status;
    return oit_gpu_read_largest(&s->gpu, s->distance_max_framebuffer[0], norm, err);
}

static oit_status ddp_render(oit_algorithm *alg, const oit_scene *scene,
                             const oit_frame_settings *frame, oit_error *err)
{
    ddp_state *s = (ddp_state *)alg;
    const oit_modulation *modulation = &frame->modulation;
    const bool distance = modulation->mode == OIT_MODULATE_DISTANCE;
    if (frame->width != s->gpu.output.width || frame->height != s->gpu.output.height ||
        (distance && !s->distance_targets)) {
        s->distance_targets = s->distance_targets || distance;
        oit_status status = ddp_resize(alg, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }
    oit_status status = oit_gpu_frame_begin(&s->gpu, scene, frame, err);
    if (status != OIT_OK)
        return status;

    glViewport(0, 0, s->gpu.output.width, s->gpu.output.height);
    glDisable(GL_CULL_FACE); /* both sides of every surface are layers */
    glDisable(GL_DEPTH_TEST); /* the min-max target does the depth work */
    glDisable(GL_BLEND);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);

    float distance_norm = 1.0f;
    if (distance)
        status = ddp_distance_norm(s, scene, frame, &distance_norm, err);
    int layers = 0;
    if (status == OIT_OK)
        status = ddp_sweep_layers(s, scene, frame,
                                  distance ? DDP_SWEEP_DISTANCE_BLEND : DDP_SWEEP_PLAIN,
                                  distance_norm, &layers, &s->gpu.stats.truncated, err);

    const oit_texture_unit composed[] = {{OIT_TEXUNIT_ACCUM_FRONT, s->front},
                                         {OIT_TEXUNIT_ACCUM_BACK, s->back}};
    status = oit_gpu_fullscreen_stage(&s->gpu, status, "compose", s->compose_program, 0, composed,
                                      2, err);

    s->gpu.stats.layers = layers;
    return oit_gpu_frame_end(&s->gpu, status, err);
}

static void ddp_destroy(oit_algorithm *alg)
{
    ddp_state *s = (ddp_state *)alg;
    if (!s)
        return;
    ddp_release_targets(s);
    glDeleteQueries(2, s->probe_queries);
    oit_gpu_destroy(&s->gpu);
}

/* ddp knows the adjacent distance (its blending delayed by a layer) and
 * nothing of the neighbouring pixels. */
static const oit_capabilities ddp_capabilities = {
    .modulations = {OIT_REFUSES_NEIGHBOUR_MODULATIONS(
        "dual depth peeling blends each front layer in the pass that peels it, before the adjacent pixels' "
        "fragments of that layer are known (dp approximates curvature and dist-curv from neighbours in the same "
        "peeled layer)")},
    .distances = {OIT_ADJACENT_DISTANCE_ONLY("skip and far-end distances need layers further along the ray than "
                                             "the ones peeled (use ll, ib or reference)")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_MAX_LAYERS,
};

const oit_algorithm_ops oit_algorithm_ddp = {
    .name = "ddp",
    .summary = "dual depth peeling (Bavoil & Myers 2008): nearest and farthest layer per pass",
    .uses_gl = true,
    .exact = true,
    .capabilities = &ddp_capabilities,
    .create = ddp_create,
    .resize = ddp_resize,
    .render = ddp_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = ddp_destroy,
};
