/* gl_frame.c: what every pass of a frame sets and draws: the frame's
 * uniforms, per-part opacity, the scene's draw call and the fragment
 * counters' read-back (gl_util.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"
#include "sections.h"

/* ------------------------------------------------------------- geometry */

/* Matrices are double in C and float on the GPU: rounded here, once. */
static void round_matrix4(const double m[16], float out[16])
{
    for (int i = 0; i < 16; ++i)
        out[i] = (float)m[i];
}

void oit_gl_frame_block(const oit_frame_settings *frame, oit_frame_block *out)
{
    memset(out, 0, sizeof *out);
    round_matrix4(frame->modelview, out->modelview);
    round_matrix4(frame->projection, out->projection);
    double matrix[16];
    oit_plane_to_eye_double(frame, matrix);
    round_matrix4(matrix, out->plane_to_eye);
    oit_mat4_inverse_double(frame->modelview, matrix); /* zero if singular */
    round_matrix4(matrix, out->inverse_modelview);
    oit_mat4_inverse_double(frame->projection, matrix); /* zero if singular */
    round_matrix4(matrix, out->inverse_projection);
    double normal_matrix[9];
    if (!oit_mat4_normal_matrix(frame->modelview, normal_matrix)) {
        /* singular modelview: fall back to its upper 3x3 */
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row)
                normal_matrix[col * 3 + row] = frame->modelview[col * 4 + row];
    }
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            out->normal_matrix[col * 4 + row] = (float)normal_matrix[col * 3 + row];
    for (int c = 0; c < 3; ++c)
        out->background[c] = frame->background[c];
    out->alpha = frame->alpha;
    out->viewport[0] = frame->width;
    out->viewport[1] = frame->height;
    out->shading = frame->shading == OIT_SHADE_HEADLIGHT ? OIT_SHADING_HEADLIGHT : OIT_SHADING_FLAT;
    /* the local modulation of common/local_modulation.glsl (docs/modulation.md) */
    const oit_local_modulation *local = &frame->local;
    out->focus_shape = (int32_t)local->focus_shape;
    for (int i = 0; i < 3; ++i) {
        out->focus_a[i] = (float)local->focus[i];
        out->focus_b[i] = (float)local->focus[3 + i];
    }
    out->focus_a[3] = local->focus_shape == OIT_FOCUS_BOX ? 0.0f : (float)local->focus[3];
    out->focus_region = oit_local_focus_region(frame);
    out->contrast = local->contrast;
    const oit_modulation *m = &frame->modulation;
    out->distance_mode = m->mode == OIT_MODULATE_DISTANCE ? (int32_t)m->distance : -1;
    out->distance_skip = m->distance_skip > 0 ? m->distance_skip : 2;
    /* auto (0): the algorithm writes the frame's largest distance once it knows it */
    out->distance_norm = m->focus_region > 0.0f ? m->focus_region : 1.0f;
    /* section planes in eye space (sections.h; oit_frame_relative checked them:
     * a frame that fails here draws no planes) */
    uint32_t section_count = 0;
    if (oit_section_eye_planes(frame, out->section_planes, &section_count, NULL) != OIT_OK)
        section_count = 0;
    out->section_count = (int32_t)section_count;
    out->section_all_parts = local->section_parts == NULL;
    /* per-part opacity and the parts the sections cut are no parameters: oit_gl_bind_part_alpha */
}

oit_status oit_gl_check_frame_block(GLuint program, const char *description, oit_error *err)
{
    if (glGetUniformBlockIndex(program, "oit_frame_block") == GL_INVALID_INDEX)
        return OIT_OK;
    static const struct {
        const char *name;
        GLint offset;
    } members[] = {
        {"u_modelview", OIT_FRAME_MODELVIEW},
        {"u_projection", OIT_FRAME_PROJECTION},
        {"u_plane_to_eye", OIT_FRAME_PLANE_TO_EYE},
        {"u_local_inverse_modelview", OIT_FRAME_INVERSE_MODELVIEW},
        {"u_local_inverse_projection", OIT_FRAME_INVERSE_PROJECTION},
        {"u_normal_matrix", OIT_FRAME_NORMAL_MATRIX},
        {"u_background", OIT_FRAME_BACKGROUND},
        {"u_alpha", OIT_FRAME_ALPHA},
        {"u_local_focus_a", OIT_FRAME_FOCUS_A},
        {"u_local_focus_b", OIT_FRAME_FOCUS_B},
        {"u_viewport", OIT_FRAME_VIEWPORT},
        {"u_shading", OIT_FRAME_SHADING},
        {"u_local_focus_shape", OIT_FRAME_FOCUS_SHAPE},
        {"u_local_focus_region", OIT_FRAME_FOCUS_REGION},
        {"u_local_contrast", OIT_FRAME_CONTRAST},
        {"u_distance_mode", OIT_FRAME_DISTANCE_MODE},
        {"u_distance_skip", OIT_FRAME_DISTANCE_SKIP},
        {"u_distance_norm", OIT_FRAME_DISTANCE_NORM},
        {"u_section_count", OIT_FRAME_SECTION_COUNT},
        {"u_section_all_parts", OIT_FRAME_SECTION_ALL_PARTS},
        {"u_section_planes", OIT_FRAME_SECTION_PLANES},
    };
    for (size_t i = 0; i < sizeof members / sizeof members[0]; ++i) {
        GLuint index = GL_INVALID_INDEX;
        glGetUniformIndices(program, 1, &members[i].name, &index);
        if (index == GL_INVALID_INDEX)
            continue; /* not used by this program */
        GLint offset = -1;
        glGetActiveUniformsiv(program, 1, &index, GL_UNIFORM_OFFSET, &offset);
        if (offset != members[i].offset)
            return oit_fail(err, OIT_E_RUNTIME,
                            "%s: %s is at byte %d of the frame block, oit_shared.h says %d",
                            description, members[i].name, offset, members[i].offset);
    }
    return OIT_OK;
}

/* both per-part buffer textures: opacity and highlight */
static void bind_part_alpha_texture(const oit_scene *scene)
{
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_LOCAL_PART_ALPHA);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_alpha_texture);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_LOCAL_PART_TINT);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_tint_texture);
    glActiveTexture(GL_TEXTURE0 + OIT_TEXUNIT_LOCAL_PART_SECTION);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_section_texture);
    glActiveTexture(GL_TEXTURE0);
}

/* The selection highlight (oit_local_modulation.component_highlight): per
 * part its colour and weight, 0 for every part when the frame highlights none
 * (the shaders then leave the colour as it is). */
static void write_part_tint(const oit_scene *scene, const oit_local_modulation *local)
{
    if (!scene->part_tint_buffer)
        return;
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_tint_buffer);
    const uint32_t given = local->component_highlight
                               ? (local->component_highlight_count < scene->part_count
                                      ? local->component_highlight_count
                                      : scene->part_count)
                               : 0;
    bool any = false;
    for (uint32_t i = 0; i < given && !any; ++i)
        any = local->component_highlight[i] > 0.0f;
    const uint32_t written = any ? given : 0;
    /* in chunks from the stack: no allocation that could fail */
    float tint[4 * 256];
    for (uint32_t first = 0; first < written; first += 256) {
        const uint32_t n = written - first < 256 ? written - first : 256;
        for (uint32_t i = 0; i < n; ++i)
            tint[4 * i + 3] = oit_local_highlight(local, first + i, &tint[4 * i]);
        glBufferSubData(GL_TEXTURE_BUFFER, (GLintptr)first * 4 * (GLintptr)sizeof(float),
                        (GLsizeiptr)n * 4 * (GLsizeiptr)sizeof(float), tint);
    }
    const float none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (written < scene->part_count)
        glClearBufferSubData(GL_TEXTURE_BUFFER, GL_RGBA32F,
                             (GLintptr)written * 4 * (GLintptr)sizeof(float),
                             (GLsizeiptr)(scene->part_count - written) * 4 * (GLsizeiptr)sizeof(float),
                             GL_RGBA, GL_FLOAT, none);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

/* Which parts the sections cut (oit_local_modulation.section_parts): written
 * only when the frame names parts and has planes (the shaders read it only
 * then, u_section_all_parts 0); parts past the flags the frame gives are not cut. */
static void write_part_sections(const oit_scene *scene, const oit_local_modulation *local)
{
    if (!scene->part_section_buffer || !local->section_parts || local->section_count == 0)
        return;
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_section_buffer);
    uint8_t flags[1024];
    for (uint32_t first = 0; first < scene->part_count; first += 1024) {
        const uint32_t n = scene->part_count - first < 1024 ? scene->part_count - first : 1024;
        for (uint32_t i = 0; i < n; ++i)
            flags[i] = oit_section_cuts_part(local, first + i) ? 1 : 0;
        glBufferSubData(GL_TEXTURE_BUFFER, (GLintptr)first, (GLsizeiptr)n, flags);
    }
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
}

/* The one place C hands per-part opacity (and the selection highlight) to the GPU. The buffer is the
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
    write_part_tint(scene, local);
    write_part_sections(scene, local);
    bind_part_alpha_texture(scene);
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
