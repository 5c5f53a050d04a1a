// frame.glsl: the per-frame uniforms every pass may use, at the locations of
// oit_shared.h. oit_gl_set_frame_uniforms() (gl_util.c) sets them by these names.
#include "common/oit_shared.h"
#include "common/variants.glsl"

layout(location = OIT_UNIFORM_MODELVIEW) uniform mat4 u_modelview;
layout(location = OIT_UNIFORM_PROJECTION) uniform mat4 u_projection;
layout(location = OIT_UNIFORM_NORMAL_MATRIX) uniform mat3 u_normal_matrix;
layout(location = OIT_UNIFORM_ALPHA) uniform float u_alpha;     // frame opacity multiplier
layout(location = OIT_UNIFORM_SHADING) uniform int u_shading;   // OIT_SHADING_*
layout(location = OIT_UNIFORM_BACKGROUND) uniform vec3 u_background;
layout(location = OIT_UNIFORM_VIEWPORT) uniform ivec2 u_viewport; // width, height in pixels
