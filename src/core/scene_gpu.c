/* scene_gpu.c: a model's vertex, index and component buffers on the GPU. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

void oit_scene_cpu(oit_scene *scene, const oit_model *model)
{
    memset(scene, 0, sizeof *scene);
    scene->model = model;
    scene->index_count = model ? model->triangle_count * 3 : 0;
}

static GLuint upload_attribute(GLuint location, const void *data, size_t bytes, int components,
                               bool integer, uint64_t *total)
{
    GLuint buffer = 0;
    glGenBuffers(1, &buffer);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)bytes, data, GL_STATIC_DRAW);
    if (integer)
        glVertexAttribIPointer(location, components, GL_UNSIGNED_INT, 0, NULL);
    else
        glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, NULL);
    glEnableVertexAttribArray(location);
    *total += bytes;
    return buffer;
}

oit_status oit_scene_upload(oit_scene *scene, const oit_model *model, oit_error *err)
{
    oit_scene_cpu(scene, model);
    if (!model->positions || !model->normals || !model->vertex_component ||
        (model->triangle_count && !model->indices) ||
        (model->component_count && !model->components))
        return oit_fail(err, OIT_E_INPUT,
                        "model is not finished (positions, normals, components and indices "
                        "are needed)");
    /* one glDrawElements draws the whole model: its count is a GLsizei */
    if (model->triangle_count > (uint32_t)(INT32_MAX / 3))
        return oit_fail(err, OIT_E_INPUT,
                        "model.triangle_count %u is more than the %d triangles one draw call "
                        "can draw (3 x triangles indices, a 32-bit GLsizei)",
                        model->triangle_count, INT32_MAX / 3);
    /* per-part opacity is read through a buffer texture, one texel per part */
    GLint max_texels = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    if (max_texels > 0 && model->component_count > (uint32_t)max_texels)
        return oit_fail(err, OIT_E_RUNTIME,
                        "model.component_count %u is more than the %d parts whose opacity this GL "
                        "holds in one buffer texture (GL_MAX_TEXTURE_BUFFER_SIZE)",
                        model->component_count, max_texels);
    if (model->vertex_section_cap && model->component_count > (1u << OIT_COMPONENT_CAP_SHIFT))
        return oit_fail(err, OIT_E_INPUT,
                        "model.component_count %u is more than the %u parts a model with section caps "
                        "can number (the component attribute's low %d bits)",
                        model->component_count, 1u << OIT_COMPONENT_CAP_SHIFT, OIT_COMPONENT_CAP_SHIFT);
    const size_t vertices = model->vertex_count;

    /* Models built in memory may lack welded ids: then every vertex is its own. */
    uint32_t *identity_ids = NULL;
    const uint32_t *welded_ids = model->welded_ids;
    if (!welded_ids) {
        identity_ids = malloc((vertices ? vertices : 1) * sizeof *identity_ids);
        if (!identity_ids)
            return oit_fail(err, OIT_E_RUNTIME, "out of memory uploading the model");
        for (size_t i = 0; i < vertices; ++i)
            identity_ids[i] = (uint32_t)i;
        welded_ids = identity_ids;
    }
    /* vec4 per component: rgb colour, a opacity (std430 array of vec4) */
    size_t component_slots = model->component_count ? model->component_count : 1;
    float *component_data = calloc(component_slots * 4, sizeof *component_data);
    if (!component_data) {
        free(identity_ids);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory uploading the model");
    }
    for (uint32_t i = 0; i < model->component_count; ++i) {
        memcpy(component_data + i * 4, model->components[i].colour, 3 * sizeof(float));
        component_data[i * 4 + 3] = model->components[i].opacity;
    }

    /* Section caps: the component attribute carries 1 + the cap's section
     * above OIT_COMPONENT_CAP_SHIFT (geometry.vert splits it off), so a cap
     * fragment is not removed by its own plane (docs/sections.md). */
    uint32_t *cap_components = NULL;
    if (model->vertex_section_cap) {
        cap_components = malloc((vertices ? vertices : 1) * sizeof *cap_components);
        if (!cap_components) {
            free(component_data);
            free(identity_ids);
            return oit_fail(err, OIT_E_RUNTIME, "out of memory uploading the model");
        }
        for (size_t v = 0; v < vertices; ++v)
            cap_components[v] = model->vertex_component[v] |
                                (uint32_t)model->vertex_section_cap[v] << OIT_COMPONENT_CAP_SHIFT;
    }

    glGenVertexArrays(1, &scene->vertex_array);
    glBindVertexArray(scene->vertex_array);
    uint64_t bytes = 0;
    scene->vertex_buffers[0] = upload_attribute(OIT_ATTRIB_POSITION, model->positions,
                                                vertices * 3 * sizeof(float), 3, false, &bytes);
    scene->vertex_buffers[1] = upload_attribute(OIT_ATTRIB_NORMAL, model->normals,
                                                vertices * 3 * sizeof(float), 3, false, &bytes);
    scene->vertex_buffers[2] = upload_attribute(OIT_ATTRIB_COMPONENT,
                                                cap_components ? cap_components : model->vertex_component,
                                                vertices * sizeof(uint32_t), 1, true, &bytes);
    scene->vertex_buffers[3] = upload_attribute(OIT_ATTRIB_WELDED_ID, welded_ids,
                                                vertices * sizeof(uint32_t), 1, true, &bytes);
    glGenBuffers(1, &scene->index_buffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, scene->index_buffer); /* recorded in the VAO */
    size_t index_bytes = (size_t)model->triangle_count * 3 * sizeof(uint32_t);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)index_bytes, model->indices,
                 GL_STATIC_DRAW);
    bytes += index_bytes;
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);

    glGenBuffers(1, &scene->component_buffer);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, scene->component_buffer);
    glBufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(component_slots * 4 * sizeof(float)),
                 component_data, GL_STATIC_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    bytes += component_slots * 4 * sizeof(float);
    /* per-part opacity, one float per part, all 1 until a frame sets them
     * (oit_gl_bind_part_alpha) */
    scene->part_count = model->component_count ? model->component_count : 1;
    const float one = 1.0f;
    glGenBuffers(1, &scene->part_alpha_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_alpha_buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)(scene->part_count * sizeof(float)), NULL,
                 GL_DYNAMIC_DRAW);
    glClearBufferData(GL_TEXTURE_BUFFER, GL_R32F, GL_RED, GL_FLOAT, &one);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bytes += scene->part_count * sizeof(float);
    glGenTextures(1, &scene->part_alpha_texture);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_alpha_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32F, scene->part_alpha_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    /* selection highlight, a vec4 per part, none until a frame sets one
     * (oit_gl_bind_part_alpha) */
    const float no_tint[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glGenBuffers(1, &scene->part_tint_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_tint_buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)(scene->part_count * 4 * sizeof(float)), NULL,
                 GL_DYNAMIC_DRAW);
    glClearBufferData(GL_TEXTURE_BUFFER, GL_RGBA32F, GL_RGBA, GL_FLOAT, no_tint);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bytes += scene->part_count * 4 * sizeof(float);
    glGenTextures(1, &scene->part_tint_texture);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_tint_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, scene->part_tint_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    /* which parts the sections cut, a byte per part, all until a frame names
     * some (oit_gl_bind_part_alpha) */
    const uint8_t cut = 1;
    glGenBuffers(1, &scene->part_section_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->part_section_buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)scene->part_count, NULL, GL_DYNAMIC_DRAW);
    glClearBufferData(GL_TEXTURE_BUFFER, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &cut);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bytes += scene->part_count;
    glGenTextures(1, &scene->part_section_texture);
    glBindTexture(GL_TEXTURE_BUFFER, scene->part_section_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R8UI, scene->part_section_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    /* per triangle its reach (ib's neighbour search), read as a buffer texture */
    glGenBuffers(1, &scene->triangle_reach_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->triangle_reach_buffer);
    size_t reach_bytes = (size_t)model->triangle_count * sizeof(float);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)reach_bytes, model->triangle_reach, GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bytes += reach_bytes;
    /* coplanar clusters: each triangle's plane, and the planes (canonical_depth.glsl) */
    const float no_plane[4] = {0.0f, 0.0f, 1.0f, 0.0f};
    const uint32_t plane_zero = 0;
    bool has_planes = model->planes && model->triangle_plane && model->plane_count > 0;
    size_t plane_bytes = has_planes ? (size_t)model->plane_count * 4 * sizeof(float) : sizeof no_plane;
    size_t triangle_plane_bytes = has_planes ? (size_t)model->triangle_count * sizeof(uint32_t) : sizeof plane_zero;
    glGenBuffers(1, &scene->plane_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->plane_buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)plane_bytes, has_planes ? (const void *)model->planes : no_plane,
                 GL_STATIC_DRAW);
    glGenBuffers(1, &scene->triangle_plane_buffer);
    glBindBuffer(GL_TEXTURE_BUFFER, scene->triangle_plane_buffer);
    glBufferData(GL_TEXTURE_BUFFER, (GLsizeiptr)triangle_plane_bytes,
                 has_planes ? (const void *)model->triangle_plane : &plane_zero, GL_STATIC_DRAW);
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    bytes += plane_bytes + triangle_plane_bytes;
    glGenTextures(1, &scene->plane_texture);
    glBindTexture(GL_TEXTURE_BUFFER, scene->plane_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, scene->plane_buffer);
    glGenTextures(1, &scene->triangle_plane_texture);
    glBindTexture(GL_TEXTURE_BUFFER, scene->triangle_plane_texture);
    glTexBuffer(GL_TEXTURE_BUFFER, GL_R32UI, scene->triangle_plane_buffer);
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    free(component_data);
    free(identity_ids);
    free(cap_components);

    scene->has_gpu = true;
    scene->index_count = model->triangle_count * 3;
    scene->gpu_bytes = bytes;
    oit_status status = oit_gl_check("uploading the model", err);
    if (status != OIT_OK)
        oit_scene_release(scene);
    return status;
}

void oit_scene_release(oit_scene *scene)
{
    if (scene->has_gpu) {
        glDeleteVertexArrays(1, &scene->vertex_array);
        glDeleteBuffers(4, scene->vertex_buffers);
        glDeleteBuffers(1, &scene->index_buffer);
        glDeleteBuffers(1, &scene->component_buffer);
        glDeleteTextures(1, &scene->part_alpha_texture);
        glDeleteBuffers(1, &scene->part_alpha_buffer);
        glDeleteTextures(1, &scene->part_tint_texture);
        glDeleteBuffers(1, &scene->part_tint_buffer);
        glDeleteTextures(1, &scene->part_section_texture);
        glDeleteBuffers(1, &scene->part_section_buffer);
        glDeleteBuffers(1, &scene->triangle_reach_buffer);
        glDeleteTextures(1, &scene->plane_texture);
        glDeleteTextures(1, &scene->triangle_plane_texture);
        glDeleteBuffers(1, &scene->plane_buffer);
        glDeleteBuffers(1, &scene->triangle_plane_buffer);
    }
    memset(scene, 0, sizeof *scene);
}
