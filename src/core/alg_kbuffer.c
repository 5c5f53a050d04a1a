/*
 * alg_kbuffer.c: the k-buffer (Bavoil, Callahan, Lefohn, Comba & Silva 2007),
 * as the two-pass "atomic loop" of NVIDIA's vk_order_independent_transparency:
 * every pixel keeps its k nearest fragments exactly (closest_layers.c: select,
 * store, compose) and blends the rest as a tail.
 *
 * The tail: the fragments past a pixel's k nearest are blended "over" in
 * submission order by the fixed-function blender into one float target
 * (premultiplied: ONE, ONE_MINUS_SRC_ALPHA, the later fragment in front), what
 * the NVIDIA sample calls tail blending. Order-dependent, like blend: right
 * where the tail happens to come back to front or is all one colour. Compose
 * puts it behind the core. Exact when k >= every pixel's list length.
 */
#include "closest_layers.h"

static const closest_layers_tail kbuffer_tail = {
    .algorithm = "kbuffer",
    .store_shader = "kbuffer/store.frag",
    .compose_shader = "kbuffer/compose.frag",
    .target_count = 1,
    .targets = {{GL_RGBA32F, {0.0f, 0.0f, 0.0f, 0.0f}, GL_ONE, GL_ONE_MINUS_SRC_ALPHA,
                 OIT_TEXUNIT_CLOSEST_TAIL}},
};

static oit_status kbuffer_create(const oit_algorithm_config *config, oit_algorithm **out,
                                 oit_error *err)
{
    return closest_layers_create(&kbuffer_tail, config, out, err);
}

const oit_algorithm_ops oit_algorithm_kbuffer = {
    .name = "kbuffer",
    .summary = "k-buffer (Bavoil et al. 2007), atomic loop: k nearest layers exact, tail blended in order",
    .uses_gl = true,
    .exact = false,
    .capabilities = &closest_layers_capabilities,
    .create = kbuffer_create,
    .resize = closest_layers_resize,
    .render = closest_layers_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = closest_layers_destroy,
};
