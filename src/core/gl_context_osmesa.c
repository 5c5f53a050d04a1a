/*
 * gl_context_osmesa.c: the OSMesa back end (see gl_context.c for how GL entry
 * points reach this context).
 */
#include <GL/osmesa.h>
#include <stdlib.h>

#include "gl_context_osmesa.h"

/* The context never presents anything, but OSMesa needs a colour buffer to
 * make a context current. */
#define OSMESA_BUFFER_SIZE 16

struct oit_osmesa_context {
    OSMesaContext context;
    unsigned char buffer[OSMESA_BUFFER_SIZE * OSMESA_BUFFER_SIZE * 4];
};

oit_status oit_osmesa_create(int major, int minor, oit_osmesa_context **out, oit_error *err)
{
    *out = NULL;
    oit_osmesa_context *context = calloc(1, sizeof *context);
    if (!context)
        return oit_fail(err, OIT_E_RUNTIME, "osmesa: out of memory");
    const int attributes[] = {
        OSMESA_FORMAT, OSMESA_RGBA,
        OSMESA_DEPTH_BITS, 0,
        OSMESA_STENCIL_BITS, 0,
        OSMESA_ACCUM_BITS, 0,
        OSMESA_PROFILE, OSMESA_CORE_PROFILE,
        OSMESA_CONTEXT_MAJOR_VERSION, major,
        OSMESA_CONTEXT_MINOR_VERSION, minor,
        0,
    };
    context->context = OSMesaCreateContextAttribs(attributes, NULL);
    if (!context->context) {
        free(context);
        return oit_fail(err, OIT_E_RUNTIME,
                        "osmesa: cannot create an OpenGL %d.%d core-profile context", major,
                        minor);
    }
    if (!OSMesaMakeCurrent(context->context, context->buffer, GL_UNSIGNED_BYTE,
                           OSMESA_BUFFER_SIZE, OSMESA_BUFFER_SIZE)) {
        OSMesaDestroyContext(context->context);
        free(context);
        return oit_fail(err, OIT_E_RUNTIME, "osmesa: cannot make the context current");
    }
    *out = context;
    return OIT_OK;
}

void oit_osmesa_destroy(oit_osmesa_context *context)
{
    if (!context)
        return;
    if (OSMesaGetCurrentContext() == context->context)
        OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(context->context);
    free(context);
}

oit_gl_proc oit_osmesa_get_proc_address(const char *name)
{
    return (oit_gl_proc)OSMesaGetProcAddress(name);
}
