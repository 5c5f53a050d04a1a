/* capabilities.h: what the algorithms' capability tables (oit_capabilities,
 * oit.h) share: the reasons most of them give, as designated initializers. */
#ifndef OIT_CAPABILITIES_H
#define OIT_CAPABILITIES_H

#include "oit.h"

/* The non-local modulations need each fragment's surface neighbours. */
#define OIT_NEEDS_NEIGHBOURS(why) "opacity modulation '%s' needs surface neighbours (ib only): " why
#define OIT_REFUSES_NEIGHBOUR_MODULATIONS(why)                                                            \
    [OIT_MODULATE_CURVATURE] = OIT_NEEDS_NEIGHBOURS(why), [OIT_MODULATE_DIST_CURV] = OIT_NEEDS_NEIGHBOURS(why), \
    [OIT_MODULATE_FIELDS] = OIT_NEEDS_NEIGHBOURS(why), [OIT_MODULATE_EDGES] = OIT_NEEDS_NEIGHBOURS(why)

/* The buffer views show per-pixel lists (ll) and the Illustration Buffer (ib). */
#define OIT_BUFFER_VIEWS_REASON "buffer views are ll's and ib's (view '%s')"
#define OIT_REFUSES_BUFFER_VIEWS                                                                          \
    [OIT_VIEW_HEATMAP] = OIT_BUFFER_VIEWS_REASON, [OIT_VIEW_PEEL_LIMIT] = OIT_BUFFER_VIEWS_REASON,            \
    [OIT_VIEW_LAYER] = OIT_BUFFER_VIEWS_REASON, [OIT_VIEW_NEIGHBOURS] = OIT_BUFFER_VIEWS_REASON,              \
    [OIT_VIEW_CURVATURE] = OIT_BUFFER_VIEWS_REASON, [OIT_VIEW_DISTANCE] = OIT_BUFFER_VIEWS_REASON,            \
    [OIT_VIEW_FIELDS] = OIT_BUFFER_VIEWS_REASON

/* The distances past the adjacent one need fragments further along the ray. */
#define OIT_ADJACENT_DISTANCE_ONLY(why)                                                                   \
    [OIT_DISTANCE_SKIP] = "only the adjacent distance: " why, [OIT_DISTANCE_FAR_END] = "only the adjacent distance: " why

#endif
