// ib_common.glsl: the Illustration Buffer's buffers, parameters and helpers,
// shared by every ib pass. Bindings and byte counts: common/oit_shared.h;
// the data layout is described in docs/illustration-buffer.md.
#ifndef IB_COMMON_GLSL
#define IB_COMMON_GLSL

#include "common/oit_shared.h"
#include "common/frame.glsl"
// normals: octahedral, 2 x snorm16 (oit_pack_normal / oit_unpack_normal), shared with dp
#include "common/octahedral.glsl"

// Helper invocations (2x2-quad lanes off the primitive) must not write memory,
// but Mesa llvmpipe 22.3 lets their stores through (see shaders/ll/ll_nodes.glsl).
// The drawn passes (fill, compose) return early in them, enabling
// GL_ARB_ES3_1_compatibility for gl_HelperInvocation; the other passes are
// compute shaders, which have none.
#ifdef GL_ARB_ES3_1_compatibility
#define IB_HELPER_INVOCATION gl_HelperInvocation
#else
#define IB_HELPER_INVOCATION false
#endif

// Fill nodes (uvec4: depth bits, triangle, packed normal, next). After the sort
// the same memory holds the transparency fields: .xy copy 0, .zw copy 1, each
// x = packUnorm2x16(alpha, beta), y = gamma (16 bit) | flags << 16.
layout(std430, binding = OIT_SSBO_IB_NODES) buffer ib_node_buffer {
    uvec4 ib_nodes[];
};
// Sorted runs: every pixel's fragments contiguous and front to back, so a
// fragment's place in its run is its layer index.
// x = depth bits, y = triangle, z = octahedral normal (snorm16x2),
// w = curvature (unorm16) | distance (half float) << 16.
layout(std430, binding = OIT_SSBO_IB_RUN_CORE) buffer ib_run_core_buffer {
    uvec4 ib_core[];
};
// Neighbour links: the layer index of the neighbour in the neighbouring pixel's
// run, 16 bit each: x = left | right << 16, y = bottom | top << 16.
layout(std430, binding = OIT_SSBO_IB_RUN_LINKS) buffer ib_run_links_buffer {
    uvec2 ib_links[];
};
layout(std430, binding = OIT_SSBO_IB_COUNTERS) buffer ib_counter_buffer {
    uint ib_counters[OIT_IB_COUNTER_COUNT];
};
// The scene's own buffers, read through the triangle index (gl_PrimitiveID).
layout(std430, binding = OIT_SSBO_IB_INDICES) readonly buffer ib_index_buffer {
    uint ib_indices[];
};
layout(std430, binding = OIT_SSBO_IB_WELDED) readonly buffer ib_welded_buffer {
    uint ib_welded[];
};
layout(std430, binding = OIT_SSBO_IB_POSITIONS) readonly buffer ib_position_buffer {
    float ib_positions[];
};
layout(std430, binding = OIT_SSBO_IB_VERTEX_COMPONENT) readonly buffer ib_vertex_component_buffer {
    uint ib_vertex_components[];
};
// The triangle table (ib/triangles.comp, rebuilt every frame), two rows per
// triangle: 2t = the three vertex ids the neighbour search compares (welded
// ids for welded, vertex indices otherwise) and the component; 2t + 1 = the
// triangle's eye-space plane (normal xyz, offset w: dot(normal, p) = w), as
// float bits. One lookup instead of up to 14 through the scene's buffers.
layout(std430, binding = OIT_SSBO_IB_TRIANGLES) buffer ib_triangle_buffer {
    uvec4 ib_triangle_rows[];
};

// Read-only views of the same buffers as buffer textures. Mesa llvmpipe loads
// from storage buffers lane by lane (a loop with a branch per lane and
// component); texelFetch gathers all lanes at once, so passes that only read a
// buffer use these (after a GL_TEXTURE_FETCH_BARRIER_BIT).
layout(binding = OIT_TEXUNIT_IB_RUN_CORE) uniform usamplerBuffer ib_core_texture;
layout(binding = OIT_TEXUNIT_IB_RUN_LINKS) uniform usamplerBuffer ib_links_texture;
layout(binding = OIT_TEXUNIT_IB_TRIANGLES) uniform usamplerBuffer ib_triangle_texture;
layout(binding = OIT_TEXUNIT_IB_RUN_WORDS) uniform usamplerBuffer ib_core_words_texture;
layout(binding = OIT_TEXUNIT_IB_COMPONENTS) uniform samplerBuffer ib_components_texture;
layout(binding = OIT_TEXUNIT_IB_NODES) uniform usamplerBuffer ib_nodes_texture;
layout(binding = OIT_TEXUNIT_IB_TRIANGLE_REACH) uniform samplerBuffer ib_triangle_reach_texture;

// Work-group counts (x, y, 1) at counter `slot` for glDispatchComputeIndirect:
// `groups` in rows of at most OIT_IB_MAX_GROUPS_X (epsilon_dispatch.comp,
// tiles_dispatch.comp; the passes number their groups row by row).
void ib_write_dispatch(uint groups, int slot)
{
    uint x = min(groups, uint(OIT_IB_MAX_GROUPS_X));
    ib_counters[slot] = x;
    ib_counters[slot + 1] = x == 0u ? 1u : (groups + x - 1u) / x;
    ib_counters[slot + 2] = 1u;
}

uvec4 ib_core_fetch(uint slot) { return texelFetch(ib_core_texture, int(slot)); }
// The component's material (as oit_components[component]: rgb colour, a opacity).
vec4 ib_component_material(uint component) { return texelFetch(ib_components_texture, int(component)); }
// The triangle's reach, model space (oit_model.triangle_reach).
float ib_triangle_reach(uint triangle) { return texelFetch(ib_triangle_reach_texture, int(triangle)).x; }
// Only the window depth (one channel is cheaper to gather than four).
float ib_depth_fetch(uint slot) { return uintBitsToFloat(texelFetch(ib_core_words_texture, int(4u * slot)).x); }

// Per-frame parameters; mirrors struct ib_params in src/core/alg_ib.c.
layout(std430, binding = OIT_SSBO_IB_PARAMS) readonly buffer ib_param_buffer {
    mat4 ib_inverse_projection;
    int ib_mode;
    int ib_view;
    int ib_view_parameter;
    int ib_search;
    int ib_curvature_neighbours;
    float ib_curvature_effect;
    float ib_focus_region; // <= 0: normalise by the frame's largest distance
    int ib_distance_mode;
    int ib_distance_skip;
    int ib_fields; // OIT_FIELD_* mask: 1 alpha, 2 beta, 4 gamma
    float ib_lambda_alpha;
    float ib_lambda_beta;
    float ib_lambda_gamma;
    float ib_halo_r;
    float ib_halo_g;
    float ib_halo_b;
    int ib_last_layer_opaque;
    float ib_epsilon_max;
    float ib_radius_eye; // the model's bounding radius in eye space
    int ib_needs_fields;
    // The id search's window: a candidate sharing a vertex with f's triangle is
    // at most 2 * ib_triangle_reach(f's triangle) * ib_edge_scale + ib_window_margin
    // from f in eye depth (see alg_ib.c).
    float ib_edge_scale;
    float ib_window_margin;
    int ib_banded; // the frame is drawn in bands of rows (sort.comp counts its long runs)
};

// The band of rows the compute passes work on (alg_ib.c; docs/illustration-buffer.md,
// "Bands"): x..y the rows stored, the only ones the fill drew (the others count as
// outside the image), z..w the rows the band composes, the only ones counted in the
// statistics. The whole image in a frame drawn whole.
layout(location = OIT_UNIFORM_IB_BAND) uniform ivec4 ib_band;

// The first row of tiles (OIT_IB_TILE_SIZE squared pixels) the per-pixel passes
// are dispatched from: the one holding the band's first stored row.
int ib_band_tile_row() { return ib_band.x / OIT_IB_TILE_SIZE; }
// The pixel of invocation global_id of a per-pixel pass (work groups of a tile).
ivec2 ib_band_pixel(uvec3 global_id)
{
    return ivec2(global_id.xy) + ivec2(0, ib_band_tile_row() * OIT_IB_TILE_SIZE);
}
// The pixel is in a row the band composes: its figures count.
bool ib_counted(ivec2 pixel) { return pixel.y >= ib_band.z && pixel.y < ib_band.w; }

// Per pixel: during the fill the list head, afterwards the run's first slot.
layout(binding = OIT_IMAGE_LIST_HEAD, r32ui) uniform uimage2D ib_heads;
// Per pixel: the run's length (written by the sort).
layout(binding = OIT_IMAGE_LIST_COUNT, r32ui) uniform uimage2D ib_counts;

const ivec2 IB_DIRECTIONS[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
const uint IB_NONE = uint(OIT_IB_NO_NEIGHBOUR);

// ---- eye space from pixel and window depth

// The eye position at canonical depth s (common/canonical_depth.glsl): s runs
// linearly along the pixel's ray from its near-plane point (NDC depth -1) to
// its far-plane point (+1).
vec3 ib_ray_point(vec2 pixel_centre, float ndc_depth)
{
    vec4 ndc = vec4(2.0 * pixel_centre / vec2(u_viewport) - 1.0, ndc_depth, 1.0);
    vec4 eye = ib_inverse_projection * ndc;
    return eye.xyz / eye.w;
}

vec3 ib_eye_position(vec2 pixel_centre, float depth)
{
    vec3 near_point = ib_ray_point(pixel_centre, -1.0);
    return near_point + depth * (ib_ray_point(pixel_centre, 1.0) - near_point);
}

// Linear eye depth (distance in front of the eye along -z).
float ib_eye_depth(vec2 pixel_centre, float depth)
{
    return -ib_eye_position(pixel_centre, depth).z;
}

// ---- distance along the ray (curvature_distance.comp, distance_max.comp)

// The layer fragment i of a run of run_length measures its distance to: the
// next (adjacent), k on (skip) or the last (far end); i itself for the last.
uint ib_distance_target(uint i, uint run_length)
{
    if (ib_distance_mode == OIT_IB_DISTANCE_ADJACENT)
        return min(i + 1u, run_length - 1u);
    if (ib_distance_mode == OIT_IB_DISTANCE_SKIP)
        return min(i + uint(max(ib_distance_skip, 1)), run_length - 1u);
    return run_length - 1u;
}

// The distance in linear eye depth between two canonical depths on a pixel's ray.
float ib_depth_distance(vec2 pixel_centre, float depth, float target_depth)
{
    return abs(ib_eye_depth(pixel_centre, target_depth) - ib_eye_depth(pixel_centre, depth));
}

// ---- the depth order: window depth, then triangle index

bool ib_in_front(uvec2 a, uvec2 b)
{
    float da = uintBitsToFloat(a.x), db = uintBitsToFloat(b.x);
    return da < db || (da == db && a.y < b.y);
}

// ---- triangles

uvec3 ib_triangle_vertices(uint triangle)
{
    return uvec3(ib_indices[3u * triangle], ib_indices[3u * triangle + 1u],
                 ib_indices[3u * triangle + 2u]);
}

// The component of the provoking (last) vertex, as v_component; from the triangle table.
uint ib_triangle_component(uint triangle)
{
    return texelFetch(ib_triangle_texture, int(2u * triangle)).w;
}

// The ids the neighbour search compares (xyz) and the component (w).
uvec4 ib_triangle_ids(uint triangle) { return texelFetch(ib_triangle_texture, int(2u * triangle)); }

// The triangle's eye-space plane: normal (xyz, not normalised) and offset (w).
vec4 ib_triangle_plane(uint triangle)
{
    return uintBitsToFloat(texelFetch(ib_triangle_texture, int(2u * triangle + 1u)));
}

vec3 ib_vertex_eye(uint v)
{
    vec3 p = vec3(ib_positions[3u * v], ib_positions[3u * v + 1u], ib_positions[3u * v + 2u]);
    return (u_modelview * vec4(p, 1.0)).xyz;
}

// ---- runs and neighbours

uint ib_run_start(ivec2 pixel) { return imageLoad(ib_heads, pixel).x; }
uint ib_run_length(ivec2 pixel) { return imageLoad(ib_counts, pixel).x; }

// In the image, and in a row the band stores.
bool ib_inside(ivec2 pixel)
{
    return all(greaterThanEqual(pixel, ivec2(0, ib_band.x))) &&
           all(lessThan(pixel, ivec2(u_viewport.x, ib_band.y)));
}

// Layer index of fragment `slot`'s neighbour in direction d, or IB_NONE.
uint ib_link(uint slot, int d)
{
    uvec2 links = texelFetch(ib_links_texture, int(slot)).xy;
    uint word = (d < 2) ? links.x : links.y;
    return (d & 1) == 0 ? (word & 0xFFFFu) : (word >> 16);
}

// A fragment addressed by pixel and slot (its index in the run buffers).
struct ib_fragment {
    ivec2 pixel;
    uint slot;
    uint layer;
};

// The neighbour of f in direction d; returns false where there is none.
bool ib_neighbour(ib_fragment f, int d, out ib_fragment g)
{
    uint layer = ib_link(f.slot, d);
    g.pixel = f.pixel + IB_DIRECTIONS[d];
    g.layer = layer;
    g.slot = 0u;
    if (layer == IB_NONE)
        return false;
    g.slot = ib_run_start(g.pixel) + layer;
    return true;
}

// Diagonal neighbour through the surface: first along d1 then d2, else d2 then d1.
bool ib_diagonal(ib_fragment f, int d1, int d2, out ib_fragment g)
{
    ib_fragment h;
    if (ib_neighbour(f, d1, h) && ib_neighbour(h, d2, g))
        return true;
    if (ib_neighbour(f, d2, h) && ib_neighbour(h, d1, g))
        return true;
    return false;
}

int ib_neighbour_count(uint slot)
{
    int count = 0;
    for (int d = 0; d < 4; ++d)
        count += ib_link(slot, d) != IB_NONE ? 1 : 0;
    return count;
}

// ---- transparency fields: value (16 bit each) and flags (1 = free to change)

const uint IB_FREE_ALPHA = 1u, IB_FREE_BETA = 2u, IB_FREE_GAMMA = 4u;

uvec2 ib_fields_raw(uint slot, int copy)
{
    uvec4 n = ib_nodes[slot];
    return copy == 0 ? n.xy : n.zw;
}

// As ib_fields_raw, through the buffer texture, for passes that only read the fields.
uvec2 ib_fields_fetch(uint slot, int copy)
{
    uvec4 n = texelFetch(ib_nodes_texture, int(slot));
    return copy == 0 ? n.xy : n.zw;
}

vec3 ib_fields_values(uvec2 raw)
{
    return vec3(unpackUnorm2x16(raw.x), float(raw.y & 0xFFFFu) / 65535.0);
}

uint ib_fields_flags(uvec2 raw) { return raw.y >> 16; }

void ib_store_fields(uint slot, int copy, vec3 values, uint flags)
{
    values = clamp(values, 0.0, 1.0);
    uvec2 raw = uvec2(packUnorm2x16(values.xy),
                      uint(round(values.z * 65535.0)) | (flags << 16));
    if (copy == 0)
        ib_nodes[slot].xy = raw;
    else
        ib_nodes[slot].zw = raw;
}

#endif
