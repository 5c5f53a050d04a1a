// epsilon_dispatch.comp: the work-group counts of the epsilon pass from the
// number of fragments neighbours.comp queued, for glDispatchComputeIndirect:
// dispatching one invocation per fragment instead, most of them only to find
// they have no item, costs more than the search itself on small scenes.
// Groups go in rows of at most OIT_IB_MAX_GROUPS_X (neighbours_epsilon.comp
// numbers its items row by row). Compute pass, one invocation.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(local_size_x = 1) in;

void main()
{
    uint items = ib_counters[OIT_IB_COUNTER_EPSILON_ITEMS];
    ib_write_dispatch((items + uint(OIT_IB_ITEMS_PER_GROUP) - 1u) / uint(OIT_IB_ITEMS_PER_GROUP),
                      OIT_IB_COUNTER_EPSILON_DISPATCH);
}
