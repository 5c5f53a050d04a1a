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
