// shade.glsl: the per-fragment shading, the GLSL twin of oit_shade() in
// src/core/matrix.c. Include it in fragment shaders fed by geometry.vert.
#include "common/frame.glsl"
#include "common/local_modulation.glsl"

in vec3 v_eye_position;
in vec3 v_eye_normal;
flat in uint v_component;
flat in uint v_section_cap; // 0, or 1 + the section whose cap the fragment is

// vec4 per component: rgb material colour, a material opacity
layout(std430, binding = OIT_SSBO_COMPONENTS) readonly buffer oit_component_table {
    vec4 oit_components[];
};

vec3 oit_shade_rgb(vec3 colour, vec3 eye_normal, vec3 eye_position)
{
    float factor = 1.0;
    if (u_shading == OIT_SHADING_HEADLIGHT) {
        float n_length = length(eye_normal);
        float v_length = length(eye_position);
        if (n_length > 0.0) {
            vec3 v = v_length > 0.0 ? -eye_position / v_length : vec3(0.0, 0.0, 1.0);
            float n_dot_v = dot(eye_normal, v) / n_length;
            const float ambient = float(OIT_HEADLIGHT_AMBIENT_PERCENT) / 100.0;
            // two-sided: through transparent surfaces back faces are seen
            factor = ambient + (1.0 - ambient) * abs(n_dot_v);
        }
    }
    return oit_local_contrast(colour * factor);
}

// The current fragment's opacity, local modulation applied (per-component
// opacity, focus shapes, section planes: common/local_modulation.glsl); passes that only ask
// whether a fragment is stored need no more (0: hidden, never a layer).
float oit_fragment_alpha()
{
    return oit_local_alpha(clamp(u_alpha * oit_components[v_component].a, 0.0, 1.0), v_component,
                           v_section_cap, v_eye_position);
}

// The shaded colour and opacity of the current fragment (highlight and contrast too).
vec4 oit_shade_fragment()
{
    return vec4(oit_shade_rgb(oit_local_tint(oit_components[v_component].rgb, v_component), v_eye_normal,
                              v_eye_position),
                oit_fragment_alpha());
}
