/*
 * closest_layers.h: the k closest layers of every pixel, the machinery kbuffer
 * and hybrid share (core-internal). They differ only in the tail: what happens
 * to the fragments behind a pixel's k nearest. closest_layers.c describes the
 * passes; alg_kbuffer.c and alg_hybrid.c describe their tails.
 */
#ifndef OIT_CLOSEST_LAYERS_H
#define OIT_CLOSEST_LAYERS_H

#include "gpu_algorithm.h"

#define CLOSEST_LAYERS_MAX_TAIL_TARGETS 2

/* One float target the store pass blends the tail fragments into. */
typedef struct closest_layers_tail_target {
    GLenum format;      /* sized internal format (GL_RGBA32F, GL_R32F) */
    GLfloat clear[4];   /* its value before the store pass */
    GLenum source, destination; /* glBlendFunci factors (the equation is GL_FUNC_ADD) */
    GLenum texture_unit; /* where compose reads it (OIT_TEXUNIT_CLOSEST_TAIL...) */
} closest_layers_tail_target;

/* What an algorithm of the family does with its tail. */
typedef struct closest_layers_tail {
    const char *algorithm;      /* "kbuffer": names the algorithm in messages */
    const char *store_shader;   /* the store pass's fragment shader: slot or tail output */
    const char *compose_shader; /* compose: defines closest_layers_tail() */
    int target_count;
    closest_layers_tail_target targets[CLOSEST_LAYERS_MAX_TAIL_TARGETS];
} closest_layers_tail;

/* What the family renders: the same for every tail. */
extern const oit_capabilities closest_layers_capabilities;

/* The oit_algorithm_ops of the family: create takes the tail (a static
 * description, kept by pointer); the others are the ops themselves. */
oit_status closest_layers_create(const closest_layers_tail *tail, const oit_algorithm_config *config,
                                 oit_algorithm **out, oit_error *err);
oit_status closest_layers_resize(oit_algorithm *alg, int width, int height, oit_error *err);
oit_status closest_layers_render(oit_algorithm *alg, const oit_scene *scene,
                                 const oit_frame_settings *frame, oit_error *err);
void closest_layers_destroy(oit_algorithm *alg);

#endif
