/*
 * alg_mboit.c: moment-based order-independent transparency (Muenstermann,
 * Krumpen, Klein & Peters, "Moment-Based Order-Independent Transparency",
 * Proc. ACM CGIT 1(1), i3D 2018). Approximate, two additive geometry passes
 * and a resolve, constant memory per pixel.
 *
 * The transmittance in front of a fragment, prod (1 - a) over the fragments
 * in front, is the exponential of minus the absorbance, a sum of optical
 * depths -ln(1 - a): additive, so the moments of its distribution over depth
 * can be summed in any order. config.moments picks which moments
 * (shaders/mboit/common.glsl has the equations, E1..E5):
 *   power4 (the default): b0 and 4 power moments of the depth warped to [-1, 1]
 *   power6: b0 and 6 power moments
 *   trig3:  b0 and 3 trigonometric (complex) moments of the depth as a phase
 * 1. "moments": depth test off, additive blending; every fragment adds its
 *    optical depth (opacity clamped below 1) into b0 (R32F) and that times its
 *    moment vector into an RGBA32F target (moments 1..4) and, for power6 and
 *    trig3, an RG32F one (moments 5, 6 / the third complex moment).
 * 2. "transmittance": depth test off, additive blending; every fragment
 *    reconstructs T, the transmittance in front of its depth, from its pixel's
 *    moments (the bounds of the Hamburger problem for power moments, of the
 *    trigonometric problem for trig3, biased and interpolated between the
 *    bounds by the overestimation, as the paper) and adds (T a c, T a) into an
 *    RGBA32F target.
 * 3. "compose": C = (sum T a c) / (sum T a) * (1 - exp(-b0)) + background *
 *    exp(-b0), the paper's normalisation: the coverage 1 - exp(-b0) is exact.
 * Memory per pixel: power4 4 + 16 + 16 + 4 (output) = 40 bytes; power6 and
 * trig3 8 more (the RG32F target): 48.
 * The passes are absorbance_passes.c's, shared with wavelet; this file says
 * which moments, in which targets.
 */
#include <stdio.h>

#include "absorbance_passes.h"
#include "capabilities.h"
#include "oit_shared.h"

_Static_assert(OIT_MBOIT_TARGET_EXTRA == OIT_MBOIT_TARGET_MOMENTS + 1, "the extra target follows the moments");

static oit_status mboit_create(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err)
{
    /* checked: oit_algorithm_create */
    oit_moments moments = config->moments == OIT_MOMENTS_DEFAULT ? OIT_MOMENTS_POWER4 : config->moments;
    /* the moments other than power4 need the third target (moments 5, 6 / the third complex moment) */
    const bool extra = moments != OIT_MOMENTS_POWER4;
    absorbance_projection projection = {
        .algorithm = "mboit",
        .stage = "moments",
        .projection_shader = "mboit/moments.frag",
        .transmittance_shader = "mboit/transmittance.frag",
        .target_count = extra ? 2 : 1,
        .target_formats = {GL_RGBA32F, GL_RG32F},
        .target_units = {OIT_TEXUNIT_MBOIT_MOMENTS, OIT_TEXUNIT_MBOIT_EXTRA},
        .transmittance_reads_b0 = true,
    };
    /* the shaders' variant: OIT_MBOIT_POWER4, _POWER6 or _TRIG3 (oit_shared.h) */
    const int variant = moments == OIT_MOMENTS_POWER4   ? OIT_MBOIT_POWER4
                        : moments == OIT_MOMENTS_POWER6 ? OIT_MBOIT_POWER6
                                                        : OIT_MBOIT_TRIG3;
    snprintf(projection.defines, sizeof projection.defines, "#define MBOIT_VARIANT %d\n", variant);
    return absorbance_passes_create(&projection, config, out, err);
}

static const oit_capabilities mboit_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "moment-based OIT keeps only moments of the depths, not the fragments",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("moment-based OIT keeps no fragment, so no pixel sees its "
                                                      "neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_MOMENTS,
};

const oit_algorithm_ops oit_algorithm_mboit = {
    .name = "mboit",
    .summary = "moment-based OIT (Muenstermann et al. 2018): two additive passes, approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &mboit_capabilities,
    .create = mboit_create,
    .resize = absorbance_passes_resize,
    .render = absorbance_passes_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = absorbance_passes_destroy,
};
