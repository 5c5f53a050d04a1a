// canonical_depth.glsl: the window depth every exact algorithm sorts and peels
// by. Not gl_FragCoord.z, which the rasterizer interpolates per triangle in
// float, so that coincident faces cut into different triangles land an ulp or
// two apart and their order follows rounding noise (z-fighting). Instead each
// triangle names its coplanar cluster's plane (oit_model.planes), and the
// depth is that plane's at the pixel centre: every fragment on one plane gets
// the same bits at a pixel, whatever its triangle; ties then order by
// triangle index. alg_reference.c computes the same in double.
#include "common/frame.glsl"

layout(location = OIT_UNIFORM_PLANE_TO_NDC) uniform mat4 u_plane_to_ndc;
layout(binding = OIT_TEXUNIT_TRIANGLE_PLANES) uniform usamplerBuffer oit_triangle_planes;
layout(binding = OIT_TEXUNIT_PLANES) uniform samplerBuffer oit_planes;

// `precise`: the same arithmetic in every program (no contraction into fused
// multiply-adds that one compilation makes and another does not), so passes
// that compare depths across programs (ddp's init and peel) agree bit for bit.
float oit_canonical_depth()
{
    uint plane_index = texelFetch(oit_triangle_planes, gl_PrimitiveID).r;
    precise vec4 plane = u_plane_to_ndc * texelFetch(oit_planes, int(plane_index));
    precise vec2 ndc = gl_FragCoord.xy * (2.0 / vec2(u_viewport)) - 1.0;
    // a plane seen edge-on has no depth of its own at a pixel: keep the rasterizer's
    if (abs(plane.z) <= float(OIT_EDGE_ON_PLANE_PPM) * 1e-6 * (abs(plane.x) + abs(plane.y)))
        return gl_FragCoord.z;
    precise float ndc_z = -(plane.x * ndc.x + plane.y * ndc.y + plane.w) / plane.z;
    return clamp(ndc_z * 0.5 + 0.5, 0.0, 1.0);
}
