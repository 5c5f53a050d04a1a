/*
 * linked_lists.h: ll's per-pixel linked lists as a family (core-internal): the
 * fill, the fragment pool with its growth and bands, the sort and the
 * statistics of alg_ll.c, with the last full-screen pass (the resolve) and the
 * order the sort puts each list in described by the member. ll composites the
 * depth-sorted lists (ll/compose.frag); adaptive (alg_adaptive.c) sorts them
 * into primitive order and resolves them through a k-node visibility function.
 */
#ifndef OIT_LINKED_LISTS_H
#define OIT_LINKED_LISTS_H

#include "gpu_algorithm.h"

typedef struct linked_lists_resolve {
    const char *algorithm;      /* "ll": names the algorithm in messages and the pool */
    const char *resolve_shader; /* the last full-screen pass ("ll/compose.frag") */
    /* the sort: true = by (depth, triangle), front to back (ll); false = by
     * (triangle, depth), the order the draw call submits the fragments in
     * (LL_ORDER_PRIMITIVE in ll_nodes.glsl) */
    bool depth_order;
    /* true: config.ll_sort picks the sort (ll); false: always OIT_LL_SORT_MERGE */
    bool sort_option;
    /* true: the resolve takes ll's views and the distance modulation (uniforms
     * OIT_UNIFORM_LL_*); false: it shows the colour image only */
    bool views;
    /* true: the resolve is compiled with "#define LL_RESOLVE_LAYERS k" (config.layers) */
    bool layers;
} linked_lists_resolve;

/* create takes the member (a static description, kept by pointer); the others are the ops. */
oit_status linked_lists_create(const linked_lists_resolve *resolve, const oit_algorithm_config *config,
                               oit_algorithm **out, oit_error *err);
oit_status linked_lists_resize(oit_algorithm *alg, int width, int height, oit_error *err);
oit_status linked_lists_render(oit_algorithm *alg, const oit_scene *scene,
                               const oit_frame_settings *frame, oit_error *err);
void linked_lists_destroy(oit_algorithm *alg);

#endif
