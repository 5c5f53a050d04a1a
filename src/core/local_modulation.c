/* local_modulation.c: the local opacity modulations (per-component opacity,
 * focus shapes, contrast) in C, for the reference renderer; the GLSL twin is
 * shaders/common/local_modulation.glsl. Definitions: docs/modulation.md. */
#include <math.h>
#include <string.h>

#include "oit.h"

float oit_local_focus_region(const oit_frame_settings *frame)
{
    if (frame->modulation.focus_region > 0.0f)
        return frame->modulation.focus_region;
    if (frame->local.focus_default_region > 0.0f)
        return frame->local.focus_default_region;
    return 1.0f;
}

/* General 4x4 inverse by cofactors, in double. */
bool oit_local_inverse_modelview(const float modelview[16], double out[16])
{
    double m[16];
    for (int i = 0; i < 16; ++i)
        m[i] = modelview[i];
    return oit_mat4_inverse_double(m, out);
}

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

static double focus_distance(const oit_local_modulation *local, const double p[3])
{
    const float *f = local->focus;
    switch (local->focus_shape) {
    case OIT_FOCUS_POINT: {
        double d[3] = {p[0] - f[0], p[1] - f[1], p[2] - f[2]};
        return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    case OIT_FOCUS_PLANE: {
        double length = sqrt((double)f[0] * f[0] + (double)f[1] * f[1] + (double)f[2] * f[2]);
        return length > 0.0 ? fabs(f[0] * p[0] + f[1] * p[1] + f[2] * p[2] + f[3]) / length : 0.0;
    }
    case OIT_FOCUS_BOX: {
        double sum = 0.0;
        for (int i = 0; i < 3; ++i) {
            double below = f[i] - p[i], above = p[i] - f[3 + i];
            double outside = below > above ? below : above;
            if (outside > 0.0)
                sum += outside * outside;
        }
        return sqrt(sum);
    }
    default: return 0.0;
    }
}

double oit_local_alpha(const oit_frame_settings *frame, double alpha, uint32_t component,
                       const double model_position[3])
{
    const oit_local_modulation *local = &frame->local;
    if (local->component_alpha && component < local->component_count)
        alpha *= local->component_alpha[component];
    if (local->focus_shape != OIT_FOCUS_NONE && alpha > 0.0) {
        double factor = focus_distance(local, model_position) / oit_local_focus_region(frame);
        alpha *= factor < 0.0 ? 0.0 : (factor > 1.0 ? 1.0 : factor);
    }
    return alpha;
}

void oit_local_contrast(const oit_frame_settings *frame, float rgb[3])
{
    float c = frame->local.contrast;
    if (c == 0.0f || c == 1.0f)
        return;
    for (int i = 0; i < 3; ++i) {
        float v = (rgb[i] - 0.5f) * c + 0.5f;
        rgb[i] = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
    }
}
