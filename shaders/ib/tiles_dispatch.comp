// tiles_dispatch.comp: the work-group counts of the passes over the tile list
// (ib/tiles.glsl) from the number of tiles sort.comp appended, for
// glDispatchComputeIndirect, as epsilon_dispatch.comp does for its items:
// groups in rows of at most OIT_IB_MAX_GROUPS_X. Compute pass, one invocation.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(local_size_x = 1) in;

void main()
{
    ib_write_dispatch(ib_counters[OIT_IB_COUNTER_TILES], OIT_IB_COUNTER_TILE_DISPATCH);
}
