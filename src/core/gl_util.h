/*
 * gl_util.h: the GL helpers every GPU algorithm shares (core-internal).
 * Include this instead of <GL/glew.h> directly; never together with <GL/osmesa.h>.
 */
#ifndef OIT_GL_UTIL_H
#define OIT_GL_UTIL_H

#include <GL/glew.h>
#include <stddef.h>
#include <stdint.h>

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
/* The same sources with `defines` ("#define NAME VALUE\n" lines, or NULL) right
 * after the #version line: the program variants of common/variants.glsl. A pass
 * leaves out, at compile time, a feature the frame does not use, rather than
 * branch on a uniform: llvmpipe runs both sides of every branch, uniform or
 * not, so a feature compiled in costs its full price when it is off. */
oit_status oit_gl_program_variant(const char *shader_dir, const char *vertex_path,
                                  const char *fragment_path, const char *defines, GLuint *out,
                                  oit_error *err);
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

/* ---- memory: every buffer and texture an algorithm allocates ---- */

/* Each algorithm keeps one oit_gl_memory and allocates every GL buffer store
 * and every texture (its output included) through the functions below, which
 * record the exact bytes of each object: textures width x height x the bytes
 * per texel of their internal format (oit_gl_texel_bytes), buffers the size
 * given to glBufferData. stats.memory_bytes is oit_gl_memory_total();
 * bytes_per_pixel and bytes_per_fragment come from the per-use sums.
 * Buffer textures (glTexBuffer) own no storage (their buffer is counted), and
 * framebuffers, vertex arrays, queries and programs hold none either; none of
 * them is recorded. oit_gl_enumerate_allocated_bytes() (oit.h) is the
 * independent check (tests/memory_figures.sh). */
typedef enum oit_gl_memory_use {
    OIT_GL_MEMORY_PIXELS,    /* sized by the image: width x height texels (the output too) */
    OIT_GL_MEMORY_FRAGMENTS, /* sized by the fragment pool: capacity x bytes per fragment */
    OIT_GL_MEMORY_FIXED,     /* the rest: counters, parameters, per-triangle tables */
    OIT_GL_MEMORY_USE_COUNT
} oit_gl_memory_use;

#define OIT_GL_MEMORY_MAX_OBJECTS 32

typedef struct oit_gl_memory_object {
    GLuint name;
    bool texture; /* else a buffer */
    oit_gl_memory_use use;
    uint64_t bytes;
} oit_gl_memory_object;

typedef struct oit_gl_memory {
    oit_gl_memory_object objects[OIT_GL_MEMORY_MAX_OBJECTS]; /* the live ones, count of them */
    int count;
    uint64_t bytes[OIT_GL_MEMORY_USE_COUNT]; /* sums over objects by use */
} oit_gl_memory;

/* Bytes per texel of the sized internal formats the algorithms use (RGBA8,
 * RGBA32F, RG32F, R32F, R32UI, RG32UI, RGBA32UI, DEPTH_COMPONENT32F, and a few
 * more); 0 for any other (recorded as 0 bytes with a warning on stderr, so
 * the independent check fails until the table has it). */
size_t oit_gl_texel_bytes(GLenum internal_format);
/* oit_gl_texture_2d, recorded. */
GLuint oit_gl_memory_texture_2d(oit_gl_memory *memory, oit_gl_memory_use use, GLenum internal_format,
                                int width, int height);
/* glDeleteTextures, forgetting the recorded ones; the names are set to 0.
 * Names not recorded (buffer textures) are deleted all the same. */
void oit_gl_memory_delete_textures(oit_gl_memory *memory, GLsizei count, GLuint *textures);
/* glBufferData(target, bytes, data, usage) on buffer (bound to target, then
 * target is bound to 0): (re)specifies its store and records `bytes`,
 * replacing what it had. */
void oit_gl_memory_buffer_data(oit_gl_memory *memory, oit_gl_memory_use use, GLenum target,
                               GLuint buffer, uint64_t bytes, const void *data, GLenum usage);
/* glDeleteBuffers, forgetting the recorded ones; the names are set to 0. */
void oit_gl_memory_delete_buffers(oit_gl_memory *memory, GLsizei count, GLuint *buffers);
uint64_t oit_gl_memory_total(const oit_gl_memory *memory);
uint64_t oit_gl_memory_bytes(const oit_gl_memory *memory, oit_gl_memory_use use);

/* ---- the RGBA8 output every algorithm composes into ---- */

typedef struct oit_gl_output {
    GLuint framebuffer;
    GLuint colour; /* RGBA8 texture */
    GLuint fullscreen_vertex_array; /* empty VAO for full-screen triangles */
    int width, height;
    /* the algorithm's tracker: the colour texture is recorded there
     * (OIT_GL_MEMORY_PIXELS); set it before the first resize */
    oit_gl_memory *memory;
} oit_gl_output;

oit_status oit_gl_output_resize(oit_gl_output *output, int width, int height, oit_error *err);
/* glCheckFramebufferStatus of the bound GL_FRAMEBUFFER; when incomplete,
 * OIT_E_RUNTIME naming WHAT, the status, the image size and what the
 * algorithm's textures and buffers (memory, may be NULL) needed in all: e.g.
 * "blend: the accumulation framebuffer is incomplete (GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT,
 * 0x8cd6): the driver could not allocate its textures at 16384x16384, the
 * frame's textures and buffers needing 5.00 GiB in all". */
oit_status oit_gl_check_framebuffer(const char *what, int width, int height, const oit_gl_memory *memory,
                                    oit_error *err);
void oit_gl_output_release(oit_gl_output *output);
/* glReadPixels into a new image, flipped to top-row-first. */
oit_status oit_gl_output_read(const oit_gl_output *output, oit_image *out, oit_error *err);
/* Draw one triangle covering the viewport (vertex shader common/fullscreen.vert). */
void oit_gl_draw_fullscreen(const oit_gl_output *output);

/* ---- geometry ---- */

/* The frame's parameter block (common/frame.glsl, std140), as C lays it out:
 * oit_shared.h's OIT_FRAME_* offsets, asserted below. */
typedef struct oit_frame_block {
    float modelview[16], projection[16], plane_to_eye[16];
    float inverse_modelview[16], inverse_projection[16];
    float normal_matrix[12]; /* mat3: three columns of vec4 */
    float background[3], alpha;
    float focus_a[4], focus_b[4];
    int32_t viewport[2], shading, focus_shape;
    float focus_region, contrast;
    int32_t distance_mode, distance_skip;
    float distance_norm;
    int32_t section_count, section_all_parts, padding;
    float section_planes[OIT_SECTIONS_MAX][4];
} oit_frame_block;
_Static_assert(offsetof(oit_frame_block, projection) == OIT_FRAME_PROJECTION &&
                   offsetof(oit_frame_block, plane_to_eye) == OIT_FRAME_PLANE_TO_EYE &&
                   offsetof(oit_frame_block, inverse_modelview) == OIT_FRAME_INVERSE_MODELVIEW &&
                   offsetof(oit_frame_block, inverse_projection) == OIT_FRAME_INVERSE_PROJECTION &&
                   offsetof(oit_frame_block, normal_matrix) == OIT_FRAME_NORMAL_MATRIX &&
                   offsetof(oit_frame_block, background) == OIT_FRAME_BACKGROUND &&
                   offsetof(oit_frame_block, alpha) == OIT_FRAME_ALPHA &&
                   offsetof(oit_frame_block, focus_a) == OIT_FRAME_FOCUS_A &&
                   offsetof(oit_frame_block, focus_b) == OIT_FRAME_FOCUS_B &&
                   offsetof(oit_frame_block, viewport) == OIT_FRAME_VIEWPORT &&
                   offsetof(oit_frame_block, shading) == OIT_FRAME_SHADING &&
                   offsetof(oit_frame_block, focus_shape) == OIT_FRAME_FOCUS_SHAPE &&
                   offsetof(oit_frame_block, focus_region) == OIT_FRAME_FOCUS_REGION &&
                   offsetof(oit_frame_block, contrast) == OIT_FRAME_CONTRAST &&
                   offsetof(oit_frame_block, distance_mode) == OIT_FRAME_DISTANCE_MODE &&
                   offsetof(oit_frame_block, distance_skip) == OIT_FRAME_DISTANCE_SKIP &&
                   offsetof(oit_frame_block, distance_norm) == OIT_FRAME_DISTANCE_NORM &&
                   offsetof(oit_frame_block, section_count) == OIT_FRAME_SECTION_COUNT &&
                   offsetof(oit_frame_block, section_all_parts) == OIT_FRAME_SECTION_ALL_PARTS &&
                   offsetof(oit_frame_block, section_planes) == OIT_FRAME_SECTION_PLANES &&
                   sizeof(oit_frame_block) == OIT_FRAME_BLOCK_BYTES,
               "oit_frame_block differs from oit_shared.h's OIT_FRAME_* offsets");
/* The block of a frame: its matrices rounded to float once, the inverses and
 * the normal matrix computed in double first. */
void oit_gl_frame_block(const oit_frame_settings *frame, oit_frame_block *out);
/* A program's frame block at oit_shared.h's offsets (GL_UNIFORM_OFFSET of
 * every member it uses), or OIT_E_RUNTIME naming the member; OK for a
 * program without the block. */
oit_status oit_gl_check_frame_block(GLuint program, const char *description, oit_error *err);
/* One glDrawElements over the whole model, so gl_PrimitiveID is the triangle index. */
void oit_gl_draw_scene(const oit_scene *scene);
/* Per-part opacity for this frame: writes frame->local.component_alpha (its
 * component_count floats; 1 for the scene's parts past them, and for all when
 * NULL) into the scene's part-alpha buffer and binds its buffer texture at
 * OIT_TEXUNIT_LOCAL_PART_ALPHA, where common/local_modulation.glsl reads it.
 * Every part, however many: no limit. Every GPU algorithm calls it once at
 * the start of render(), before its first pass. */
/* The selection highlight (frame->local.component_highlight) goes the same
 * way: colour and weight per part into the scene's part-tint buffer, bound at
 * OIT_TEXUNIT_LOCAL_PART_TINT (oit_local_tint in common/local_modulation.glsl). */
void oit_gl_bind_part_alpha(const oit_scene *scene, const oit_frame_settings *frame);

/* ---- limits ---- */

/* ll, ib: read the fill's 64-bit fragment count from the counter buffer: the
 * 32-bit counter at OIT_FRAME_COUNTER_FRAGMENTS and the times it wrapped at
 * wraps_slot (after a buffer-update barrier; waits for the fill). */
uint64_t oit_gl_read_frame_fragments(GLuint counter_buffer, int wraps_slot);

/* ll, ib: the fill's fragment count (64-bit: the 32-bit counter plus the times
 * it wrapped) must fit the 32-bit node indices (OIT_MAX_FRAME_FRAGMENTS);
 * past it OIT_E_RUNTIME naming the algorithm, the count and the limit.
 * counter_start is oit_algorithm_config.fragment_counter_start (tests), named
 * in the message when it is not 0. */
oit_status oit_gl_check_frame_fragments(const char *algorithm, uint64_t fragments,
                                        uint32_t counter_start, oit_error *err);

/* ll, ib: every fragment the fill stored must have been walked by the sort;
 * fewer means a shader loop was cut short (Mesa llvmpipe ends any loop after
 * 65535 iterations, nested loops included), and the frame is OIT_E_RUNTIME
 * instead of an image that silently misses fragments. */
oit_status oit_gl_check_sorted_fragments(const char *algorithm, uint64_t stored, uint64_t sorted,
                                         oit_error *err);

/* Create a 2D texture with storage, nearest filtering, clamped. */
GLuint oit_gl_texture_2d(GLenum internal_format, int width, int height);

#endif
