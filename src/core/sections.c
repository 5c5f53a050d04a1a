/* sections.c: the section planes' rule for the shells (docs/sections.md).
 * The GPU passes have it in shaders/common/local_modulation.glsl, the
 * reference and the pick their own code (reference_raster.c, pick.c). */
#include "oit.h"
#include "oit_shared.h"

_Static_assert(OIT_SECTION_PLANES_MAX == OIT_SECTIONS_MAX,
               "oit.h's OIT_SECTION_PLANES_MAX must equal oit_shared.h's OIT_SECTIONS_MAX");

static bool part_is_cut(const oit_local_modulation *local, uint32_t component)
{
    if (!local->section_parts)
        return true;
    return component < local->section_parts_count && local->section_parts[component] != 0;
}

bool oit_section_removes(const oit_local_modulation *local, uint32_t component, const double p[3])
{
    if (!local || local->section_count == 0 || !part_is_cut(local, component))
        return false;
    uint32_t count = local->section_count < OIT_SECTION_PLANES_MAX ? local->section_count
                                                                   : OIT_SECTION_PLANES_MAX;
    for (uint32_t i = 0; i < count; ++i) {
        const double *s = local->sections[i];
        if (s[0] * p[0] + s[1] * p[1] + s[2] * p[2] > s[3])
            return true;
    }
    return false;
}
