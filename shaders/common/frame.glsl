// frame.glsl: the frame's parameters every pass may use: one uniform block,
// uploaded once per frame (oit_gpu_frame_begin, gl_frame.c).
#include "common/oit_shared.h"
#include "common/variants.glsl"

// The frame's parameters, one std140 block at the byte offsets of oit_shared.h
// (OIT_FRAME_*), in that order; its members are read by these names.
layout(std140, binding = OIT_UBO_FRAME) uniform oit_frame_block {
    mat4 u_modelview;
    mat4 u_projection;
    mat4 u_plane_to_eye;             // common/canonical_depth.glsl
    mat4 u_local_inverse_modelview;  // common/local_modulation.glsl
    mat4 u_local_inverse_projection;
    mat3 u_normal_matrix;
    vec3 u_background;
    float u_alpha;                   // frame opacity multiplier
    vec4 u_local_focus_a;            // point xyz | plane abcd | box min
    vec4 u_local_focus_b;            // box max
    ivec2 u_viewport;                // width, height in pixels
    int u_shading;                   // OIT_SHADING_*
    int u_local_focus_shape;         // OIT_FOCUS_SHAPE_*
    float u_local_focus_region;
    float u_local_contrast;
    int u_distance_mode;             // -1: off
    int u_distance_skip;
    float u_distance_norm;
    int u_section_count;             // section planes (common/local_modulation.glsl)
    int u_section_all_parts;         // 1: they cut every part
    vec4 u_section_planes[OIT_SECTIONS_MAX]; // eye space: removed where dot(xyz, e) + w > 0
};
