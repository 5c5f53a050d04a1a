// local_modulation.glsl: the local opacity modulations every algorithm applies
// per fragment (docs/modulation.md), the GLSL twin of src/core/local_modulation.c.
// Its parameters are the frame block's (common/frame.glsl); the per-part
// opacity is a buffer texture, filled by oit_gl_bind_part_alpha().
//   alpha' = alpha * component_alpha[component] * saturate(d / focus_region)
// with d the distance, in model coordinates, to the focus point, to the focus
// plane, or to the focus box (0 inside it). alpha' == 0: the fragment is never stored.
// Section planes (docs/sections.md): alpha' = 0 where a plane removes the
// fragment (dot(q.xyz, eye) + q.w > 0 for an eye-space plane q of a part it
// cuts), except a cap on its own plane.
//   material rgb' = mix(rgb, highlight rgb, highlight weight[component])  (0: unchanged)
//   rgb' = saturate((rgb - 0.5) * contrast + 0.5)  (contrast 0 or 1: unchanged)
#ifndef OIT_LOCAL_MODULATION_GLSL
#define OIT_LOCAL_MODULATION_GLSL
#include "common/frame.glsl"

// Per-part opacity: one float per part of the model, every part (1 where the
// frame sets none; no limit on the number of parts). The one place the GLSL
// side reads oit_local_modulation.component_alpha.
layout(binding = OIT_TEXUNIT_LOCAL_PART_ALPHA) uniform samplerBuffer u_local_part_alpha;
// Selection highlight: per part (highlight rgb, weight), weight 0 for a part
// not highlighted (oit_local_modulation.component_highlight).
layout(binding = OIT_TEXUNIT_LOCAL_PART_TINT) uniform samplerBuffer u_local_part_tint;
// Which parts the section planes cut (1), read only when u_section_all_parts
// is 0 (oit_local_modulation.section_parts); parts past its end are not cut.
layout(binding = OIT_TEXUNIT_LOCAL_PART_SECTION) uniform usamplerBuffer u_local_part_section;


// The pixel's ray in eye space: its points at NDC depth -1 and +1, where the
// canonical depth (common/canonical_depth.glsl) is 0 and 1.
void oit_pixel_ray(vec2 pixel_centre, out vec3 near_point, out vec3 far_point)
{
    precise vec2 ndc = pixel_centre * (2.0 / vec2(u_viewport)) - 1.0;
    precise vec4 near_h = u_local_inverse_projection * vec4(ndc, -1.0, 1.0);
    precise vec4 far_h = u_local_inverse_projection * vec4(ndc, 1.0, 1.0);
    near_point = near_h.xyz / near_h.w;
    far_point = far_h.xyz / far_h.w;
}

// Linear eye depth (in front of the eye, along -z) of canonical depth s at a
// pixel centre (as ib_eye_depth).
float oit_eye_depth(vec2 pixel_centre, float s)
{
    vec3 near_point, far_point;
    oit_pixel_ray(pixel_centre, near_point, far_point);
    return -(near_point.z + s * (far_point.z - near_point.z));
}

// The distance modulation's opacity: saturate(distance / norm).
float oit_distance_alpha(float distance)
{
    return clamp(distance / u_distance_norm, 0.0, 1.0);
}

// The distance from model position p to the focus shape.
float oit_focus_distance(vec3 p)
{
    if (u_local_focus_shape == OIT_FOCUS_SHAPE_POINT)
        return length(p - u_local_focus_a.xyz);
    if (u_local_focus_shape == OIT_FOCUS_SHAPE_PLANE)
        return abs(dot(u_local_focus_a.xyz, p) + u_local_focus_a.w) / length(u_local_focus_a.xyz);
    vec3 outside = max(max(u_local_focus_a.xyz - p, p - u_local_focus_b.xyz), vec3(0.0));
    return length(outside);
}

// Whether a section plane removes the fragment of part component at
// eye_position (eye space). section_cap is 0, or 1 + the section whose cap the
// fragment is: a cap lies on its own plane, so that plane keeps it (the other
// planes cut it as any surface). The reference's twin: reference_raster.c,
// section_removes.
bool oit_section_removed(uint component, uint section_cap, vec3 eye_position)
{
    if (u_section_count == 0)
        return false;
    if (u_section_all_parts == 0 &&
        (component >= uint(textureSize(u_local_part_section)) ||
         texelFetch(u_local_part_section, int(component)).x == 0u))
        return false;
    for (int i = 0; i < u_section_count; ++i) {
        vec4 q = u_section_planes[i];
        precise float side = dot(q.xyz, eye_position) + q.w;
        if (uint(i) + 1u != section_cap && side > 0.0)
            return true;
    }
    return false;
}

// alpha times the component's opacity and the focus factor, without the
// section planes: for a fragment already kept (ib's compose: its fill removed
// what the planes remove).
float oit_local_alpha_kept(float alpha, uint component, vec3 eye_position)
{
    if (component < uint(textureSize(u_local_part_alpha))) // past the end texelFetch gives 0
        alpha *= texelFetch(u_local_part_alpha, int(component)).x;
    if (u_local_focus_shape != OIT_FOCUS_SHAPE_NONE && alpha > 0.0) {
        vec3 p = (u_local_inverse_modelview * vec4(eye_position, 1.0)).xyz;
        alpha *= clamp(oit_focus_distance(p) / u_local_focus_region, 0.0, 1.0);
    }
    return alpha;
}

// alpha (already clamped to [0, 1]) times the component's opacity and the
// focus factor at eye_position (eye space; the shapes are in model space);
// 0 where a section plane removes the fragment.
float oit_local_alpha(float alpha, uint component, uint section_cap, vec3 eye_position)
{
    if (oit_section_removed(component, section_cap, eye_position))
        return 0.0;
    return oit_local_alpha_kept(alpha, component, eye_position);
}

// The material colour of a highlighted part: mix(rgb, highlight, weight),
// before shading (the reference does the same: reference_raster.c).
vec3 oit_local_tint(vec3 rgb, uint component)
{
    if (component >= uint(textureSize(u_local_part_tint)))
        return rgb;
    vec4 tint = texelFetch(u_local_part_tint, int(component));
    return tint.a > 0.0 ? mix(rgb, tint.rgb, tint.a) : rgb;
}

vec3 oit_local_contrast(vec3 rgb)
{
    if (u_local_contrast == 0.0 || u_local_contrast == 1.0)
        return rgb;
    return clamp((rgb - 0.5) * u_local_contrast + 0.5, 0.0, 1.0);
}

#endif
