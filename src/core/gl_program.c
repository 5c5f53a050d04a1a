/* gl_program.c: shader programs from the shader tree (#include expanded,
 * #line kept per file, variants by #define) and GL error checks (gl_util.h). */
#define _POSIX_C_SOURCE 200809L /* strdup */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_util.h"

/* ------------------------------------------------------------ programs */

#define SHADER_MAX_FILES 32
#define SHADER_MAX_INCLUDE_DEPTH 16

typedef struct shader_source {
    char *text;
    size_t length, capacity;
    char *files[SHADER_MAX_FILES]; /* index == GLSL source-string number in #line */
    int file_count;
} shader_source;

static bool source_append(shader_source *source, const char *text, size_t length)
{
    if (source->length + length + 1 > source->capacity) {
        size_t capacity = source->capacity ? source->capacity : 4096;
        while (source->length + length + 1 > capacity)
            capacity *= 2;
        char *grown = realloc(source->text, capacity);
        if (!grown)
            return false;
        source->text = grown;
        source->capacity = capacity;
    }
    memcpy(source->text + source->length, text, length);
    source->length += length;
    source->text[source->length] = '\0';
    return true;
}

static bool source_printf(shader_source *source, const char *fmt, int a, int b)
{
    char line[64];
    int length = snprintf(line, sizeof line, fmt, a, b);
    return source_append(source, line, (size_t)length);
}

static void source_free(shader_source *source)
{
    free(source->text);
    for (int i = 0; i < source->file_count; ++i)
        free(source->files[i]);
    memset(source, 0, sizeof *source);
}

static char *read_text_file(const char *path)
{
    /* a regular file only: a FIFO or a device in the shader tree would block
     * or never end (the caller names the path) */
    FILE *file;
    oit_error ignored;
    if (oit_open_regular_file(path, NULL, &file, &ignored) != OIT_OK)
        return NULL;
    char *text = NULL;
    if (fseek(file, 0, SEEK_END) == 0) {
        long size = ftell(file);
        if (size >= 0 && fseek(file, 0, SEEK_SET) == 0 && (text = malloc((size_t)size + 1))) {
            if (fread(text, 1, (size_t)size, file) != (size_t)size) {
                free(text);
                text = NULL;
            } else {
                text[size] = '\0';
            }
        }
    }
    fclose(file);
    return text;
}

/* If the line is `#include "path"`, copy path into out and return true. */
static bool parse_include(const char *line, size_t length, char *out, size_t out_size)
{
    const char *end = line + length;
    while (line < end && (*line == ' ' || *line == '\t'))
        ++line;
    if (line == end || *line != '#')
        return false;
    ++line;
    while (line < end && (*line == ' ' || *line == '\t'))
        ++line;
    if ((size_t)(end - line) < 7 || strncmp(line, "include", 7) != 0)
        return false;
    line += 7;
    while (line < end && (*line == ' ' || *line == '\t'))
        ++line;
    if (line == end || *line != '"')
        return false;
    const char *close = memchr(line + 1, '"', (size_t)(end - line - 1));
    if (!close || (size_t)(close - line - 1) >= out_size)
        return false;
    memcpy(out, line + 1, (size_t)(close - line - 1));
    out[close - line - 1] = '\0';
    return true;
}

static oit_status expand_file(shader_source *source, const char *shader_dir,
                              const char *relative_path, const char *included_from, int depth,
                              oit_error *err)
{
    for (int i = 0; i < source->file_count; ++i)
        if (strcmp(source->files[i], relative_path) == 0)
            return OIT_OK; /* expanded once per shader */
    if (depth > SHADER_MAX_INCLUDE_DEPTH)
        return oit_fail(err, OIT_E_RUNTIME, "shader %s: includes nested too deeply",
                        relative_path);
    if (source->file_count == SHADER_MAX_FILES)
        return oit_fail(err, OIT_E_RUNTIME, "shader %s: more than %d included files",
                        relative_path, SHADER_MAX_FILES);
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", shader_dir, relative_path);
    char *text = read_text_file(path);
    if (!text) {
        if (included_from)
            return oit_fail(err, OIT_E_RUNTIME, "shader %s: cannot read %s (included from %s)",
                            relative_path, path, included_from);
        return oit_fail(err, OIT_E_RUNTIME, "shader %s: cannot read %s", relative_path, path);
    }
    int file_number = source->file_count;
    source->files[source->file_count++] = strdup(relative_path);

    oit_status status = OIT_OK;
    if (!source_printf(source, "#line 1 %d\n", file_number, 0))
        status = oit_fail(err, OIT_E_RUNTIME, "shader %s: out of memory", relative_path);
    int line_number = 0;
    for (const char *line = text; status == OIT_OK && *line;) {
        const char *newline = strchr(line, '\n');
        size_t length = newline ? (size_t)(newline - line) : strlen(line);
        ++line_number;
        char include_path[512];
        if (parse_include(line, length, include_path, sizeof include_path)) {
            status = expand_file(source, shader_dir, include_path,
                                 source->files[file_number], depth + 1, err);
            if (status == OIT_OK &&
                !source_printf(source, "#line %d %d\n", line_number + 1, file_number))
                status = oit_fail(err, OIT_E_RUNTIME, "shader %s: out of memory", relative_path);
        } else if (!source_append(source, line, length) || !source_append(source, "\n", 1)) {
            status = oit_fail(err, OIT_E_RUNTIME, "shader %s: out of memory", relative_path);
        }
        line += length + (newline ? 1 : 0);
    }
    free(text);
    return status;
}

static oit_status compile_shader(const char *shader_dir, const char *path, const char *defines,
                                 GLenum type, GLuint *out, oit_error *err)
{
    *out = 0;
    shader_source source = {0};
    oit_status status = OIT_OK;
    if (!source_append(&source, "#version 430 core\n", 18) ||
        (defines && !source_append(&source, defines, strlen(defines))))
        status = oit_fail(err, OIT_E_RUNTIME, "shader %s: out of memory", path);
    if (status == OIT_OK)
        status = expand_file(&source, shader_dir, path, NULL, 0, err);
    if (status != OIT_OK) {
        source_free(&source);
        return status;
    }
    GLuint shader = glCreateShader(type);
    const GLchar *text = source.text;
    glShaderSource(shader, 1, &text, NULL);
    glCompileShader(shader);
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
        char files[256] = "";
        size_t used = 0;
        for (int i = 0; i < source.file_count && used < sizeof files; ++i)
            used += (size_t)snprintf(files + used, sizeof files - used, "%s%d=%s", i ? " " : "",
                                     i, source.files[i]);
        char log[OIT_ERROR_MESSAGE_SIZE];
        glGetShaderInfoLog(shader, sizeof log, NULL, log);
        status = oit_fail(err, OIT_E_RUNTIME, "compile error in %s%s%s (sources %s): %s", path,
                          defines ? " with " : "", defines ? defines : "", files, log);
        glDeleteShader(shader);
        shader = 0;
    }
    source_free(&source);
    *out = shader;
    return status;
}

static oit_status link_program(GLuint *shaders, int shader_count, const char *description,
                               GLuint *out, oit_error *err)
{
    GLuint program = glCreateProgram();
    for (int i = 0; i < shader_count; ++i)
        glAttachShader(program, shaders[i]);
    glLinkProgram(program);
    for (int i = 0; i < shader_count; ++i) {
        glDetachShader(program, shaders[i]);
        glDeleteShader(shaders[i]);
    }
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (!linked) {
        char log[OIT_ERROR_MESSAGE_SIZE];
        glGetProgramInfoLog(program, sizeof log, NULL, log);
        glDeleteProgram(program);
        *out = 0;
        return oit_fail(err, OIT_E_RUNTIME, "link error in %s: %s", description, log);
    }
    *out = program;
    return OIT_OK;
}

oit_status oit_gl_program(const char *shader_dir, const char *vertex_path,
                          const char *fragment_path, GLuint *out, oit_error *err)
{
    return oit_gl_program_variant(shader_dir, vertex_path, fragment_path, NULL, out, err);
}

oit_status oit_gl_program_variant(const char *shader_dir, const char *vertex_path,
                                  const char *fragment_path, const char *defines, GLuint *out,
                                  oit_error *err)
{
    *out = 0;
    GLuint shaders[2] = {0, 0};
    oit_status status =
        compile_shader(shader_dir, vertex_path, defines, GL_VERTEX_SHADER, &shaders[0], err);
    if (status != OIT_OK)
        return status;
    status =
        compile_shader(shader_dir, fragment_path, defines, GL_FRAGMENT_SHADER, &shaders[1], err);
    if (status != OIT_OK) {
        glDeleteShader(shaders[0]);
        return status;
    }
    char description[512];
    snprintf(description, sizeof description, "%s + %s", vertex_path, fragment_path);
    return link_program(shaders, 2, description, out, err);
}

oit_status oit_gl_compute_program(const char *shader_dir, const char *compute_path, GLuint *out,
                                  oit_error *err)
{
    *out = 0;
    GLuint shader = 0;
    oit_status status =
        compile_shader(shader_dir, compute_path, NULL, GL_COMPUTE_SHADER, &shader, err);
    if (status != OIT_OK)
        return status;
    return link_program(&shader, 1, compute_path, out, err);
}

/* -------------------------------------------------------------- errors */

static const char *gl_error_name(GLenum error)
{
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "unknown GL error";
    }
}

oit_status oit_gl_check(const char *where, oit_error *err)
{
    GLenum error = glGetError();
    /* Drain the queue so the next check starts clean. */
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i)
        ;
    char debug_message[OIT_ERROR_MESSAGE_SIZE];
    bool has_debug_message = oit_gl_debug_take_error(debug_message, sizeof debug_message);
    if (error != GL_NO_ERROR && has_debug_message)
        return oit_fail(err, OIT_E_RUNTIME, "%s in %s: %s", gl_error_name(error), where,
                        debug_message);
    if (error != GL_NO_ERROR)
        return oit_fail(err, OIT_E_RUNTIME, "%s (0x%04x) in %s", gl_error_name(error),
                        (unsigned)error, where);
    if (has_debug_message)
        return oit_fail(err, OIT_E_RUNTIME, "GL error in %s: %s", where, debug_message);
    return OIT_OK;
}

static const char *framebuffer_status_name(GLenum status)
{
    switch (status) {
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    default: return "incomplete";
    }
}

oit_status oit_gl_check_framebuffer(const char *what, int width, int height, const oit_gl_memory *memory,
                                    oit_error *err)
{
    GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE)
        return OIT_OK;
    GLenum error = glGetError();
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i)
        ;
    double total = memory ? (double)oit_gl_memory_total(memory) : 0.0;
    char amount[64] = "";
    if (memory)
        snprintf(amount, sizeof amount, total >= 1024.0 * 1024.0 * 1024.0 ? "%.2f GiB" : "%.1f MiB",
                 total / (total >= 1024.0 * 1024.0 * 1024.0 ? 1024.0 * 1024.0 * 1024.0 : 1024.0 * 1024.0));
    /* an attachment whose storage the driver could not allocate is the usual cause */
    bool allocation = error == GL_OUT_OF_MEMORY || status == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT;
    return oit_fail(err, OIT_E_RUNTIME, "%s is incomplete (%s, 0x%04x)%s at %dx%d%s%s%s%s", what,
                    framebuffer_status_name(status), (unsigned)status,
                    allocation ? ": the driver could not allocate its textures" : "", width, height,
                    memory ? ", the frame's textures and buffers needing " : "", amount,
                    memory ? " in all" : "", error == GL_OUT_OF_MEMORY ? " (GL_OUT_OF_MEMORY)" : "");
}
