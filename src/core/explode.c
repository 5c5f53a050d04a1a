/* explode.c: the exploded view's offsets (docs/sections.md, "Exploded view").
 * The rule is oit.h's, at oit_explode_offsets. */
#include <math.h>
#include <string.h>

#include "oit.h"

oit_status oit_explode_offsets(const oit_model *model, double factor, float *offsets, oit_error *err)
{
    if (!isfinite(factor) || factor < 0.0 || factor > OIT_EXPLODE_MAX)
        return oit_fail(err, OIT_E_INPUT, "explode factor %g is outside 0..%g", factor,
                        OIT_EXPLODE_MAX);
    memset(offsets, 0, (size_t)model->component_count * 3 * sizeof offsets[0]);
    /* TODO(issue 28, explode): the rule */
    return OIT_OK;
}
