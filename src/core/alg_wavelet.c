/*
 * alg_wavelet.c: wavelet transparency (Aizenshtein, Smal & McGuire, "Wavelet
 * Transparency", 2022). Approximate, two additive geometry passes and a
 * resolve, constant memory per pixel: mboit's shape with another basis.
 *
 * The absorbance in front of a depth, A(z) = sum over the fragments in front
 * of -ln(1 - a), is a sum of steps, one per fragment; its projection onto a
 * Haar basis of rank R (config.wavelet_rank, --wavelet-rank; N = 2^(R+1)
 * coefficients: the scaling function and the wavelets of levels 0..R) is
 * linear in it, so every fragment adds its own step's coefficients, in any
 * order (shaders/wavelet/common.glsl has the equations, W1..W5).
 * 1. "coefficients": depth test off, additive blending; every fragment adds its
 *    optical depth (opacity clamped below 1, common/optical_depth.glsl, shared
 *    with mboit) into b0 (R32F) and its step's N coefficients into N / 4
 *    RGBA32F targets (the depth: the canonical depth in [0, 1], mboit's).
 * 2. "transmittance": depth test off, additive blending; every fragment reads
 *    its pixel's coefficients, subtracts its own step's (a fragment is not in
 *    front of itself; a public implementation of the method, Flywheel's GLSL,
 *    removes the fragment's own signal the same way), reconstructs the absorbance in front of its depth
 *    (the projection's bin means, interpolated from the previous bin's at the
 *    start of its bin to its own bin's at the end) and adds (T a c, T a) into
 *    an RGBA32F target.
 * 3. "compose": mboit's (mboit/compose.frag, the same program source): C =
 *    (sum T a c) / (sum T a) * (1 - exp(-b0)) + background * exp(-b0).
 * Memory per pixel: 4 (b0) + 4 N (coefficients) + 16 (accumulation) + 4
 * (output) = 24 + 2^(R+3) bytes: rank 1 40, rank 2 56, rank 3 (the default) 88.
 * The passes are absorbance_passes.c's, shared with mboit; this file says
 * which coefficients, in which targets.
 */
#include <stdio.h>

#include "absorbance_passes.h"
#include "capabilities.h"
#include "oit_shared.h"

_Static_assert(OIT_WAVELET_RANK_MAX == 3, "oit.h's OIT_WAVELET_RANK_MAX and oit_shared.h's differ");
_Static_assert(OIT_WAVELET_RANK_DEFAULT >= 1 && OIT_WAVELET_RANK_DEFAULT <= OIT_WAVELET_RANK_MAX,
               "the default rank is outside 1..OIT_WAVELET_RANK_MAX");
_Static_assert((2 << OIT_WAVELET_RANK_MAX) / 4 <= ABSORBANCE_PROJECTION_TARGETS_MAX,
               "the highest rank's coefficient targets do not fit absorbance_passes.h");

static oit_status wavelet_create(const oit_algorithm_config *config, oit_algorithm **out, oit_error *err)
{
    /* checked: oit_algorithm_create */
    int rank = config->wavelet_rank == 0 ? OIT_WAVELET_RANK_DEFAULT : config->wavelet_rank;
    absorbance_projection projection = {
        .algorithm = "wavelet",
        .stage = "coefficients",
        .projection_shader = "wavelet/coefficients.frag",
        .transmittance_shader = "wavelet/transmittance.frag",
        .target_count = (2 << rank) / 4, /* 2^(rank+1) coefficients, four to an RGBA32F target */
    };
    for (int t = 0; t < projection.target_count; ++t) {
        projection.target_formats[t] = GL_RGBA32F;
        projection.target_units[t] = OIT_TEXUNIT_WAVELET_COEFFICIENTS + (GLenum)t;
    }
    snprintf(projection.defines, sizeof projection.defines, "#define WAVELET_RANK %d\n", rank);
    return absorbance_passes_create(&projection, config, out, err);
}

static const oit_capabilities wavelet_capabilities = {
    .modulations = {[OIT_MODULATE_DISTANCE] = "the distance modulation needs the next fragment along the ray, and "
                                              "wavelet transparency keeps only Haar coefficients of the absorbance, "
                                              "not the fragments",
                    OIT_REFUSES_NEIGHBOUR_MODULATIONS("wavelet transparency keeps no fragment, so no pixel sees its "
                                                      "neighbours' fragments")},
    .views = {OIT_REFUSES_BUFFER_VIEWS},
    .options = OIT_OPTION_WAVELET_RANK,
};

const oit_algorithm_ops oit_algorithm_wavelet = {
    .name = "wavelet",
    .summary = "wavelet transparency (Aizenshtein et al. 2022): Haar-projected absorbance, two additive passes, "
               "approximate",
    .uses_gl = true,
    .exact = false,
    .capabilities = &wavelet_capabilities,
    .create = wavelet_create,
    .resize = absorbance_passes_resize,
    .render = absorbance_passes_render,
    .read_image = oit_gpu_read_image,
    .stats = oit_gpu_stats,
    .accumulate = oit_gpu_accumulate,
    .destroy = absorbance_passes_destroy,
};
