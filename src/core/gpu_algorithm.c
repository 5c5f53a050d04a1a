/* gpu_algorithm.c: see gpu_algorithm.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_algorithm.h"

oit_status oit_gpu_create(size_t state_size, const char *name, const oit_algorithm_config *config,
                          oit_gpu_algorithm **out, oit_error *err)
{
    *out = NULL;
    oit_gpu_algorithm *gpu = calloc(1, state_size);
    if (!gpu)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    gpu->name = name;
    gpu->config = *config;
    const char *dir = config->shader_dir ? config->shader_dir : ".";
    gpu->shader_dir = malloc(strlen(dir) + 1);
    if (!gpu->shader_dir) {
        free(gpu);
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory", name);
    }
    strcpy(gpu->shader_dir, dir);
    gpu->config.shader_dir = gpu->shader_dir;
    gpu->output.memory = &gpu->memory;
    oit_stats_reset(&gpu->stats);
    oit_timer_create(&gpu->timer);
    glGenBuffers(1, &gpu->frame_block);
    oit_gl_memory_buffer_data(&gpu->memory, OIT_GL_MEMORY_FIXED, GL_UNIFORM_BUFFER, gpu->frame_block,
                              OIT_FRAME_BLOCK_BYTES, NULL, GL_DYNAMIC_DRAW);
    *out = gpu;
    return OIT_OK;
}

oit_status oit_gpu_created(oit_gpu_algorithm *gpu, oit_status status, void (*destroy)(oit_algorithm *alg),
                           oit_algorithm **out, oit_error *err)
{
    if (status == OIT_OK) {
        char where[64];
        snprintf(where, sizeof where, "%s: create", gpu->name);
        status = oit_gl_check(where, err);
    }
    if (status != OIT_OK) {
        destroy((oit_algorithm *)gpu);
        return status;
    }
    *out = (oit_algorithm *)gpu;
    return OIT_OK;
}

void oit_gpu_destroy(oit_gpu_algorithm *gpu)
{
    if (!gpu)
        return;
    for (int i = 0; i < gpu->program_count; ++i)
        glDeleteProgram(gpu->programs[i]);
    oit_gl_memory_delete_buffers(&gpu->memory, 1, &gpu->frame_block);
    if (gpu->sample_sum)
        oit_gl_memory_delete_textures(&gpu->memory, 1, &gpu->sample_sum);
    oit_gl_output_release(&gpu->output);
    oit_timer_destroy(&gpu->timer);
    free(gpu->shader_dir);
    free(gpu);
}

static oit_status keep_program(oit_gpu_algorithm *gpu, oit_status status, GLuint program, GLuint *out,
                               oit_error *err)
{
    if (status != OIT_OK)
        return status;
    status = oit_gl_check_frame_block(program, gpu->name, err);
    if (status != OIT_OK) {
        glDeleteProgram(program);
        return status;
    }
    if (gpu->program_count == OIT_GPU_PROGRAMS_MAX) {
        glDeleteProgram(program);
        return oit_fail(err, OIT_E_RUNTIME, "%s: more than %d programs", gpu->name, OIT_GPU_PROGRAMS_MAX);
    }
    gpu->programs[gpu->program_count++] = program;
    *out = program;
    return OIT_OK;
}

oit_status oit_gpu_program(oit_gpu_algorithm *gpu, const char *vertex_path, const char *fragment_path,
                           GLuint *out, oit_error *err)
{
    GLuint program = 0;
    oit_status status = oit_gl_program(gpu->config.shader_dir, vertex_path, fragment_path, &program, err);
    return keep_program(gpu, status, program, out, err);
}

oit_status oit_gpu_program_variant(oit_gpu_algorithm *gpu, const char *vertex_path, const char *fragment_path,
                                   const char *defines, GLuint *out, oit_error *err)
{
    GLuint program = 0;
    oit_status status =
        oit_gl_program_variant(gpu->config.shader_dir, vertex_path, fragment_path, defines, &program, err);
    return keep_program(gpu, status, program, out, err);
}

oit_status oit_gpu_compute_program(oit_gpu_algorithm *gpu, const char *compute_path, GLuint *out,
                                   oit_error *err)
{
    GLuint program = 0;
    oit_status status = oit_gl_compute_program(gpu->config.shader_dir, compute_path, &program, err);
    return keep_program(gpu, status, program, out, err);
}

oit_status oit_gpu_stage_check(const oit_gpu_algorithm *gpu, const char *stage, oit_error *err)
{
    if (gpu->timer.cancelled)
        return oit_timer_status(&gpu->timer, err);
    if (!gpu->config.debug)
        return OIT_OK;
    char where[96];
    snprintf(where, sizeof where, "%s: %s", gpu->name, stage);
    return oit_gl_check(where, err);
}

oit_status oit_gpu_frame_begin(oit_gpu_algorithm *gpu, const oit_scene *scene, const oit_frame_settings *frame,
                               oit_error *err)
{
    if (!scene->has_gpu)
        return oit_fail(err, OIT_E_INPUT, "%s: the scene has no GPU buffers", gpu->name);
    oit_stats_reset(&gpu->stats);
    gpu->stats.memory_bytes = oit_gl_memory_total(&gpu->memory);
    oit_timer_frame_begin(&gpu->timer, frame);
    oit_frame_block block;
    oit_gl_frame_block(frame, &block);
    glBindBuffer(GL_UNIFORM_BUFFER, gpu->frame_block);
    glBufferSubData(GL_UNIFORM_BUFFER, 0, sizeof block, &block);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, OIT_UBO_FRAME, gpu->frame_block);
    oit_gl_bind_part_alpha(scene, frame); /* per-part opacity, every part */
    return OIT_OK;
}

oit_status oit_gpu_frame_begin_sized(oit_gpu_algorithm *gpu,
                                     oit_status (*resize)(oit_algorithm *alg, int width, int height, oit_error *err),
                                     const oit_scene *scene, const oit_frame_settings *frame, oit_error *err)
{
    if (frame->width != gpu->output.width || frame->height != gpu->output.height) {
        oit_status status = resize((oit_algorithm *)gpu, frame->width, frame->height, err);
        if (status != OIT_OK)
            return status;
    }
    return oit_gpu_frame_begin(gpu, scene, frame, err);
}

void oit_gpu_set_distance_norm(oit_gpu_algorithm *gpu, float norm)
{
    glBindBuffer(GL_UNIFORM_BUFFER, gpu->frame_block);
    glBufferSubData(GL_UNIFORM_BUFFER, OIT_FRAME_DISTANCE_NORM, sizeof norm, &norm);
    glBindBuffer(GL_UNIFORM_BUFFER, 0);
}

oit_status oit_gpu_frame_end(oit_gpu_algorithm *gpu, oit_status status, oit_error *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    oit_timer_frame_end(&gpu->timer, &gpu->stats);
    if (status == OIT_OK) {
        char where[64];
        snprintf(where, sizeof where, "%s: render", gpu->name);
        status = oit_gl_check(where, err);
    }
    /* what the targets, buffers and the output hold (the tracker, gl_util.h) */
    gpu->stats.memory_bytes = oit_gl_memory_total(&gpu->memory);
    gpu->stats.bytes_per_pixel = (double)oit_gl_memory_bytes(&gpu->memory, OIT_GL_MEMORY_PIXELS) /
                                 ((double)gpu->output.width * (double)gpu->output.height);
    return status;
}

GLuint oit_gpu_target(oit_gpu_algorithm *gpu, GLenum internal_format, int width, int height)
{
    return oit_gl_memory_texture_2d(&gpu->memory, OIT_GL_MEMORY_PIXELS, internal_format, width, height);
}

oit_status oit_gpu_check_framebuffer(const oit_gpu_algorithm *gpu, const char *what, int width, int height,
                                     oit_error *err)
{
    char name[96];
    snprintf(name, sizeof name, "%s: the %s framebuffer", gpu->name, what);
    return oit_gl_check_framebuffer(name, width, height, &gpu->memory, err);
}

oit_status oit_gpu_framebuffer(const oit_gpu_algorithm *gpu, GLuint *framebuffer, const char *what,
                               const GLuint *colour, int colour_count, GLuint depth, int width, int height,
                               oit_error *err)
{
    GLenum draw[8]; /* GL 4.3 promises 8 draw buffers */
    if (colour_count < 0 || colour_count > 8)
        return oit_fail(err, OIT_E_RUNTIME, "%s: the %s framebuffer has %d colour targets (at most 8)", gpu->name,
                        what, colour_count);
    if (!*framebuffer)
        glGenFramebuffers(1, framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, *framebuffer);
    for (int i = 0; i < colour_count; ++i) {
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + (GLenum)i, GL_TEXTURE_2D, colour[i], 0);
        draw[i] = colour[i] ? GL_COLOR_ATTACHMENT0 + (GLenum)i : GL_NONE;
    }
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
    glDrawBuffers(colour_count, draw);
    return oit_gpu_check_framebuffer(gpu, what, width, height, err);
}

oit_status oit_gpu_resize_end(oit_gpu_algorithm *gpu, oit_status status, int width, int height, oit_error *err)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status == OIT_OK) {
        char where[64];
        snprintf(where, sizeof where, "%s: resize", gpu->name);
        status = oit_gl_check(where, err);
    }
    if (status != OIT_OK)
        return status;
    gpu->output.width = width;
    gpu->output.height = height;
    gpu->stats.memory_bytes = oit_gl_memory_total(&gpu->memory);
    return OIT_OK;
}

oit_status oit_gpu_read_largest(oit_gpu_algorithm *gpu, GLuint framebuffer, float *largest, oit_error *err)
{
    oit_timer_stage_begin(&gpu->timer, "distance_max_read");
    size_t pixels = (size_t)gpu->output.width * (size_t)gpu->output.height;
    float *values = malloc(pixels * sizeof *values);
    if (!values)
        return oit_fail(err, OIT_E_RUNTIME, "%s: out of memory for the distance maximum", gpu->name);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, gpu->output.width, gpu->output.height, GL_RED, GL_FLOAT, values);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    float found = 0.0f;
    for (size_t i = 0; i < pixels; ++i)
        found = values[i] > found ? values[i] : found;
    free(values);
    oit_timer_stage_end(&gpu->timer);
    *largest = found > 0.0f ? found : 1.0f;
    return oit_gpu_stage_check(gpu, "distance_max_read", err);
}

oit_status oit_gpu_fullscreen_stage(oit_gpu_algorithm *gpu, oit_status status, const char *stage,
                                    GLuint program, GLbitfield barriers, const oit_texture_unit *textures, int texture_count, oit_error *err)
{
    if (status != OIT_OK)
        return status;
    oit_timer_stage_begin(&gpu->timer, stage);
    if (barriers)
        glMemoryBarrier(barriers);
    glBindFramebuffer(GL_FRAMEBUFFER, gpu->output.framebuffer);
    glUseProgram(program);
    for (int i = 0; i < texture_count; ++i) {
        glActiveTexture(GL_TEXTURE0 + textures[i].unit);
        glBindTexture(GL_TEXTURE_2D, textures[i].texture);
    }
    glActiveTexture(GL_TEXTURE0);
    oit_gl_draw_fullscreen(&gpu->output);
    oit_timer_stage_end(&gpu->timer);
    return oit_gpu_stage_check(gpu, stage, err);
}

oit_status oit_gpu_read_image(oit_algorithm *alg, oit_image *out, oit_error *err)
{
    return oit_gl_output_read(&((oit_gpu_algorithm *)alg)->output, out, err);
}

void oit_gpu_stats(const oit_algorithm *alg, oit_stats *out)
{
    *out = ((const oit_gpu_algorithm *)alg)->stats;
}

oit_status oit_gpu_accumulate(oit_algorithm *alg, int sample, int samples, oit_stats *frame, oit_error *err)
{
    oit_gpu_algorithm *gpu = (oit_gpu_algorithm *)alg;
    int width = gpu->output.width, height = gpu->output.height;
    if (samples <= 1 || (gpu->sample_sum && (gpu->sample_sum_width != width || gpu->sample_sum_height != height))) {
        if (gpu->sample_sum)
            oit_gl_memory_delete_textures(&gpu->memory, 1, &gpu->sample_sum);
        gpu->sample_sum = 0;
        if (samples <= 1)
            return OIT_OK;
    }
    if (sample < 0 || sample >= samples || samples > OIT_SAMPLES_MAX || !frame || !gpu->output.colour)
        return oit_fail(err, OIT_E_RUNTIME, "%s: sample %d of %d cannot be accumulated", gpu->name, sample,
                        samples);
    if (!gpu->sample_program) { /* built on first use, outside the stage's time */
        oit_status status = oit_gpu_compute_program(gpu, "common/samples_accumulate.comp", &gpu->sample_program, err);
        if (status != OIT_OK)
            return status;
    }
    glFinish();
    double start = oit_now_ms();
    if (!gpu->sample_sum) {
        gpu->sample_sum = oit_gl_memory_texture_2d(&gpu->memory, OIT_GL_MEMORY_PIXELS, GL_RGBA16UI, width, height);
        gpu->sample_sum_width = width;
        gpu->sample_sum_height = height;
    }
    int step = sample == 0 ? OIT_SAMPLES_STORE : sample + 1 < samples ? OIT_SAMPLES_ADD : OIT_SAMPLES_RESOLVE;
    glMemoryBarrier(GL_ALL_BARRIER_BITS); /* the frame's last writes to the output */
    glBindImageTexture(OIT_IMAGE_SAMPLES_OUTPUT, gpu->output.colour, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8UI);
    glBindImageTexture(OIT_IMAGE_SAMPLES_SUM, gpu->sample_sum, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16UI);
    glUseProgram(gpu->sample_program);
    glUniform1i(glGetUniformLocation(gpu->sample_program, "u_step"), step);
    glUniform1ui(glGetUniformLocation(gpu->sample_program, "u_samples"), (GLuint)samples);
    glDispatchCompute((GLuint)(width + 7) / 8, (GLuint)(height + 7) / 8, 1);
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    glUseProgram(0);
    glBindImageTexture(OIT_IMAGE_SAMPLES_OUTPUT, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8UI);
    glBindImageTexture(OIT_IMAGE_SAMPLES_SUM, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16UI);
    glFinish();
    double ms = oit_now_ms() - start;
    char where[64];
    snprintf(where, sizeof where, "%s: samples_accumulate", gpu->name);
    oit_status status = oit_gl_check(where, err);
    if (status != OIT_OK)
        return status;
    oit_stats_add_stage(frame, "samples_accumulate", ms);
    frame->cpu_ms += ms;
    uint64_t held = oit_gl_memory_total(&gpu->memory);
    frame->memory_bytes = held > frame->memory_bytes ? held : frame->memory_bytes;
    frame->bytes_per_pixel =
        (double)oit_gl_memory_bytes(&gpu->memory, OIT_GL_MEMORY_PIXELS) / ((double)width * (double)height);
    if (step == OIT_SAMPLES_RESOLVE)
        gpu->stats = *frame;
    return OIT_OK;
}
