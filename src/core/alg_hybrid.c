/*
 * alg_hybrid.c: hybrid transparency (Maule, Comba, Torchelsen & Bastos 2013,
 * "Hybrid transparency", I3D): every pixel keeps its k nearest fragments
 * exactly (closest_layers.c: select, store, compose) and accumulates the rest
 * as a tail.
 *
 * The tail: the fragments past a pixel's k nearest are accumulated
 * order-independently into float targets: sum(c a) and sum(a) by additive
 * blending, prod(1 - a) by multiplicative blending (ZERO, ONE_MINUS_SRC_COLOR),
 * as wboit does with weight 1. Compose resolves it as the average colour
 * sum(c a) / sum(a) covering 1 - prod(1 - a), behind the core. Its coverage is
 * exact, its colour an unweighted average: right where the tail is all one
 * colour. Exact when k >= every pixel's list length.
 */
#include "closest_layers.h"

static const closest_layers_tail hybrid_tail = {
    .algorithm = "hybrid",
    .store_shader = "hybrid/store.frag",
    .compose_shader = "hybrid/compose.frag",
    .target_count = 2,
    .targets = {{GL_RGBA32F, {0.0f, 0.0f, 0.0f, 0.0f}, GL_ONE, GL_ONE, OIT_TEXUNIT_CLOSEST_TAIL},
                {GL_R32F, {1.0f, 0.0f, 0.0f, 0.0f}, GL_ZERO, GL_ONE_MINUS_SRC_COLOR,
                 OIT_TEXUNIT_CLOSEST_TAIL_PRODUCT}},
};

static oit_status hybrid_create(const oit_algorithm_config *config, oit_algorithm **out,
                                oit_error *err)
{
    return closest_layers_create(&hybrid_tail, config, out, err);
}

const oit_algorithm_ops oit_algorithm_hybrid = {
    .name = "hybrid",
    .summary = "hybrid transparency (Maule et al. 2013): k nearest layers exact, tail averaged",
    .uses_gl = true,
    .exact = false,
    .capabilities = &closest_layers_capabilities,
    .create = hybrid_create,
    .resize = closest_layers_resize,
    .render = closest_layers_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = closest_layers_destroy,
};
