/* fragment_pool.c: see fragment_pool.h. */
#include <stdio.h>

#include "fragment_pool.h"

#define POOL_MEGABYTE (1024.0 * 1024.0)

uint64_t oit_pool_bytes_per_fragment(const oit_fragment_pool *pool)
{
    uint64_t bytes = 0;
    for (int i = 0; i < pool->buffer_count; ++i)
        bytes += pool->buffer_bytes[i];
    return bytes;
}

uint64_t oit_pool_budget(const oit_fragment_pool *pool)
{
    return pool->budget_bytes / oit_pool_bytes_per_fragment(pool);
}

uint64_t oit_pool_limit(const oit_fragment_pool *pool)
{
    uint64_t budget = oit_pool_budget(pool);
    return budget < pool->gl_limit ? budget : pool->gl_limit;
}

oit_status oit_pool_allocate(oit_fragment_pool *pool, uint64_t capacity, oit_error *err)
{
    if (capacity == 0)
        capacity = 1; /* zero-sized buffers cannot be bound */
    while (glGetError() != GL_NO_ERROR) {
    }
    for (int i = 0; i < pool->buffer_count; ++i)
        oit_gl_memory_buffer_data(pool->memory, OIT_GL_MEMORY_FRAGMENTS, GL_SHADER_STORAGE_BUFFER,
                                  pool->buffers[i], capacity * pool->buffer_bytes[i], NULL,
                                  GL_DYNAMIC_COPY);
    for (int i = 0; i < pool->view_count; ++i) {
        glBindTexture(GL_TEXTURE_BUFFER, pool->views[i]);
        glTexBuffer(GL_TEXTURE_BUFFER, pool->view_format[i], pool->buffers[pool->view_buffer[i]]);
    }
    glBindTexture(GL_TEXTURE_BUFFER, 0);
    GLenum error = glGetError();
    if (error != GL_NO_ERROR) {
        pool->capacity = 0;
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: could not allocate a fragment pool of %llu fragments (%.1f MB): "
                        "GL error 0x%04x",
                        pool->algorithm, (unsigned long long)capacity,
                        (double)(capacity * oit_pool_bytes_per_fragment(pool)) / POOL_MEGABYTE,
                        (unsigned)error);
    }
    pool->capacity = capacity;
    return OIT_OK;
}

oit_status oit_pool_grow(oit_fragment_pool *pool, uint64_t needed, oit_error *err)
{
    if (needed > oit_pool_budget(pool))
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: the frame needs %llu fragments (%.1f MB), over the --max-memory "
                        "budget of %.1f MB",
                        pool->algorithm, (unsigned long long)needed,
                        (double)(needed * oit_pool_bytes_per_fragment(pool)) / POOL_MEGABYTE,
                        (double)pool->budget_bytes / POOL_MEGABYTE);
    if (needed > pool->gl_limit)
        return oit_fail(err, OIT_E_RUNTIME,
                        "%s: the frame needs %llu fragments, more than this GL can address in "
                        "%s (%llu%s)",
                        pool->algorithm, (unsigned long long)needed, pool->gl_binding,
                        (unsigned long long)pool->gl_limit, pool->gl_binding_note);
    uint64_t capacity = needed + needed / 4; /* headroom, so a camera move rarely refills */
    uint64_t limit = oit_pool_limit(pool);
    if (capacity > limit)
        capacity = limit;
    return oit_pool_allocate(pool, capacity, err);
}

void oit_pool_limit_text(const oit_fragment_pool *pool, char *out, size_t size)
{
    if (oit_pool_budget(pool) < pool->gl_limit)
        snprintf(out, size, "the --max-memory budget of %.1f MB holds (%llu)",
                 (double)pool->budget_bytes / POOL_MEGABYTE,
                 (unsigned long long)oit_pool_budget(pool));
    else
        snprintf(out, size, "this GL can address in %s (%llu)", pool->gl_binding,
                 (unsigned long long)pool->gl_limit);
}
