/*
 * fragment_pool.h: the fragment pool of the list algorithms (ll, ib;
 * core-internal): storage buffers sized per fragment, read-only buffer-texture
 * views over them, a capacity that grows with headroom within the memory
 * budget and what one GL buffer binding can address, and the messages that
 * say which limit a frame met.
 */
#ifndef OIT_FRAGMENT_POOL_H
#define OIT_FRAGMENT_POOL_H

#include "gl_util.h"

#define OIT_POOL_MAX_BUFFERS 4
#define OIT_POOL_MAX_VIEWS 4

typedef struct oit_fragment_pool {
    const char *algorithm;       /* names it in messages: "ll" */
    const char *gl_binding;      /* what gl_limit is of, in messages: "one shader storage buffer" */
    const char *gl_binding_note; /* after the limit in a frame's message ("; GL_MAX_..."), or "" */
    oit_gl_memory *memory;       /* the algorithm's tracker (OIT_GL_MEMORY_FRAGMENTS) */
    uint64_t budget_bytes;       /* oit_algorithm_config.max_memory_bytes */
    int buffer_count;
    GLuint buffers[OIT_POOL_MAX_BUFFERS];
    uint64_t buffer_bytes[OIT_POOL_MAX_BUFFERS]; /* per fragment */
    int view_count;
    GLuint views[OIT_POOL_MAX_VIEWS];  /* buffer textures */
    int view_buffer[OIT_POOL_MAX_VIEWS]; /* over buffers[view_buffer[i]] */
    GLenum view_format[OIT_POOL_MAX_VIEWS];
    uint64_t gl_limit;           /* the most fragments one binding addresses (tests lower it) */
    uint64_t capacity;           /* fragments the pool holds */
} oit_fragment_pool;

/* The bytes of all its buffers per fragment. */
uint64_t oit_pool_bytes_per_fragment(const oit_fragment_pool *pool);
/* The fragments the memory budget allows. */
uint64_t oit_pool_budget(const oit_fragment_pool *pool);
/* The most it may hold: the budget's and the GL's limits, the smaller. */
uint64_t oit_pool_limit(const oit_fragment_pool *pool);
/* (Re)specifies every buffer for `capacity` fragments (at least 1) and its
 * views; the names stay, so bindings remain valid; the contents are undefined
 * until the next fill. */
oit_status oit_pool_allocate(oit_fragment_pool *pool, uint64_t capacity, oit_error *err);
/* Room for `needed` fragments with a quarter of headroom (so a camera move
 * rarely refills), within the limits; past the budget or the GL's binding,
 * OIT_E_RUNTIME naming the limit. */
oit_status oit_pool_grow(oit_fragment_pool *pool, uint64_t needed, oit_error *err);
/* "this GL can address in one shader storage buffer (N)" or "the --max-memory
 * budget of X MB holds (N)": whichever limits a band's pool. */
void oit_pool_limit_text(const oit_fragment_pool *pool, char *out, size_t size);

#endif
