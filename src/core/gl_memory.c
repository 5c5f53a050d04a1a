/* gl_memory.c: the memory tracker every texture and buffer goes through, and
 * its independent check from the driver's own figures (gl_util.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* ------------------------------------------------------------- memory */

size_t oit_gl_texel_bytes(GLenum internal_format)
{
    switch (internal_format) {
    case GL_R8:
    case GL_R8UI:
    case GL_R8I:
        return 1;
    case GL_RG8:
    case GL_R16F:
    case GL_R16UI:
    case GL_R16I:
    case GL_DEPTH_COMPONENT16:
        return 2;
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
    case GL_RG16F:
    case GL_R32F:
    case GL_R32UI:
    case GL_R32I:
    case GL_RGB10_A2:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH24_STENCIL8:
        return 4;
    case GL_RGBA16F:
    case GL_RGBA16:
    case GL_RG32F:
    case GL_RG32UI:
    case GL_RGBA16UI:
    case GL_RG32I:
        return 8;
    case GL_RGBA32F:
    case GL_RGBA32UI:
    case GL_RGBA32I:
        return 16;
    default:
        return 0;
    }
}

/* The record of (name, texture), or NULL. */
static oit_gl_memory_object *memory_find(oit_gl_memory *memory, GLuint name, bool texture)
{
    for (int i = 0; i < memory->count; ++i)
        if (memory->objects[i].name == name && memory->objects[i].texture == texture)
            return &memory->objects[i];
    return NULL;
}

static void memory_forget(oit_gl_memory *memory, GLuint name, bool texture)
{
    oit_gl_memory_object *object = memory_find(memory, name, texture);
    if (!object)
        return;
    memory->bytes[object->use] -= object->bytes;
    *object = memory->objects[--memory->count];
}

static void memory_record(oit_gl_memory *memory, GLuint name, bool texture, oit_gl_memory_use use,
                          uint64_t bytes)
{
    memory_forget(memory, name, texture); /* a buffer store respecified replaces the old one */
    if (memory->count == OIT_GL_MEMORY_MAX_OBJECTS) {
        fprintf(stderr, "oit: warning: more than %d GL objects to account for; the memory figures "
                        "leave %s %u out\n",
                OIT_GL_MEMORY_MAX_OBJECTS, texture ? "texture" : "buffer", name);
        return;
    }
    memory->objects[memory->count++] = (oit_gl_memory_object){name, texture, use, bytes};
    memory->bytes[use] += bytes;
}

GLuint oit_gl_memory_texture_2d(oit_gl_memory *memory, oit_gl_memory_use use, GLenum internal_format,
                                int width, int height)
{
    GLuint texture = oit_gl_texture_2d(internal_format, width, height);
    if (!memory || !texture)
        return texture;
    size_t texel = oit_gl_texel_bytes(internal_format);
    if (texel == 0)
        fprintf(stderr, "oit: warning: no texel size for internal format 0x%04x; the memory "
                        "figures leave texture %u out\n",
                (unsigned)internal_format, texture);
    memory_record(memory, texture, true, use, (uint64_t)width * (uint64_t)height * texel);
    return texture;
}

void oit_gl_memory_delete_textures(oit_gl_memory *memory, GLsizei count, GLuint *textures)
{
    for (GLsizei i = 0; memory && i < count; ++i)
        if (textures[i])
            memory_forget(memory, textures[i], true);
    glDeleteTextures(count, textures);
    for (GLsizei i = 0; i < count; ++i)
        textures[i] = 0;
}

void oit_gl_memory_buffer_data(oit_gl_memory *memory, oit_gl_memory_use use, GLenum target,
                               GLuint buffer, uint64_t bytes, const void *data, GLenum usage)
{
    glBindBuffer(target, buffer);
    glBufferData(target, (GLsizeiptr)bytes, data, usage);
    glBindBuffer(target, 0);
    if (memory && buffer)
        memory_record(memory, buffer, false, use, bytes);
}

void oit_gl_memory_delete_buffers(oit_gl_memory *memory, GLsizei count, GLuint *buffers)
{
    for (GLsizei i = 0; memory && i < count; ++i)
        if (buffers[i])
            memory_forget(memory, buffers[i], false);
    glDeleteBuffers(count, buffers);
    for (GLsizei i = 0; i < count; ++i)
        buffers[i] = 0;
}

uint64_t oit_gl_memory_total(const oit_gl_memory *memory)
{
    uint64_t total = 0;
    for (int use = 0; use < OIT_GL_MEMORY_USE_COUNT; ++use)
        total += memory->bytes[use];
    return total;
}

uint64_t oit_gl_memory_bytes(const oit_gl_memory *memory, oit_gl_memory_use use)
{
    return memory->bytes[use];
}

/* Names are scanned upwards until this many in a row are not objects. */
#define ENUMERATE_GAP 4096u

/* Bytes per texel (times 8) from the component sizes GL reports for a level. */
static int64_t level_bits(GLuint texture, GLint level)
{
    static const GLenum sizes[] = {GL_TEXTURE_RED_SIZE,   GL_TEXTURE_GREEN_SIZE,
                                   GL_TEXTURE_BLUE_SIZE,  GL_TEXTURE_ALPHA_SIZE,
                                   GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE,
                                   GL_TEXTURE_SHARED_SIZE};
    int64_t bits = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        GLint value = 0;
        glGetTextureLevelParameteriv(texture, level, sizes[k], &value);
        bits += value;
    }
    return bits;
}

/* The number of levels GL lets one query for a texture of this target. */
static GLint level_count(GLuint texture, GLint target)
{
    GLint immutable = 0, levels = 0, largest = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    if (immutable) {
        glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
        return levels;
    }
    if (target == GL_TEXTURE_RECTANGLE || target == GL_TEXTURE_2D_MULTISAMPLE ||
        target == GL_TEXTURE_2D_MULTISAMPLE_ARRAY)
        return 1;
    glGetIntegerv(target == GL_TEXTURE_3D         ? GL_MAX_3D_TEXTURE_SIZE
                  : target == GL_TEXTURE_CUBE_MAP ? GL_MAX_CUBE_MAP_TEXTURE_SIZE
                                                  : GL_MAX_TEXTURE_SIZE,
                  &largest);
    while (largest > 0) {
        ++levels;
        largest >>= 1;
    }
    return levels;
}

static int64_t texture_bytes(GLuint texture)
{
    /* A buffer texture's storage is its buffer's, counted with the buffers
     * (and texture parameters cannot be queried on it). */
    GLint buffer = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_BUFFER_DATA_STORE_BINDING, &buffer);
    if (buffer != 0)
        return 0;
    GLint target = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    /* Mesa refuses texture parameter queries on buffer textures: one without
     * a buffer lands here (the caller checks there was no error before) */
    if (target == GL_TEXTURE_BUFFER || glGetError() == GL_INVALID_OPERATION)
        return 0;
    int64_t faces = target == GL_TEXTURE_CUBE_MAP ? 6 : 1;
    int64_t bytes = 0;
    GLint levels = level_count(texture, target);
    for (GLint level = 0; level < levels; ++level) {
        GLint width = 0, height = 0, depth = 0, samples = 0, compressed = 0;
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_WIDTH, &width);
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_HEIGHT, &height);
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_DEPTH, &depth);
        if (width <= 0 || height <= 0 || depth <= 0)
            continue;
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_COMPRESSED, &compressed);
        if (compressed) {
            GLint image = 0;
            glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &image);
            bytes += faces * image;
            continue;
        }
        glGetTextureLevelParameteriv(texture, level, GL_TEXTURE_SAMPLES, &samples);
        int64_t texels = (int64_t)width * height * depth * (samples > 1 ? samples : 1);
        bytes += faces * texels * level_bits(texture, level) / 8;
    }
    return bytes;
}

static int64_t renderbuffer_bytes(GLuint renderbuffer)
{
    static const GLenum sizes[] = {GL_RENDERBUFFER_RED_SIZE,   GL_RENDERBUFFER_GREEN_SIZE,
                                   GL_RENDERBUFFER_BLUE_SIZE,  GL_RENDERBUFFER_ALPHA_SIZE,
                                   GL_RENDERBUFFER_DEPTH_SIZE, GL_RENDERBUFFER_STENCIL_SIZE};
    GLint width = 0, height = 0, samples = 0;
    glGetNamedRenderbufferParameteriv(renderbuffer, GL_RENDERBUFFER_WIDTH, &width);
    glGetNamedRenderbufferParameteriv(renderbuffer, GL_RENDERBUFFER_HEIGHT, &height);
    glGetNamedRenderbufferParameteriv(renderbuffer, GL_RENDERBUFFER_SAMPLES, &samples);
    int64_t bits = 0;
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; ++k) {
        GLint value = 0;
        glGetNamedRenderbufferParameteriv(renderbuffer, sizes[k], &value);
        bits += value;
    }
    return (int64_t)width * height * (samples > 1 ? samples : 1) * bits / 8;
}

int64_t oit_gl_enumerate_allocated_bytes(void)
{
    if (!glGetNamedBufferParameteri64v || !glGetTextureParameteriv ||
        !glGetTextureLevelParameteriv || !glGetNamedRenderbufferParameteriv)
        return -1;
    while (glGetError() != GL_NO_ERROR) {
    }
    int64_t total = 0;
    GLuint misses = 0;
    for (GLuint name = 1; misses < ENUMERATE_GAP; ++name) {
        if (!glIsBuffer(name)) {
            ++misses;
            continue;
        }
        misses = 0;
        GLint64 size = 0;
        glGetNamedBufferParameteri64v(name, GL_BUFFER_SIZE, &size);
        total += size;
        if (glGetError() != GL_NO_ERROR)
            return -1;
    }
    misses = 0;
    for (GLuint name = 1; misses < ENUMERATE_GAP; ++name) {
        if (!glIsTexture(name)) {
            ++misses;
            continue;
        }
        misses = 0;
        total += texture_bytes(name);
        if (glGetError() != GL_NO_ERROR)
            return -1;
    }
    misses = 0;
    for (GLuint name = 1; misses < ENUMERATE_GAP; ++name) {
        if (!glIsRenderbuffer(name)) {
            ++misses;
            continue;
        }
        misses = 0;
        total += renderbuffer_bytes(name);
        if (glGetError() != GL_NO_ERROR)
            return -1;
    }
    return total;
}
