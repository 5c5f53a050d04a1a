/*
 * alg_adaptive.c: adaptive transparency (Salvi, Montgomery and Lefohn,
 * "Adaptive Transparency", HPG 2011), in the paper's own form: the fragments
 * are captured in per-pixel linked lists, and the resolve pass builds each
 * pixel's compressed visibility function from its list, then composites every
 * fragment with that function's value at its depth.
 *
 * Everything up to the resolve is ll's (linked_lists.h, alg_ll.c): the fill,
 * the fragment pool with its growth and bands, the sort (--sort merge, always)
 * and the statistics. Two differences, both in the member below: the sort
 * orders each list by triangle index (LL_ORDER_PRIMITIVE), the order the
 * draw call submits the fragments in, so the visibility function is built in
 * the same order whatever order the fill's atomics ran in (deterministic on
 * every GPU, and the order a rasterizer-ordered implementation would see);
 * and the resolve is shaders/adaptive/resolve.frag, compiled for k =
 * config.layers (--layers, default 8) nodes per pixel, held in the shader's
 * registers: no per-pixel memory beyond ll's.
 *
 * The resolve-time form, not mlab's spin lock: llvmpipe has no fragment
 * shader interlock, a spin lock makes the function depend on the order the
 * fragments won the lock in (arrival order), and the visibility function
 * needs every fragment's final visibility anyway, which the paper's one-pass
 * variant gets only by a second geometry pass. docs/algorithms.md, "adaptive".
 *
 * Exact where no list is longer than k (nothing is removed); past k, the
 * removed nodes move steps of the function forward in depth, which darkens
 * the fragments they pass over. The total transmittance is always exact.
 *
 * Memory: ll's (per pixel: the list head and the RGBA8 output, 8 bytes; per
 * fragment: OIT_LL_NODE_BYTES + two next pointers, 24 bytes), counted by the
 * tracker as ll's is.
 */
#include "capabilities.h"
#include "linked_lists.h"

static const linked_lists_resolve adaptive_resolve = {
    .algorithm = "adaptive",
    .resolve_shader = "adaptive/resolve.frag",
    .depth_order = false,
    .sort_option = false,
    .views = false,
    .layers = true,
};

static oit_status adaptive_create(const oit_algorithm_config *config, oit_algorithm **out,
                                  oit_error *err)
{
    return linked_lists_create(&adaptive_resolve, config, out, err);
}

static const oit_capabilities adaptive_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs each fragment's neighbour in depth, "
                                              "and the resolve walks the lists in primitive order",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("a pixel's list has no link to the adjacent pixels' lists")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_LAYERS | OIT_OPTION_FRAGMENT_POOL | OIT_OPTION_MAX_MEMORY,
};

const oit_algorithm_ops oit_algorithm_adaptive = {
    .name = "adaptive",
    .summary = "adaptive transparency (Salvi et al. 2011): ll's lists resolved through a k-node visibility "
               "function, approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &adaptive_capabilities,
    .create = adaptive_create,
    .resize = linked_lists_resize,
    .render = linked_lists_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = linked_lists_destroy,
};
