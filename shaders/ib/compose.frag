// compose.frag: walks each pixel's sorted run front to back, recomputes each
// fragment's colour and opacity (shading from the stored normal and the eye
// position rebuilt from pixel and depth: the same formula as every algorithm),
// modulates the opacity and composites in float: C += T a c; T *= 1 - a;
// finally C += T background. The RGBA8 output is written once.
// Views show the buffer instead (heatmap, peel limit, layer, neighbour count,
// curvature, distance, fields). ib_pass = the fields' current copy.
// Also counts Psi's pixels. Empty pixels are discarded (as in ll: the output
// is cleared to the background first); the views and the modulations are
// compiled in only in the general variant (common/variants.glsl).
#extension GL_ARB_ES3_1_compatibility : enable
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "ib/ib_common.glsl"

layout(location = OIT_UNIFORM_IB_PASS) uniform int fields_copy;

layout(location = 0) out vec4 out_colour;

// blue -> green -> yellow -> red; oit_heatmap_colour (image_error.c) is the same
// scale for the legends: change both together
vec3 heat(float t)
{
    t = clamp(t, 0.0, 1.0) * 3.0;
    if (t < 1.0)
        return mix(vec3(0.0, 0.0, 1.0), vec3(0.0, 1.0, 0.0), t);
    if (t < 2.0)
        return mix(vec3(0.0, 1.0, 0.0), vec3(1.0, 1.0, 0.0), t - 1.0);
    return mix(vec3(1.0, 1.0, 0.0), vec3(1.0, 0.0, 0.0), t - 2.0);
}

// neighbour count 0..4: magenta, red, orange, yellow, green
vec3 neighbour_colour(int count)
{
    const vec3 colours[5] = vec3[5](vec3(1.0, 0.0, 1.0), vec3(1.0, 0.0, 0.0), vec3(1.0, 0.5, 0.0),
                                    vec3(1.0, 1.0, 0.0), vec3(0.0, 0.8, 0.0));
    return colours[clamp(count, 0, 4)];
}

float distance_norm()
{
    if (ib_focus_region > 0.0)
        return ib_focus_region;
    float largest = uintBitsToFloat(ib_counters[OIT_IB_COUNTER_MAX_DISTANCE]);
    return largest > 0.0 ? largest : 1.0;
}

void main()
{
    if (IB_HELPER_INVOCATION) {
        out_colour = vec4(0.0); // discarded anyway
        return;
    }
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    uint run_length = ib_run_length(pixel);
    if (run_length == 0u)
        discard; // LL_EMPTY_PIXEL_DISCARD (ll/ll_nodes.glsl)
    uint start = ib_run_start(pixel);
    // Psi's numerator: pixels whose list is longer than 2/3 of the longest (as ll's compose)
    if (3u * run_length > 2u * ib_counters[OIT_FRAME_COUNTER_MAX_LIST])
        atomicAdd(ib_counters[OIT_IB_COUNTER_PSI_PIXELS], 1u);

#if OIT_VARIANT_VIEWS
    if (ib_view == OIT_IB_VIEW_HEATMAP) {
        uint longest = max(ib_counters[OIT_FRAME_COUNTER_MAX_LIST], 1u);
        out_colour = vec4(heat(float(run_length) / float(longest)), 1.0);
        return;
    }
    if (ib_view == OIT_IB_VIEW_CURVATURE || ib_view == OIT_IB_VIEW_DISTANCE ||
        ib_view == OIT_IB_VIEW_FIELDS) {
        // the value of fragment view_parameter, unblended; background where there is none
        uint layer = uint(ib_view_parameter);
        vec3 value = u_background;
        if (layer < run_length) {
            uint slot = start + layer;
            uint w = ib_core_fetch(slot).w;
            if (ib_view == OIT_IB_VIEW_CURVATURE)
                value = vec3(clamp(float(w & 0xFFFFu) / 65535.0 * ib_curvature_effect, 0.0, 1.0));
            else if (ib_view == OIT_IB_VIEW_DISTANCE)
                value = vec3(clamp(unpackHalf2x16(w >> 16).x / distance_norm(), 0.0, 1.0));
            else
                value = ib_fields_values(ib_fields_fetch(slot, fields_copy));
        }
        out_colour = vec4(value, 1.0);
        return;
    }
#endif

#if OIT_VARIANT_IB_MODES
    float norm = distance_norm();
    vec3 halo = vec3(ib_halo_r, ib_halo_g, ib_halo_b);
#endif
    vec3 colour = vec3(0.0);
    float transmittance = 1.0;
    for (uint i = 0u; i < run_length; ++i) {
#if OIT_VARIANT_VIEWS
        if (ib_view == OIT_IB_VIEW_PEEL_LIMIT && i >= uint(ib_view_parameter))
            break;
        if (ib_view == OIT_IB_VIEW_LAYER && i != uint(ib_view_parameter))
            continue;
#endif
        uint slot = start + i;
        uvec4 core = ib_core_fetch(slot); // buffer texture: gathered, see ib_common.glsl
        float depth = uintBitsToFloat(core.x);
        uint component = ib_triangle_component(core.y);
        vec4 material = ib_component_material(component);
        float alpha = clamp(u_alpha * material.a, 0.0, 1.0);
        vec3 normal = oit_unpack_normal(core.z);
        vec3 eye_position = ib_eye_position(gl_FragCoord.xy, depth);
        vec3 rgb = oit_shade_rgb(oit_local_tint(material.rgb, component), normal, eye_position);
#if OIT_VARIANT_VIEWS
        if (ib_view == OIT_IB_VIEW_NEIGHBOURS)
            rgb = neighbour_colour(ib_neighbour_count(slot));
#endif

#if OIT_VARIANT_IB_MODES
        float curvature = float(core.w & 0xFFFFu) / 65535.0 * ib_curvature_effect;
        float distance = unpackHalf2x16(core.w >> 16).x / norm;
        if (ib_mode == OIT_IB_MODE_CURVATURE)
            alpha = clamp(curvature, 0.0, 1.0);
        else if (ib_mode == OIT_IB_MODE_DISTANCE)
            alpha = clamp(distance, 0.0, 1.0);
        else if (ib_mode == OIT_IB_MODE_DIST_CURV)
            alpha = clamp(max(distance, curvature), 0.0, 1.0);
        else if (ib_mode == OIT_IB_MODE_EDGES && ib_neighbour_count(slot) < 4)
            alpha = 1.0;
#endif
        // local modulation (per-part opacity, focus shapes) scales whatever the mode chose
        alpha = oit_local_alpha_kept(alpha, component, eye_position); // sections: ib/fill.frag
        bool last = ib_last_layer_opaque != 0 && i + 1u == run_length;

#if OIT_VARIANT_IB_MODES
        if (ib_mode == OIT_IB_MODE_FIELDS) {
            // thesis 4.6 / algorithm 9: the halo is added as colour; the alpha
            // field raises the material opacity (a = a0 + (1 - a0) field alpha)
            vec3 fields = ib_fields_values(ib_fields_fetch(slot, fields_copy));
            float a = (ib_fields & 1) != 0 ? alpha + (1.0 - alpha) * fields.x : alpha;
            float b = (ib_fields & 2) != 0 ? fields.y : 0.0;
            float g = (ib_fields & 4) != 0 ? fields.z : 0.0;
            rgb += g * halo;
            float a_r = last ? 1.0 : a + (1.0 - a) * b;
            colour += transmittance * a_r * rgb;
            transmittance *= last ? 0.0 : (1.0 - a) * (1.0 - b);
            continue;
        }
#endif
        if (last)
            alpha = 1.0;
        colour += transmittance * alpha * rgb;
        transmittance *= 1.0 - alpha;
    }
    out_colour = vec4(colour + transmittance * u_background, 1.0);
}
