/* gl_util.c: shader loading, error checks, stage timers, the memory tracker
 * (and its independent check), the RGBA8 output and scene drawing shared by
 * the GPU algorithms. */
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

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

/* ---------------------------------------------------------- stage timing */

double oit_now_ms(void)
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec * 1e3 + (double)now.tv_nsec * 1e-6;
}

static bool software_renderer(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") ||
                        strstr(renderer, "swrast"));
}

void oit_timer_create(oit_stage_timer *timer)
{
    memset(timer, 0, sizeof *timer);
    timer->wall_clock = software_renderer();
    if (!timer->wall_clock)
        glGenQueries(OIT_MAX_STAGES, timer->queries);
    timer->created = true;
}

void oit_timer_destroy(oit_stage_timer *timer)
{
    if (timer->created && !timer->wall_clock)
        glDeleteQueries(OIT_MAX_STAGES, timer->queries);
    memset(timer, 0, sizeof *timer);
}

void oit_timer_frame_begin(oit_stage_timer *timer, const oit_frame_settings *frame)
{
    timer->count = 0;
    timer->stage_open = false;
    memset(&timer->progress, 0, sizeof timer->progress);
    if (frame)
        timer->progress = frame->progress;
    timer->stages_done = 0;
    timer->cancelled = false;
    timer->cancelled_after[0] = '\0';
    if (timer->wall_clock)
        glFinish(); /* earlier work must not count towards the first stage */
    timer->cpu_start_ms = oit_now_ms();
}

/* The last slot, once begun, keeps running until the frame ends: that is
 * how it absorbs every stage past OIT_MAX_STAGES (time-elapsed queries
 * cannot be resumed). */
static bool last_slot_running(const oit_stage_timer *timer)
{
    return timer->count == OIT_MAX_STAGES;
}

static void slot_start(oit_stage_timer *timer, int slot)
{
    if (timer->wall_clock) {
        glFinish();
        timer->stage_start_ms = oit_now_ms();
    } else if (timer->created) {
        glBeginQuery(GL_TIME_ELAPSED, timer->queries[slot]);
    }
}

static void slot_stop(oit_stage_timer *timer, int slot)
{
    if (timer->wall_clock) {
        glFinish();
        timer->wall_ms[slot] = oit_now_ms() - timer->stage_start_ms;
    } else if (timer->created) {
        glEndQuery(GL_TIME_ELAPSED);
    }
}

void oit_timer_stage_begin(oit_stage_timer *timer, const char *name)
{
    if (timer->stage_open)
        oit_timer_stage_end(timer);
    if (last_slot_running(timer)) {
        snprintf(timer->names[OIT_MAX_STAGES - 1], OIT_STAGE_NAME_SIZE, "%s",
                 "(remaining stages)");
    } else {
        snprintf(timer->names[timer->count], OIT_STAGE_NAME_SIZE, "%s", name);
        slot_start(timer, timer->count);
        ++timer->count;
    }
    timer->stage_open = true;
}

void oit_timer_stage_end(oit_stage_timer *timer)
{
    if (!timer->stage_open)
        return;
    if (!last_slot_running(timer))
        slot_stop(timer, timer->count - 1);
    timer->stage_open = false;
    ++timer->stages_done;
    if (timer->progress.report && !timer->cancelled) {
        const char *name = timer->names[timer->count > 0 ? timer->count - 1 : 0];
        if (!timer->progress.report(timer->progress.user, name, timer->stages_done)) {
            timer->cancelled = true;
            snprintf(timer->cancelled_after, sizeof timer->cancelled_after, "%s", name);
        }
    }
}

oit_status oit_timer_status(const oit_stage_timer *timer, oit_error *err)
{
    if (!timer->cancelled)
        return OIT_OK;
    return oit_fail(err, OIT_CANCELLED, "the frame was cancelled after stage %s (%d stages done)",
                    timer->cancelled_after, timer->stages_done);
}

void oit_timer_frame_end(oit_stage_timer *timer, oit_stats *stats)
{
    oit_timer_stage_end(timer);
    if (last_slot_running(timer))
        slot_stop(timer, OIT_MAX_STAGES - 1);
    glFinish();
    stats->cpu_ms = oit_now_ms() - timer->cpu_start_ms;
    stats->stage_count = timer->count;
    for (int i = 0; i < timer->count; ++i) {
        snprintf(stats->stages[i].name, OIT_STAGE_NAME_SIZE, "%s", timer->names[i]);
        if (timer->wall_clock) {
            stats->stages[i].gpu_ms = timer->wall_ms[i];
        } else {
            GLuint64 nanoseconds = 0;
            if (timer->created)
                glGetQueryObjectui64v(timer->queries[i], GL_QUERY_RESULT, &nanoseconds);
            stats->stages[i].gpu_ms = (double)nanoseconds * 1e-6;
        }
    }
}

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
