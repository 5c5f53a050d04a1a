/* local_modulation.c: what the GPU set-up needs on the CPU for the local
 * modulations (docs/modulation.md): the focus shapes' fall-off length and
 * the inverse matrices the uniforms carry. The reference renderer has its
 * own code for all of it (alg_reference.c), so the oracle shares nothing it
 * checks; the per-fragment formulas live in shaders/common/local_modulation.glsl. */
#include <math.h>
#include <string.h>

#include "oit.h"
#include "oit_shared.h"

float oit_local_focus_region(const oit_frame_settings *frame)
{
    if (frame->modulation.focus_region > 0.0f)
        return frame->modulation.focus_region;
    if (frame->local.focus_default_region > 0.0f)
        return frame->local.focus_default_region;
    return 1.0f;
}

float oit_local_highlight(const oit_local_modulation *local, uint32_t component, float rgb[3])
{
    if (local->has_highlight_colour) {
        for (int c = 0; c < 3; ++c)
            rgb[c] = local->highlight_colour[c];
    } else {
        rgb[0] = OIT_HIGHLIGHT_COLOUR_R_PERCENT / 100.0f;
        rgb[1] = OIT_HIGHLIGHT_COLOUR_G_PERCENT / 100.0f;
        rgb[2] = OIT_HIGHLIGHT_COLOUR_B_PERCENT / 100.0f;
    }
    if (!local->component_highlight || component >= local->component_highlight_count)
        return 0.0f;
    float strength = local->highlight_strength > 0.0f ? local->highlight_strength
                                                      : OIT_HIGHLIGHT_STRENGTH_PERCENT / 100.0f;
    float weight = strength * local->component_highlight[component];
    /* NaN and out-of-range weights clamp: the tint never leaves [rgb, colour] */
    return weight > 0.0f ? (weight < 1.0f ? weight : 1.0f) : 0.0f;
}

/* General 4x4 inverse by cofactors, in double. */
bool oit_mat4_inverse_double(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] +
             m[9] * m[7] * m[14] + m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] -
             m[8] * m[7] * m[14] - m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] +
             m[8] * m[7] * m[13] + m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] -
              m[8] * m[6] * m[13] - m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] -
             m[9] * m[3] * m[14] - m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] +
             m[8] * m[3] * m[14] + m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] -
             m[8] * m[3] * m[13] - m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] +
              m[8] * m[2] * m[13] + m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] +
             m[5] * m[3] * m[14] + m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] -
             m[4] * m[3] * m[14] - m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] +
              m[4] * m[3] * m[13] + m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] -
              m[4] * m[2] * m[13] - m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] -
             m[5] * m[3] * m[10] - m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] +
             m[4] * m[3] * m[10] + m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] -
              m[4] * m[3] * m[9] - m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] +
              m[4] * m[2] * m[9] + m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabs(det) > 0.0) || !isfinite(det)) {
        memset(out, 0, 16 * sizeof out[0]);
        return false;
    }
    for (int i = 0; i < 16; ++i)
        out[i] = inv[i] / det;
    return true;
}

