/*
 * gpu_algorithm.h: what every GPU algorithm holds and does the same way
 * (core-internal). An algorithm's state starts with an oit_gpu_algorithm, so
 * the generic entries of its operations table (read_image, stats) and the
 * frame's prologue and epilogue take it as such; the algorithm file keeps
 * only its passes, its targets and what its statistics add.
 */
#ifndef OIT_GPU_ALGORITHM_H
#define OIT_GPU_ALGORITHM_H

#include "gl_util.h"

#define OIT_GPU_PROGRAMS_MAX 32

typedef struct oit_gpu_algorithm {
    const char *name; /* as on the command line; messages start with it */
    oit_algorithm_config config; /* config.shader_dir points at shader_dir */
    char *shader_dir; /* a copy of the caller's ("." when NULL): programs built on first use need it */
    oit_gl_output output; /* the RGBA8 output; output.width, .height: the size resized to */
    oit_gl_memory memory; /* every texture and buffer the algorithm allocates, the output's too */
    oit_stage_timer timer;
    oit_stats stats;
    GLuint frame_block; /* the frame's parameters (OIT_UBO_FRAME), uploaded by oit_gpu_frame_begin */
    GLuint programs[OIT_GPU_PROGRAMS_MAX]; /* built by oit_gpu_program*, deleted with the algorithm */
    int program_count;
    /* anti-aliasing (oit_gpu_accumulate): the samples' per-pixel sum
     * (RGBA16UI, tracked as per-pixel memory; none in a frame of one sample)
     * and its size, and the program that adds and resolves */
    GLuint sample_sum;
    int sample_sum_width, sample_sum_height;
    GLuint sample_program;
} oit_gpu_algorithm;

/* A zeroed state of state_size bytes that starts with the base, set up
 * (configuration with its own copy of the shader folder, output tracked by
 * its memory, timer, statistics reset). */
oit_status oit_gpu_create(size_t state_size, const char *name, const oit_algorithm_config *config,
                          oit_gpu_algorithm **out, oit_error *err);
/* The end of an algorithm's create: with status OK and no GL error ("NAME:
 * create"), *out is the algorithm; otherwise destroy(gpu) frees what it made
 * and the error is returned. */
oit_status oit_gpu_created(oit_gpu_algorithm *gpu, oit_status status, void (*destroy)(oit_algorithm *alg),
                           oit_algorithm **out, oit_error *err);
/* Frees what the base holds (programs, output, timer) and the state; the
 * algorithm frees its own objects first. NULL is allowed. */
void oit_gpu_destroy(oit_gpu_algorithm *gpu);

/* Programs from the shader tree (oit_gl_program, _variant, _compute_program),
 * kept for oit_gpu_destroy. */
oit_status oit_gpu_program(oit_gpu_algorithm *gpu, const char *vertex_path, const char *fragment_path,
                           GLuint *out, oit_error *err);
oit_status oit_gpu_program_variant(oit_gpu_algorithm *gpu, const char *vertex_path, const char *fragment_path,
                                   const char *defines, GLuint *out, oit_error *err);
oit_status oit_gpu_compute_program(oit_gpu_algorithm *gpu, const char *compute_path, GLuint *out,
                                   oit_error *err);

/* After a stage: OIT_CANCELLED once the frame's progress callback asked to
 * stop; with config.debug, GL errors named "NAME: stage". */
oit_status oit_gpu_stage_check(const oit_gpu_algorithm *gpu, const char *stage, oit_error *err);

/* A frame's prologue: the scene must be on the GPU; statistics reset, the
 * memory held so far, the timer started (with the frame's progress
 * callback), the frame's parameter block uploaded and bound (every pass reads
 * it), the per-part opacity bound. */
oit_status oit_gpu_frame_begin(oit_gpu_algorithm *gpu, const oit_scene *scene, const oit_frame_settings *frame,
                               oit_error *err);
/* The same, first resizing (the algorithm's own resize) when the frame's
 * size is not the output's: the prologue of every algorithm whose targets
 * depend on the size alone. */
oit_status oit_gpu_frame_begin_sized(oit_gpu_algorithm *gpu,
                                     oit_status (*resize)(oit_algorithm *alg, int width, int height, oit_error *err),
                                     const oit_scene *scene, const oit_frame_settings *frame, oit_error *err);
/* Its epilogue: default framebuffer and program, the timer stopped (stage
 * times into the statistics), GL errors of the frame, the memory held and
 * the bytes per pixel of the image-sized allocations. Returns status, or the
 * GL error where status was OIT_OK. */
oit_status oit_gpu_frame_end(oit_gpu_algorithm *gpu, oit_status status, oit_error *err);

/* The frame's normalising length for the distance modulation, once the
 * algorithm knows it (the frame's largest distance): the block's one field
 * written after the prologue. */
void oit_gpu_set_distance_norm(oit_gpu_algorithm *gpu, float norm);

/* A screen-sized 2D target (nearest, clamped), recorded in the tracker as
 * per-pixel memory. */
GLuint oit_gpu_target(oit_gpu_algorithm *gpu, GLenum internal_format, int width, int height);
/* The bound framebuffer is complete, or OIT_E_RUNTIME "NAME: the WHAT
 * framebuffer is incomplete (...)" naming its size and the memory held. */
oit_status oit_gpu_check_framebuffer(const oit_gpu_algorithm *gpu, const char *what, int width, int height,
                                     oit_error *err);
/* A framebuffer drawing to colour[i] at GL_COLOR_ATTACHMENTi (GL_NONE where
 * colour[i] is 0) and depth-testing against `depth` (none if 0): created
 * into *framebuffer unless it holds one already (then re-attached), left
 * bound, and checked as oit_gpu_check_framebuffer(WHAT). At most 8 colours. */
oit_status oit_gpu_framebuffer(const oit_gpu_algorithm *gpu, GLuint *framebuffer, const char *what,
                               const GLuint *colour, int colour_count, GLuint depth, int width, int height,
                               oit_error *err);
/* The end of every resize: no framebuffer bound, GL errors checked ("NAME:
 * resize"), and when all went well the output's size and the memory figure
 * recorded. Returns the resize's status; the caller releases its targets if
 * it is not OIT_OK. */
oit_status oit_gpu_resize_end(oit_gpu_algorithm *gpu, oit_status status, int width, int height, oit_error *err);
/* The largest value of the R32F target of `framebuffer` (the frame's largest
 * distance, for the automatic focus region), read back as the stage
 * "distance_max_read"; 1 where every value is 0. */
oit_status oit_gpu_read_largest(oit_gpu_algorithm *gpu, GLuint framebuffer, float *largest, oit_error *err);

/* A texture a full-screen pass reads, and the unit it is bound to. */
typedef struct oit_texture_unit {
    GLenum unit; /* OIT_TEXUNIT_* */
    GLuint texture;
} oit_texture_unit;

/* The frame's last stage, where every algorithm but ll and ib ends: a
 * full-screen pass of `program` into the output (its framebuffer bound, the
 * frame's uniforms set) reading `textures` (2D), timed and checked as `stage`,
 * after glMemoryBarrier(barriers) unless barriers is 0. A uniform of the
 * algorithm's own is set before, with glProgramUniform*. Does nothing unless
 * status is OIT_OK, and returns the stage's status. */
oit_status oit_gpu_fullscreen_stage(oit_gpu_algorithm *gpu, oit_status status, const char *stage,
                                    GLuint program, GLbitfield barriers, const oit_texture_unit *textures, int texture_count, oit_error *err);

/* The operations table's read_image, stats and accumulate, for every GPU
 * algorithm. accumulate (oit.h, oit_algorithm_ops) adds the output to the
 * sum by common/samples_accumulate.comp, which reads the RGBA8 output as
 * the integers it holds, and resolves it there; its time is glFinish-bracketed
 * wall time. */
oit_status oit_gpu_read_image(oit_algorithm *alg, oit_image *out, oit_error *err);
void oit_gpu_stats(const oit_algorithm *alg, oit_stats *out);
oit_status oit_gpu_accumulate(oit_algorithm *alg, int sample, int samples, oit_stats *frame, oit_error *err);

#endif
