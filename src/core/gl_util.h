/*
 * gl_util.h: the GL helpers every GPU algorithm shares (core-internal).
 * Include this instead of <GL/glew.h> directly; never together with <GL/osmesa.h>.
 */
#ifndef OIT_GL_UTIL_H
#define OIT_GL_UTIL_H

#include <GL/glew.h>

#include "oit.h"
#include "oit_shared.h"

/* ---- programs ---- */

/* Build a program from files relative to shader_dir. Every source gets
 * "#version 430 core" prepended; lines `#include "path"` are expanded
 * (paths relative to shader_dir, nested includes allowed, each file expanded
 * at most once per shader). `#line` directives number the files 0, 1, ... in
 * order of first inclusion; compile errors list that numbering with the log. */
oit_status oit_gl_program(const char *shader_dir, const char *vertex_path,
                          const char *fragment_path, GLuint *out, oit_error *err);
oit_status oit_gl_compute_program(const char *shader_dir, const char *compute_path, GLuint *out,
                                  oit_error *err);

/* ---- errors ---- */

/* glGetError plus, in debug contexts, any error-severity KHR_debug message
 * seen since the last check. `where` names the stage in the message. */
oit_status oit_gl_check(const char *where, oit_error *err);
/* The first error-severity KHR_debug message since the last call (debug
 * contexts only; gl_context.c collects them). False if there was none. */
bool oit_gl_debug_take_error(char *out, size_t out_size);

/* ---- stage timing ---- */

typedef struct oit_stage_timer {
    GLuint queries[OIT_MAX_STAGES];
    char names[OIT_MAX_STAGES][OIT_STAGE_NAME_SIZE];
    int count;
    bool stage_open;
    double cpu_start_ms;
    bool created;
    /* Software renderers (llvmpipe) return meaningless GL_TIME_ELAPSED
     * results, so there each stage is timed as wall time between glFinish()
     * calls instead (chosen by oit_timer_create from GL_RENDERER). */
    bool wall_clock;
    double stage_start_ms;
    double wall_ms[OIT_MAX_STAGES];
    /* the frame's progress callback (oit_progress), asked after every stage */
    oit_progress progress;
    int stages_done;
    bool cancelled;
    char cancelled_after[OIT_STAGE_NAME_SIZE];
} oit_stage_timer;

double oit_now_ms(void); /* monotonic clock */
void oit_timer_create(oit_stage_timer *timer);
void oit_timer_destroy(oit_stage_timer *timer);
/* frame may be NULL (no progress callback). */
void oit_timer_frame_begin(oit_stage_timer *timer, const oit_frame_settings *frame);
/* Stages are sequential: begin closes an open stage first. Past
 * OIT_MAX_STAGES the last stage absorbs the rest. */
void oit_timer_stage_begin(oit_stage_timer *timer, const char *name);
void oit_timer_stage_end(oit_stage_timer *timer);
/* OIT_CANCELLED (with a message naming the last stage done) once the
 * frame's progress callback has asked to stop; OIT_OK before. Every
 * algorithm's per-stage check calls it, so a frame stops at the next stage
 * boundary (between peels for dp and ddp). */
oit_status oit_timer_status(const oit_stage_timer *timer, oit_error *err);
/* Waits for the GPU, fills stats->stages/stage_count/cpu_ms. */
void oit_timer_frame_end(oit_stage_timer *timer, oit_stats *stats);

/* ---- the RGBA8 output every algorithm composes into ---- */

typedef struct oit_gl_output {
    GLuint framebuffer;
    GLuint colour; /* RGBA8 texture */
    GLuint fullscreen_vertex_array; /* empty VAO for full-screen triangles */
    int width, height;
} oit_gl_output;

oit_status oit_gl_output_resize(oit_gl_output *output, int width, int height, oit_error *err);
void oit_gl_output_release(oit_gl_output *output);
/* glReadPixels into a new image, flipped to top-row-first. */
oit_status oit_gl_output_read(const oit_gl_output *output, oit_image *out, oit_error *err);
/* Draw one triangle covering the viewport (vertex shader common/fullscreen.vert). */
void oit_gl_draw_fullscreen(const oit_gl_output *output);

/* ---- geometry ---- */

/* Set the uniforms at OIT_UNIFORM_* locations for the currently bound program. */
void oit_gl_set_frame_uniforms(const oit_frame_settings *frame);
/* One glDrawElements over the whole model, so gl_PrimitiveID is the triangle index. */
void oit_gl_draw_scene(const oit_scene *scene);

/* Create a 2D texture with storage, nearest filtering, clamped. */
GLuint oit_gl_texture_2d(GLenum internal_format, int width, int height);

#endif
