/*
 * gl_context_osmesa.h: the OSMesa back end of oit_gl_context (core-internal).
 *
 * Kept in its own translation unit because <GL/osmesa.h> (which pulls in
 * <GL/gl.h>) and <GL/glew.h> cannot be included together; this header
 * therefore includes no GL header at all.
 */
#ifndef OIT_GL_CONTEXT_OSMESA_H
#define OIT_GL_CONTEXT_OSMESA_H

#include "oit.h"

typedef struct oit_osmesa_context oit_osmesa_context;

typedef void (*oit_gl_proc)(void);

/* Create a core-profile context of at least major.minor on llvmpipe and make
 * it current on a small private colour buffer (all real rendering goes to FBOs). */
oit_status oit_osmesa_create(int major, int minor, oit_osmesa_context **out, oit_error *err);
void oit_osmesa_destroy(oit_osmesa_context *context);
/* OSMesaGetProcAddress: the only lookup that reaches OSMesa's dispatch. */
oit_gl_proc oit_osmesa_get_proc_address(const char *name);

#endif
