/* capabilities.c: the one check of a frame against what its algorithm renders
 * (oit_capabilities on the operations table), and the names of the render
 * options. A capability is checked here, once, never in an algorithm. */
#include <string.h>

#include "oit.h"

const char *oit_option_flags(unsigned option)
{
    switch (option) {
    case OIT_OPTION_SORT: return "--sort";
    case OIT_OPTION_MAX_LAYERS: return "--max-layers";
    case OIT_OPTION_LAYERS: return "--layers";
    case OIT_OPTION_MOMENTS: return "--moments";
    case OIT_OPTION_FRAGMENT_POOL: return "--fragment-pool --fragment-counter-start --buffer-fragment-limit";
    case OIT_OPTION_MAX_MEMORY: return "--max-memory";
    case OIT_OPTION_LOCKS_HELD: return "--locks-held";
    case OIT_OPTION_WAVELET_RANK: return "--wavelet-rank";
    case OIT_OPTION_SEED: return "--seed --stochastic-masks";
    case OIT_OPTION_SAMPLES: return "--samples";
    default: return NULL;
    }
}

bool oit_algorithm_reads(const oit_algorithm_ops *ops, unsigned option)
{
    return ops && ops->capabilities && (ops->capabilities->options & option) == option;
}

/* "NAME: reason", the reason's "%s" replaced by the value's name. */
static oit_status refuse(oit_error *err, const char *algorithm, const char *reason, const char *value)
{
    const char *slot = strstr(reason, "%s");
    if (!slot)
        return oit_fail(err, OIT_E_INPUT, "%s: %s", algorithm, reason);
    return oit_fail(err, OIT_E_INPUT, "%s: %.*s%s%s", algorithm, (int)(slot - reason), reason, value, slot + 2);
}

oit_status oit_frame_check(const oit_algorithm_ops *ops, const oit_frame_settings *frame, oit_error *err)
{
    const oit_capabilities *can = ops->capabilities;
    const oit_modulation *m = &frame->modulation;
    if (frame->samples != 0 && oit_sample_positions(frame->samples, NULL) == 0)
        return oit_fail(err, OIT_E_INPUT, "%s: frame.samples %d is not 1, 4, 8 or 16 (0: 1)", ops->name,
                        frame->samples);
    if ((int)m->mode < 0 || (int)m->mode >= OIT_MODULATION_COUNT)
        return oit_fail(err, OIT_E_INPUT, "%s: unknown modulation %d", ops->name, (int)m->mode);
    if (can->modulations[m->mode])
        return refuse(err, ops->name, can->modulations[m->mode], oit_setting_word(OIT_SETTING_MODULATION, m->mode));
    if (m->mode == OIT_MODULATE_DISTANCE || m->mode == OIT_MODULATE_DIST_CURV) {
        if ((int)m->distance < 0 || (int)m->distance >= OIT_DISTANCE_COUNT)
            return oit_fail(err, OIT_E_INPUT, "%s: unknown distance mode %d", ops->name, (int)m->distance);
        if (can->distances[m->distance])
            return refuse(err, ops->name, can->distances[m->distance], oit_setting_word(OIT_SETTING_DISTANCE, m->distance));
    }
    if ((int)m->view < 0 || (int)m->view >= OIT_VIEW_COUNT)
        return oit_fail(err, OIT_E_INPUT, "%s: unknown view %d", ops->name, (int)m->view);
    if (can->views[m->view])
        return refuse(err, ops->name, can->views[m->view], oit_setting_word(OIT_SETTING_VIEW, m->view));
    return OIT_OK;
}

/* The standard multisample positions, in 1/16 pixel from the pixel centre,
 * x right and y down: Direct3D 11's D3D11_STANDARD_MULTISAMPLE_PATTERN
 * (D3D11_STANDARD_MULTISAMPLE_QUALITY_LEVELS, "Standard sample patterns"),
 * which Vulkan's standard sample locations repeat (the specification's
 * table "Standard sample locations", given there in [0, 1) from the pixel's
 * corner: 0.5 + offset / 16). */
static const signed char positions_1[] = {0, 0};
static const signed char positions_4[] = {-2, -6, 6, -2, -6, 2, 2, 6};
static const signed char positions_8[] = {1, -3, -1, 3, 5, 1, -3, -5, -5, 5, -7, -1, 3, 7, 7, -7};
static const signed char positions_16[] = {1,  1,  -1, -3, -3, 2,  4,  -1, -5, -2, 2,  5,  5,  3,  3,  -5,
                                           -2, 6,  0,  -7, -4, -6, -6, 4,  -8, 0,  7,  -4, 6,  7,  -7, -8};

int oit_sample_positions(int samples, const signed char **offsets)
{
    const signed char *table = NULL;
    switch (samples) {
    case 0:
    case 1: table = positions_1; samples = 1; break;
    case 4: table = positions_4; break;
    case 8: table = positions_8; break;
    case 16: table = positions_16; break;
    default: return 0;
    }
    if (offsets)
        *offsets = table;
    return samples;
}

const char *oit_sample_positions_name(int samples)
{
    switch (samples) {
    case 0:
    case 1: return "centre";
    case 4: return "d3d11-standard-4";
    case 8: return "d3d11-standard-8";
    case 16: return "d3d11-standard-16";
    default: return "unknown";
    }
}
