/*
 * absorbance_passes.h: two additive passes over the absorbance and a resolve,
 * the machinery mboit and wavelet share (core-internal). Both sum, in any
 * order, every fragment's optical depth into b0 and a projection of its step
 * over depth into a few float targets (moments; Haar coefficients); then every
 * fragment reconstructs the transmittance in front of it from those sums and
 * adds (T a c, T a); mboit/compose.frag normalises over the background. They
 * differ only in the projection: its shaders, its targets and where the second
 * pass reads them. absorbance_passes.c runs the passes; alg_mboit.c and
 * alg_wavelet.c describe their projections.
 */
#ifndef OIT_ABSORBANCE_PASSES_H
#define OIT_ABSORBANCE_PASSES_H

#include "gpu_algorithm.h"

/* the projection's targets after b0: wavelet's rank 3 has the most (16 coefficients, 4 RGBA32F) */
#define ABSORBANCE_PROJECTION_TARGETS_MAX 4

/* What an algorithm of the family projects the absorbance onto. Resolved at
 * create from the configuration (the variant, the rank) and copied. */
typedef struct absorbance_projection {
    const char *algorithm;              /* "mboit": names the algorithm in messages */
    const char *stage;                  /* the first pass's stage and framebuffer name: "moments" */
    const char *projection_shader;      /* the first pass: b0 and the projection */
    const char *transmittance_shader;   /* the second pass: (T a c, T a) */
    char defines[64];                   /* both shaders' variant: "#define MBOIT_VARIANT 1\n" */
    int target_count;                   /* targets after b0 (attachments 1..target_count) */
    GLenum target_formats[ABSORBANCE_PROJECTION_TARGETS_MAX];
    GLenum target_units[ABSORBANCE_PROJECTION_TARGETS_MAX]; /* where the second pass reads each */
    bool transmittance_reads_b0;        /* the second pass reads b0 at OIT_TEXUNIT_MBOIT_B0 too */
} absorbance_projection;

/* The oit_algorithm_ops of the family: create takes the projection (copied);
 * the others are the ops themselves. */
oit_status absorbance_passes_create(const absorbance_projection *projection, const oit_algorithm_config *config,
                                    oit_algorithm **out, oit_error *err);
oit_status absorbance_passes_resize(oit_algorithm *alg, int width, int height, oit_error *err);
oit_status absorbance_passes_render(oit_algorithm *alg, const oit_scene *scene, const oit_frame_settings *frame,
                                    oit_error *err);
void absorbance_passes_destroy(oit_algorithm *alg);

#endif
