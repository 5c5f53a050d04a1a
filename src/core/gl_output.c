/* gl_output.c: the RGBA8 output every algorithm renders into, its read-back
 * and the full-screen pass (gl_util.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* ------------------------------------------------------------- the output */

GLuint oit_gl_texture_2d(GLenum internal_format, int width, int height)
{
    GLuint texture = 0;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    return texture;
}

oit_status oit_gl_output_resize(oit_gl_output *output, int width, int height, oit_error *err)
{
    if (width <= 0 || height <= 0)
        return oit_fail(err, OIT_E_INPUT, "image size %dx%d is not positive", width, height);
    if (width > OIT_MAX_IMAGE_SIDE || height > OIT_MAX_IMAGE_SIDE)
        return oit_fail(err, OIT_E_INPUT,
                        "image size %dx%d: frame.width and frame.height must be within 1..%d "
                        "(pixels are counted in 32-bit counters; ib packs a pixel's x and y in 16 "
                        "bits each)",
                        width, height, OIT_MAX_IMAGE_SIDE);
    if (!output->fullscreen_vertex_array)
        glGenVertexArrays(1, &output->fullscreen_vertex_array);
    if (output->framebuffer && output->width == width && output->height == height)
        return OIT_OK;
    if (output->colour)
        oit_gl_memory_delete_textures(output->memory, 1, &output->colour);
    if (!output->framebuffer)
        glGenFramebuffers(1, &output->framebuffer);
    output->colour =
        oit_gl_memory_texture_2d(output->memory, OIT_GL_MEMORY_PIXELS, GL_RGBA8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, output->framebuffer);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, output->colour, 0);
    oit_status status = oit_gl_check_framebuffer("the RGBA8 output", width, height, output->memory, err);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    output->width = width;
    output->height = height;
    if (status != OIT_OK)
        return status;
    return oit_gl_check("creating the output", err);
}

void oit_gl_output_release(oit_gl_output *output)
{
    if (output->colour)
        oit_gl_memory_delete_textures(output->memory, 1, &output->colour);
    if (output->framebuffer)
        glDeleteFramebuffers(1, &output->framebuffer);
    if (output->fullscreen_vertex_array)
        glDeleteVertexArrays(1, &output->fullscreen_vertex_array);
    oit_gl_memory *memory = output->memory;
    memset(output, 0, sizeof *output);
    output->memory = memory;
}

oit_status oit_gl_output_read(const oit_gl_output *output, oit_image *out, oit_error *err)
{
    if (!output->framebuffer)
        return oit_fail(err, OIT_E_RUNTIME, "no image rendered yet");
    oit_status status = oit_image_alloc(out, output->width, output->height, err);
    if (status != OIT_OK)
        return status;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, output->framebuffer);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, output->width, output->height, GL_RGBA, GL_UNSIGNED_BYTE, out->rgba);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    /* GL returns the bottom row first; images are top row first. */
    size_t row_bytes = (size_t)output->width * 4;
    unsigned char *swap = malloc(row_bytes);
    if (!swap) {
        oit_image_free(out);
        return oit_fail(err, OIT_E_RUNTIME, "out of memory reading the image");
    }
    for (int top = 0, bottom = output->height - 1; top < bottom; ++top, --bottom) {
        memcpy(swap, out->rgba + (size_t)top * row_bytes, row_bytes);
        memcpy(out->rgba + (size_t)top * row_bytes, out->rgba + (size_t)bottom * row_bytes,
               row_bytes);
        memcpy(out->rgba + (size_t)bottom * row_bytes, swap, row_bytes);
    }
    free(swap);
    status = oit_gl_check("reading the image", err);
    if (status != OIT_OK)
        oit_image_free(out);
    return status;
}

void oit_gl_draw_fullscreen(const oit_gl_output *output)
{
    glBindVertexArray(output->fullscreen_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}
