// neighbour_search.glsl: the surface-neighbour searches of neighbours.comp
// (index / welded, nearest candidate first) and neighbours_epsilon.comp
// (epsilon with the mutual check); what they mean: neighbours.comp.
// Every read goes through a buffer texture (runs) or the triangle table (ids,
// component, plane: one row each, see triangles.comp).
#ifndef IB_NEIGHBOUR_SEARCH_GLSL
#define IB_NEIGHBOUR_SEARCH_GLSL
#include "ib/ib_common.glsl"

// The ray through a pixel centre, in eye space: near + t * direction.
// near_z and span_z: ib_eye_depth's terms along this ray, so that
// ray_eye_depth(r, s) == ib_eye_depth(centre, s) without its two matrix products.
struct pixel_ray {
    vec3 near;
    vec3 direction;
    float near_z;
    float span_z;
};

pixel_ray ray_through(vec2 pixel_centre)
{
    pixel_ray r;
    r.near = ib_eye_position(pixel_centre, 0.0);
    r.direction = ib_eye_position(pixel_centre, 1.0) - r.near;
    vec3 near_point = ib_ray_point(pixel_centre, -1.0);
    r.near_z = near_point.z;
    r.span_z = (ib_ray_point(pixel_centre, 1.0) - near_point).z;
    return r;
}

// ib_eye_depth(centre, depth) for the ray through centre (the same terms)
float ray_eye_depth(pixel_ray r, float depth)
{
    return -(r.near_z + depth * r.span_z);
}

// A fragment with what the searches need of it.
struct described_fragment {
    vec3 plane_normal; // eye-space plane of the fragment's triangle
    float plane_offset;
    vec3 normal;       // the fragment's unit normal
    uint component;
    uvec3 ids;         // its triangle's vertex ids (welded or not, as searched)
    uint triangle;
    float eye_depth;   // at its pixel centre
    float window;      // the id search's reach in eye depth (see ib_common.glsl)
};

described_fragment describe(uvec4 f, vec2 pixel_centre)
{
    described_fragment d;
    d.eye_depth = ib_eye_depth(pixel_centre, uintBitsToFloat(f.x));
    uvec4 row = ib_triangle_ids(f.y);
    vec4 plane = ib_triangle_plane(f.y);
    d.plane_normal = plane.xyz;
    d.plane_offset = plane.w;
    d.normal = oit_unpack_normal(f.z);
    d.component = row.w;
    d.ids = row.xyz;
    d.triangle = f.y;
    d.window = 2.0 * ib_triangle_reach(f.y) * ib_edge_scale + ib_window_margin;
    return d;
}

int shared_ids(uvec3 a, uvec3 b)
{
    int n = 0;
    for (int i = 0; i < 3; ++i)
        n += (a[i] == b.x || a[i] == b.y || a[i] == b.z) ? 1 : 0;
    return n;
}

// Eye depth where the ray meets the fragment's plane.
float predicted_depth(described_fragment d, pixel_ray r)
{
    float denominator = dot(d.plane_normal, r.direction);
    if (abs(denominator) < 1e-12)
        return 1e30;
    float t = (d.plane_offset - dot(d.plane_normal, r.near)) / denominator;
    return -(r.near + t * r.direction).z;
}

// ---- epsilon

// eps_n = 1 - dot(n_f, n_g) may round below 0 by this much
const float IB_EPSILON_MARGIN = 1e-5;

// eps_z: |from's plane depth on the ray through to's pixel - to's depth| / radius
// (best_by_epsilon computes it first: it also bounds the walk)
float epsilon(described_fragment from, float eps_z, uvec4 to)
{
    if (ib_triangle_component(to.y) != from.component)
        return 1e30;
    vec3 n_to = oit_unpack_normal(to.z);
    float eps_n = 1.0 - dot(from.normal, n_to);
    return eps_z + eps_n;
}

// First slot of the run [start, start + count) whose eye depth on to_ray is
// >= depth (count if none): runs are sorted by window depth, and eye depth
// grows with window depth along a pixel's ray.
uint first_at_or_behind(pixel_ray to_ray, uint start, uint count, float depth)
{
    uint low = 0u, high = count;
    while (low < high) {
        uint middle = (low + high) / 2u;
        if (ray_eye_depth(to_ray, ib_depth_fetch(start + middle)) < depth)
            low = middle + 1u;
        else
            high = middle;
    }
    return low;
}

// Best partner of `from` in the run [start, start + run_length) on to_ray:
// the smallest epsilon (the first slot on ties), ignoring candidates above
// `limit`. eps >= eps_z, and eps_z only grows away from the predicted depth,
// so the walk outwards from it stops on each side once eps_z exceeds the best
// so far (or the limit); `margin` covers eps_n's rounding below 0. The same
// answer as trying every candidate (the thesis did), for a few of them.
uint best_by_epsilon(described_fragment from, pixel_ray to_ray, uint start, uint run_length,
                     float limit, out float best_eps)
{
    const float margin = IB_EPSILON_MARGIN;
    uint best = IB_NONE;
    best_eps = 1e30;
    uint count = min(run_length, IB_NONE);
    float predicted = predicted_depth(from, to_ray);
    uint first_behind = first_at_or_behind(to_ray, start, count, predicted);
    for (int side = 0; side < 2; ++side) {
        int step = side == 0 ? 1 : -1;
        for (int j = side == 0 ? int(first_behind) : int(first_behind) - 1; j >= 0 && j < int(count);
             j += step) {
            uvec4 to = ib_core_fetch(start + uint(j));
            float actual = ray_eye_depth(to_ray, uintBitsToFloat(to.x));
            float eps_z = abs(predicted - actual) / ib_radius_eye;
            if (eps_z > min(best_eps, limit) + margin)
                break;
            float e = epsilon(from, eps_z, to);
            if (e < 1e30 && (e < best_eps || (e == best_eps && uint(j) < best))) {
                best_eps = e;
                best = uint(j);
            }
        }
    }
    return best;
}

// epsilon with the mutual check for f (core f, slot i of its run, described);
// IB_NONE if there is no acceptable partner
uint search_by_epsilon(uint i, uvec4 f, described_fragment described, pixel_ray ray, uint start,
                       uint run_length, pixel_ray other_ray, vec2 other_centre, uint other_start,
                       uint other_length)
{
    float eps;
    uint candidate =
        best_by_epsilon(described, other_ray, other_start, other_length, ib_epsilon_max, eps);
    if (candidate == IB_NONE || eps > ib_epsilon_max)
        return IB_NONE;
    // mutual check: f must be the candidate's best partner in f's pixel. f's
    // own epsilon from the candidate bounds that search: a fragment whose eps_z
    // alone passes it cannot beat f (the same answer, for fewer candidates)
    described_fragment partner = describe(ib_core_fetch(other_start + candidate), other_centre);
    float f_eps_z = abs(predicted_depth(partner, ray) - ray_eye_depth(ray, uintBitsToFloat(f.x))) /
                    ib_radius_eye;
    float back_eps;
    uint back = best_by_epsilon(partner, ray, start, run_length,
                                epsilon(partner, f_eps_z, f) + IB_EPSILON_MARGIN, back_eps);
    return back == i ? candidate : IB_NONE;
}

// ---- index, welded

bool adjacent_to(described_fragment f, uint triangle)
{
    if (triangle == f.triangle)
        return true;
    // welded ids are shared by touching parts too: a neighbour stays on its part
    uvec4 row = ib_triangle_ids(triangle);
    return row.w == f.component && shared_ids(f.ids, row.xyz) > 0;
}

// Best candidate in the run [start, start + run_length) on to_ray: on f's
// component, sharing a vertex id with f's triangle, and nearest to the depth
// f's triangle plane predicts there. The run is sorted by depth, so a binary
// search finds where the predicted depth falls and the candidates are tried
// outwards from there, nearest first: the first adjacent one is the answer,
// and most candidates are never loaded (the thesis walked the whole list).
uint search_by_ids(described_fragment f, pixel_ray to_ray, uint start, uint run_length,
                   out float nearest_gap)
{
    nearest_gap = 1e30;
    if (run_length == 0u)
        return IB_NONE;
    uint count = min(run_length, IB_NONE);
    float predicted = predicted_depth(f, to_ray);
    uint low = first_at_or_behind(to_ray, start, count, predicted);
    // the next candidates at or behind the prediction and in front of it,
    // with their triangles and depth gaps (1e30: none left on that side)
    uint behind = low;
    int in_front = int(low) - 1;
    // Only candidates within f.window of f's own depth can share a
    // vertex with f's triangle: a side is done once it leaves the window in the
    // direction it walks (behind: deeper, in front: nearer); candidates short
    // of the window are skipped without loading their triangle.
    float window_near = f.eye_depth - f.window;
    float window_far = f.eye_depth + f.window;
    uvec4 core_behind = uvec4(0u), core_in_front = uvec4(0u);
    float gap_behind = 1e30, gap_in_front = 1e30;
    float depth_behind = 0.0, depth_in_front = 0.0;
    if (behind < count) {
        core_behind = ib_core_fetch(start + behind);
        depth_behind = ray_eye_depth(to_ray, uintBitsToFloat(core_behind.x));
        gap_behind = depth_behind - predicted;
        if (depth_behind > window_far) {
            behind = count;
            gap_behind = 1e30;
        }
    }
    if (in_front >= 0) {
        core_in_front = ib_core_fetch(start + uint(in_front));
        depth_in_front = ray_eye_depth(to_ray, uintBitsToFloat(core_in_front.x));
        gap_in_front = predicted - depth_in_front;
        if (depth_in_front < window_near) {
            in_front = -1;
            gap_in_front = 1e30;
        }
    }
    // before the window cut: what bounds the epsilon search's eps_z from below
    nearest_gap = min(low < count ? abs(depth_behind - predicted) : 1e30,
                      low > 0u ? abs(predicted - depth_in_front) : 1e30);
    // one candidate per step, without branches on the side taken: llvmpipe
    // would run both sides (masked) and load twice as much
    while (behind < count || in_front >= 0) {
        bool take_behind = behind < count && (in_front < 0 || gap_behind <= gap_in_front);
        uint j = take_behind ? behind : uint(in_front);
        float depth = take_behind ? depth_behind : depth_in_front;
        bool in_window = depth >= window_near && depth <= window_far;
        if (in_window && adjacent_to(f, take_behind ? core_behind.y : core_in_front.y))
            return j;
        // the next candidate on the side just tried (the fetch is ignored past the run)
        int next = take_behind ? int(behind) + 1 : in_front - 1;
        uvec4 next_core = ib_core_fetch(start + uint(next));
        float next_depth = ray_eye_depth(to_ray, uintBitsToFloat(next_core.x));
        float gap = next_depth - predicted;
        if (take_behind) {
            bool valid = uint(next) < count && next_depth <= window_far;
            behind = valid ? uint(next) : count;
            core_behind = next_core;
            depth_behind = next_depth;
            gap_behind = valid ? gap : 1e30;
        } else {
            bool valid = next >= 0 && next_depth >= window_near;
            in_front = valid ? next : -1;
            core_in_front = next_core;
            depth_in_front = next_depth;
            gap_in_front = valid ? -gap : 1e30;
        }
    }
    return IB_NONE;
}

#endif
