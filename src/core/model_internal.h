/* model_internal.h: what model.c shares with the files that finish a model. */
#ifndef OIT_MODEL_INTERNAL_H
#define OIT_MODEL_INTERNAL_H

#include "oit.h"

/* The coplanar planes (model_planes.c): fills planes, plane_count and
 * triangle_plane from the finished positions, bounds, radius and origin. */
oit_status oit_model_find_planes(oit_model *model, oit_error *err);

#endif
