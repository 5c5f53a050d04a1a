// triangles.comp: the triangle table for this frame, two rows per triangle
// (layout in ib_common.glsl): the ids the neighbour search compares (welded
// ids for welded, vertex indices otherwise) with the component, and the
// triangle's eye-space plane. Later passes look a fragment's triangle up here
// once instead of going through the index, welded-id, component and position
// buffers (up to 14 dependent loads and three transforms per lookup).
// Compute pass, one invocation per triangle.
#include "common/oit_shared.h"
#include "ib/ib_common.glsl"

layout(location = OIT_UNIFORM_IB_PASS) uniform int item_count; // the number of triangles

layout(local_size_x = OIT_IB_ITEMS_PER_GROUP) in;

void main()
{
    uint triangle = gl_GlobalInvocationID.x +
                    gl_GlobalInvocationID.y * gl_NumWorkGroups.x * uint(OIT_IB_ITEMS_PER_GROUP);
    if (triangle >= uint(item_count))
        return;
    uvec3 v = ib_triangle_vertices(triangle);
    uvec3 ids = ib_search == OIT_IB_SEARCH_WELDED ? uvec3(ib_welded[v.x], ib_welded[v.y], ib_welded[v.z]) : v;
    // the provoking (last) vertex, as v_component: a cap's section bits split off
    // (geometry.vert), so cap and part share their component everywhere
    uint component = ib_vertex_components[v.z] & ((1u << OIT_COMPONENT_CAP_SHIFT) - 1u);
    vec3 a = ib_vertex_eye(v.x), b = ib_vertex_eye(v.y), c = ib_vertex_eye(v.z);
    vec3 plane_normal = cross(b - a, c - a);
    float plane_offset = dot(plane_normal, a);
    ib_triangle_rows[2u * triangle] = uvec4(ids, component);
    ib_triangle_rows[2u * triangle + 1u] = floatBitsToUint(vec4(plane_normal, plane_offset));
}
