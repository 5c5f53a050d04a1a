// geometry.vert: the vertex shader of every geometry pass.
// Eye-space position and normal are interpolated perspective-correctly; the
// normal is not normalized here (shade.glsl does it per fragment).
#include "common/frame.glsl"

layout(location = OIT_ATTRIB_POSITION) in vec3 a_position;
layout(location = OIT_ATTRIB_NORMAL) in vec3 a_normal;
layout(location = OIT_ATTRIB_COMPONENT) in uint a_component;

out vec3 v_eye_position;
out vec3 v_eye_normal;
flat out uint v_component;
flat out uint v_section_cap; // 0, or 1 + the section whose cap this is

// The component attribute's high bits: 1 + the section of a cap (oit_shared.h)
const uint OIT_COMPONENT_MASK = (1u << OIT_COMPONENT_CAP_SHIFT) - 1u;

// Multi-pass algorithms compare depths across passes: they must be bit-identical.
invariant gl_Position;

void main()
{
    vec4 eye_position = u_modelview * vec4(a_position, 1.0);
    v_eye_position = eye_position.xyz;
    v_eye_normal = u_normal_matrix * a_normal;
    v_component = a_component & OIT_COMPONENT_MASK;
    v_section_cap = a_component >> OIT_COMPONENT_CAP_SHIFT;
    gl_Position = u_projection * eye_position;
}
