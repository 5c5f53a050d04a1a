/* sections.c: the section planes' rule for the shells (docs/sections.md).
 * The GPU passes have it in shaders/common/local_modulation.glsl, the
 * reference and the pick their own code (reference_raster.c, pick.c). */
#include <math.h>

#include "oit.h"
#include "oit_shared.h"
#include "sections.h"

_Static_assert(OIT_SECTION_PLANES_MAX == OIT_SECTIONS_MAX,
               "oit.h's OIT_SECTION_PLANES_MAX must equal oit_shared.h's OIT_SECTIONS_MAX");

bool oit_section_cuts_part(const oit_local_modulation *local, uint32_t component)
{
    if (!local->section_parts)
        return true;
    return component < local->section_parts_count && local->section_parts[component] != 0;
}

bool oit_section_removes(const oit_local_modulation *local, uint32_t component, const double p[3])
{
    if (!local || local->section_count == 0 || !oit_section_cuts_part(local, component))
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

oit_status oit_sections_check(const oit_local_modulation *local, oit_error *err)
{
    if (local->section_count > OIT_SECTION_PLANES_MAX)
        return oit_fail(err, OIT_E_INPUT, "%u section planes, at most %d", local->section_count,
                        OIT_SECTION_PLANES_MAX);
    for (uint32_t i = 0; i < local->section_count; ++i) {
        const double *s = local->sections[i];
        for (int k = 0; k < 4; ++k)
            if (!isfinite(s[k]))
                return oit_fail(err, OIT_E_INPUT, "section plane %u: %s is not finite", i + 1,
                                k < 3 ? "a normal component" : "its offset D");
        if (s[0] == 0.0 && s[1] == 0.0 && s[2] == 0.0)
            return oit_fail(err, OIT_E_INPUT, "section plane %u has a zero normal", i + 1);
    }
    return OIT_OK;
}

oit_status oit_section_eye_planes(const oit_frame_settings *relative, float planes[OIT_SECTION_PLANES_MAX][4],
                                  uint32_t *count, oit_error *err)
{
    *count = 0;
    const oit_local_modulation *local = &relative->local;
    if (local->section_count == 0)
        return OIT_OK;
    oit_status status = oit_sections_check(local, err);
    if (status != OIT_OK)
        return status;
    double inverse[16];
    if (!oit_mat4_inverse_double(relative->modelview, inverse))
        return oit_fail(err, OIT_E_INPUT, "the modelview is singular, so section planes (model "
                                          "coordinates) cannot be placed");
    for (uint32_t i = 0; i < local->section_count; ++i) {
        /* relative position p = M^-1 e (homogeneous): (n, -d) . p is a row
         * vector times M^-1 applied to (e, 1) */
        const double row[4] = {local->sections[i][0], local->sections[i][1], local->sections[i][2],
                               -local->sections[i][3]};
        for (int col = 0; col < 4; ++col) {
            double q = row[0] * inverse[col * 4] + row[1] * inverse[col * 4 + 1] +
                       row[2] * inverse[col * 4 + 2] + row[3] * inverse[col * 4 + 3];
            planes[i][col] = (float)q;
            if (!isfinite(planes[i][col]))
                return oit_fail(err, OIT_E_INPUT,
                                "section plane %u is too large for single precision in eye space", i + 1);
        }
    }
    *count = local->section_count;
    return OIT_OK;
}
