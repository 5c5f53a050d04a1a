// blend_curvature.frag: depth peeling with the curvature modulation, the
// approximation peeling allows (docs/modulation.md). The Illustration Buffer
// finds a fragment's neighbours through the surface in the adjacent pixels'
// lists; a peeled layer has one fragment per pixel, so here the neighbour in
// direction d is the fragment of the SAME layer in the adjacent pixel, if it
// belongs to the same component. Otherwise the rest mirrors ib's
// curvature_distance.comp: curvature = mean over the neighbours that exist of
// |n - n_k| / 2 (octahedral normals as ib stores them, result quantised to
// 16 bits as ib stores it), diagonals (8 neighbours) reached through a side
// neighbour first; alpha = saturate(curvature * effect) * local factor.
// dist-curv: blending is delayed by one layer as in blend_distance.frag,
// alpha = saturate(max(distance / norm, curvature * effect)) * local factor.
// edges (ib's definition with the same neighbours): alpha = 1 where a fragment
// has fewer than four neighbours, else the material opacity; times the local
// factor. Full-screen pass; hands the premultiplied colour to the under-blender.
#include "common/oit_shared.h"
#include "common/local_modulation.glsl"
#include "common/octahedral.glsl"

layout(binding = OIT_TEXUNIT_PEEL_LAYER) uniform sampler2D layer_colour;     // rgb, local factor
layout(binding = OIT_TEXUNIT_PEEL_NORMAL) uniform usampler2D layer_normal;   // normal, component + 1
layout(binding = OIT_TEXUNIT_DEPTH_PREVIOUS) uniform sampler2D layer_depth;  // dist-curv only
layout(binding = OIT_TEXUNIT_PEEL_NEXT_LAYER) uniform sampler2D next_colour; // dist-curv: a > 0 where it exists
layout(binding = OIT_TEXUNIT_DEPTH_NEXT) uniform sampler2D next_depth;       // dist-curv only

layout(location = OIT_UNIFORM_DP_CURVATURE_EFFECT) uniform float curvature_effect;
layout(location = OIT_UNIFORM_DP_CURVATURE_NEIGHBOURS) uniform int curvature_neighbours;
layout(location = OIT_UNIFORM_DP_NEIGHBOUR_MODE) uniform int mode; // OIT_IB_MODE_*

// vec4 per component: rgb material colour, a material opacity (as shade.glsl)
layout(std430, binding = OIT_SSBO_COMPONENTS) readonly buffer oit_component_table {
    vec4 oit_components[];
};

layout(location = 0) out vec4 out_colour;

// as IB_DIRECTIONS: -x, +x, -y, +y
const ivec2 DIRECTIONS[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));

uint component_plus_one; // of the fragment being blended

// Whether the layer's fragment at q is on the same component (and exists).
bool same_surface(ivec2 q)
{
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, u_viewport)))
        return false;
    return texelFetch(layer_normal, q, 0).y == component_plus_one;
}

vec3 normal_at(ivec2 q) { return oit_unpack_normal(texelFetch(layer_normal, q, 0).x); }

float layer_curvature(ivec2 pixel)
{
    vec3 n = normal_at(pixel);
    float sum = 0.0;
    int count = 0;
    for (int d = 0; d < 4; ++d) {
        ivec2 q = pixel + DIRECTIONS[d];
        if (same_surface(q)) {
            sum += length(n - normal_at(q));
            ++count;
        }
    }
    if (curvature_neighbours == 8) {
        for (int d1 = 0; d1 < 2; ++d1) {
            for (int d2 = 2; d2 < 4; ++d2) {
                ivec2 q = pixel + DIRECTIONS[d1] + DIRECTIONS[d2];
                // through the surface: along d1 then d2, else d2 then d1
                if (same_surface(q) && (same_surface(pixel + DIRECTIONS[d1]) ||
                                        same_surface(pixel + DIRECTIONS[d2]))) {
                    sum += length(n - normal_at(q));
                    ++count;
                }
            }
        }
    }
    float curvature = count > 0 ? clamp(sum / (2.0 * float(count)), 0.0, 1.0) : 0.0;
    return round(curvature * 65535.0) / 65535.0; // ib stores it as unorm16
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 layer = texelFetch(layer_colour, pixel, 0);
    component_plus_one = texelFetch(layer_normal, pixel, 0).y;
    if (layer.a <= 0.0 || component_plus_one == 0u) {
        out_colour = vec4(0.0); // no fragment in this layer here
        return;
    }
    if (mode == OIT_IB_MODE_EDGES) {
        int count = 0;
        for (int d = 0; d < 4; ++d)
            count += same_surface(pixel + DIRECTIONS[d]) ? 1 : 0;
        float material = clamp(u_alpha * oit_components[component_plus_one - 1u].a, 0.0, 1.0);
        float alpha = (count < 4 ? 1.0 : material) * layer.a;
        out_colour = vec4(layer.rgb * alpha, alpha);
        return;
    }
    float opacity = layer_curvature(pixel) * curvature_effect;
    if (mode == OIT_IB_MODE_DIST_CURV) {
        float distance = 0.0;
        if (texelFetch(next_colour, pixel, 0).a > 0.0)
            distance = abs(oit_eye_depth(gl_FragCoord.xy, texelFetch(next_depth, pixel, 0).r) -
                           oit_eye_depth(gl_FragCoord.xy, texelFetch(layer_depth, pixel, 0).r));
        distance = unpackHalf2x16(packHalf2x16(vec2(distance, 0.0))).x; // ib stores a half float
        opacity = max(distance / u_distance_norm, opacity);
    }
    float alpha = clamp(opacity, 0.0, 1.0) * layer.a;
    out_colour = vec4(layer.rgb * alpha, alpha);
}
