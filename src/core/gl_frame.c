/* gl_frame.c: what every pass of a frame sets and draws: the frame's
 * uniforms, per-part opacity, the scene's draw call and the fragment
 * counters' read-back (gl_util.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* ------------------------------------------------------------- geometry */

/* Uniform names as declared in shaders/common/frame.glsl. A uniform the
 * program does not use is inactive; setting its location would be
 * GL_INVALID_OPERATION, hence the lookup by name. */
static bool uniform_active(GLuint program, const char *name, GLint location)
{
    return glGetUniformLocation(program, name) == location;
}

/* Matrices are double in C and float on the GPU: rounded here, once. */
static void set_matrix4_uniform(GLint location, const double m[16])
{
    float rounded[16];
    for (int i = 0; i < 16; ++i)
        rounded[i] = (float)m[i];
    glUniformMatrix4fv(location, 1, GL_FALSE, rounded);
}

/* The local modulation of common/local_modulation.glsl (docs/modulation.md). */
static void set_local_uniforms(GLuint p, const oit_local_modulation *local,
                               const oit_frame_settings *frame)
{
    if (uniform_active(p, "u_local_focus_shape", OIT_UNIFORM_LOCAL_FOCUS_SHAPE))
        glUniform1i(OIT_UNIFORM_LOCAL_FOCUS_SHAPE, (GLint)local->focus_shape);
    if (uniform_active(p, "u_local_focus_a", OIT_UNIFORM_LOCAL_FOCUS_A))
        glUniform4f(OIT_UNIFORM_LOCAL_FOCUS_A, (float)local->focus[0], (float)local->focus[1],
                    (float)local->focus[2], local->focus_shape == OIT_FOCUS_BOX ? 0.0f : (float)local->focus[3]);
    if (uniform_active(p, "u_local_focus_b", OIT_UNIFORM_LOCAL_FOCUS_B))
        glUniform4f(OIT_UNIFORM_LOCAL_FOCUS_B, (float)local->focus[3], (float)local->focus[4],
                    (float)local->focus[5], 0.0f);
    if (uniform_active(p, "u_local_focus_region", OIT_UNIFORM_LOCAL_FOCUS_REGION))
        glUniform1f(OIT_UNIFORM_LOCAL_FOCUS_REGION, oit_local_focus_region(frame));
    if (uniform_active(p, "u_local_contrast", OIT_UNIFORM_LOCAL_CONTRAST))
        glUniform1f(OIT_UNIFORM_LOCAL_CONTRAST, local->contrast);
    if (uniform_active(p, "u_local_inverse_modelview", OIT_UNIFORM_LOCAL_INVERSE_MODELVIEW)) {
        double inverse[16];
        oit_mat4_inverse_double(frame->modelview, inverse); /* zero if singular */
        set_matrix4_uniform(OIT_UNIFORM_LOCAL_INVERSE_MODELVIEW, inverse);
    }
    if (uniform_active(p, "u_local_inverse_projection", OIT_UNIFORM_LOCAL_INVERSE_PROJECTION)) {
        double inverse[16];
        oit_mat4_inverse_double(frame->projection, inverse); /* zero if singular */
        set_matrix4_uniform(OIT_UNIFORM_LOCAL_INVERSE_PROJECTION, inverse);
    }
    const oit_modulation *m = &frame->modulation;
    if (uniform_active(p, "u_distance_mode", OIT_UNIFORM_DISTANCE_MODE))
        glUniform1i(OIT_UNIFORM_DISTANCE_MODE,
                    m->mode == OIT_MODULATE_DISTANCE ? (GLint)m->distance : -1);
    if (uniform_active(p, "u_distance_skip", OIT_UNIFORM_DISTANCE_SKIP))
        glUniform1i(OIT_UNIFORM_DISTANCE_SKIP, m->distance_skip > 0 ? m->distance_skip : 2);
    /* auto (0): the algorithm sets the frame's largest distance once it knows it */
    if (uniform_active(p, "u_distance_norm", OIT_UNIFORM_DISTANCE_NORM))
        glUniform1f(OIT_UNIFORM_DISTANCE_NORM, m->focus_region > 0.0f ? m->focus_region : 1.0f);
    /* per-part opacity is no uniform: oit_gl_bind_part_alpha */
}

static void bind_part_alpha_texture(const oit_scene *scene)
{
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_LOCAL_PART_ALPHA);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_alpha_texture);
    glActiveTexture(GL_TEXTURE0);
}

/* The one place C hands per-part opacity to the GPU. The buffer is the
 * scene's (allocated once at upload, part_count floats, counted in
 * oit_scene.gpu_bytes), so every algorithm drawing the scene shares it and
 * no algorithm's memory figures change with the number of parts. */
void oit_gl_bind_part_alpha(const oit_scene *scene, const oit_frame_settings *frame)
{
    if (!scene->has_gpu || !scene->part_alpha_buffer)
        return;
    const oit_local_modulation *local = &frame->local;
    const uint32_t given = local->component_alpha
                               ? (local->component_count < scene->part_count ? local->component_count
                                                                            : scene->part_count)
                               : 0;
    const float one = 1.0f;
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_alpha_buffer);
    if (given > 0)
        glBufferSubData(GL_TEXTURE_BUFFER, 0, (GLsizeiptr)given * (GLsizeiptr)sizeof(float),
                        local->component_alpha);
    if (given < scene->part_count) /* the parts the frame does not set: 1 */
        glClearBufferSubData(GL_TEXTURE_BUFFER, GL_R32F, (GLintptr)given * (GLintptr)sizeof(float),
                             (GLsizeiptr)(scene->part_count - given) * (GLsizeiptr)sizeof(float),
                             GL_RED, GL_FLOAT, &one);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bind_part_alpha_texture(scene);
}

void oit_gl_set_frame_uniforms(const oit_frame_settings *frame)
{
    GLint program = 0;
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    if (!program)
        return;
    GLuint p = (GLuint)program;
    if (uniform_active(p, "u_modelview", OIT_UNIFORM_MODELVIEW))
        set_matrix4_uniform(OIT_UNIFORM_MODELVIEW, frame->modelview);
    if (uniform_active(p, "u_projection", OIT_UNIFORM_PROJECTION))
        set_matrix4_uniform(OIT_UNIFORM_PROJECTION, frame->projection);
    if (uniform_active(p, "u_normal_matrix", OIT_UNIFORM_NORMAL_MATRIX)) {
        double normal_matrix[9];
        float rounded[9];
        if (!oit_mat4_normal_matrix(frame->modelview, normal_matrix)) {
            /* singular modelview: fall back to its upper 3x3 */
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row)
                    normal_matrix[col * 3 + row] = frame->modelview[col * 4 + row];
        }
        for (int i = 0; i < 9; ++i)
            rounded[i] = (float)normal_matrix[i];
        glUniformMatrix3fv(OIT_UNIFORM_NORMAL_MATRIX, 1, GL_FALSE, rounded);
    }
    if (uniform_active(p, "u_alpha", OIT_UNIFORM_ALPHA))
        glUniform1f(OIT_UNIFORM_ALPHA, frame->alpha);
    if (uniform_active(p, "u_shading", OIT_UNIFORM_SHADING))
        glUniform1i(OIT_UNIFORM_SHADING,
                    frame->shading == OIT_SHADE_HEADLIGHT ? OIT_SHADING_HEADLIGHT
                                                          : OIT_SHADING_FLAT);
    if (uniform_active(p, "u_background", OIT_UNIFORM_BACKGROUND))
        glUniform3fv(OIT_UNIFORM_BACKGROUND, 1, frame->background);
    if (uniform_active(p, "u_viewport", OIT_UNIFORM_VIEWPORT))
        glUniform2i(OIT_UNIFORM_VIEWPORT, frame->width, frame->height);
    if (uniform_active(p, "u_plane_to_eye", OIT_UNIFORM_PLANE_TO_EYE)) {
        double plane_to_eye[16];
        oit_plane_to_eye_double(frame, plane_to_eye);
        set_matrix4_uniform(OIT_UNIFORM_PLANE_TO_EYE, plane_to_eye);
    }
    set_local_uniforms(p, &frame->local, frame);
}

/* --------------------------------------------------------------- limits */

uint64_t oit_gl_read_frame_fragments(GLuint counter_buffer, int wraps_slot)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint low = 0, wraps = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, counter_buffer);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, OIT_FRAME_COUNTER_FRAGMENTS * sizeof(GLuint),
                       sizeof low, &low);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)wraps_slot * sizeof(GLuint), sizeof wraps,
                       &wraps);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    return (uint64_t)wraps << 32 | low;
}

oit_status oit_gl_check_frame_fragments(const char *algorithm, uint64_t fragments,
                                        uint32_t counter_start, oit_error *err)
{
    if (fragments <= OIT_MAX_FRAME_FRAGMENTS)
        return OIT_OK;
    char started[96] = "";
    if (counter_start)
        snprintf(started, sizeof started, " (config.fragment_counter_start %u included)",
                 (unsigned)counter_start);
    return oit_fail(err, OIT_E_RUNTIME,
                    "%s: the frame has %llu fragments%s, more than the %llu its 32-bit fragment "
                    "counter and node indices can number",
                    algorithm, (unsigned long long)fragments, started,
                    (unsigned long long)OIT_MAX_FRAME_FRAGMENTS);
}

oit_status oit_gl_check_sorted_fragments(const char *algorithm, uint64_t stored, uint64_t sorted,
                                         oit_error *err)
{
    if (sorted == stored)
        return OIT_OK;
    return oit_fail(err, OIT_E_RUNTIME,
                    "%s: the sort found %llu of the frame's %llu fragments: this GL cut a per-pixel "
                    "shader loop short (Mesa llvmpipe ends a loop after 65535 iterations, the "
                    "loops nested in it included), so a pixel's list is too long for it",
                    algorithm, (unsigned long long)sorted, (unsigned long long)stored);
}

void oit_gl_draw_scene(const oit_scene *scene)
{
    if (!scene->has_gpu || scene->index_count == 0)
        return;
    glBindVertexArray(scene->vertex_array);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, OIT_SSBO_COMPONENTS, scene->component_buffer);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_PLANES);
    glBindTexture(GL_TEXTURE_BUFFER, scene->plane_texture);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_TRIANGLE_PLANES);
    glBindTexture(GL_TEXTURE_BUFFER, scene->triangle_plane_texture);
    bind_part_alpha_texture(scene); /* bound by oit_gl_bind_part_alpha already; kept robust */
    glDrawElements(GL_TRIANGLES, (GLsizei)scene->index_count, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
}
