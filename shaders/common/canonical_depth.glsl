// canonical_depth.glsl: the depth every exact algorithm sorts and peels by.
//
// Not gl_FragCoord.z, for two reasons. (1) The rasterizer interpolates each
// triangle's depth in float, so coincident faces cut into different triangles
// land an ulp or two apart and their order follows rounding noise
// (z-fighting). So each triangle names its coplanar cluster's plane
// (oit_model.planes), and the depth is that plane's at the pixel centre: every
// fragment on one plane gets the same bits at a pixel, whatever its triangle;
// ties then order by triangle index. (2) Window depth is hyperbolic in eye
// depth: with the near plane at 0.01 and surfaces at 800, two of them 1e-3
// apart differ by 2e-11 in window depth, far below a float's resolution near
// 1. So the depth is linear instead: the parameter s of the plane's point on
// the pixel's eye-space ray from its near-plane point (s = 0) to its
// far-plane point (s = 1). Floats resolve s relatively, so surfaces 1e-3
// apart at 800 units stay apart whatever the near plane. For a perspective
// projection s = (eye depth - near) / (far - near).
// alg_reference.c computes the same in double.
#include "common/shade.glsl"

layout(binding = OIT_TEXUNIT_TRIANGLE_PLANES) uniform usamplerBuffer oit_triangle_planes;
layout(binding = OIT_TEXUNIT_PLANES) uniform samplerBuffer oit_planes;

// `precise`: the same arithmetic in every program (no contraction into fused
// multiply-adds that one compilation makes and another does not), so passes
// that compare depths across programs (ddp's init and peel) agree bit for bit.
float oit_canonical_depth()
{
    uint plane_index = texelFetch(oit_triangle_planes, gl_PrimitiveID).r;
    precise vec4 plane = u_plane_to_eye * texelFetch(oit_planes, int(plane_index));
    precise vec3 near_point, far_point;
    oit_pixel_ray(gl_FragCoord.xy, near_point, far_point);
    precise vec3 along = far_point - near_point;
    precise float slope = dot(plane.xyz, along);
    precise float at_near = dot(plane.xyz, near_point) + plane.w;
    precise float s;
    // a plane seen edge-on has no depth of its own at a pixel: the interpolated
    // eye position's, projected on the ray
    if (abs(slope) <= float(OIT_EDGE_ON_PLANE_PPM) * 1e-6 * length(plane.xyz) * length(along))
        s = dot(v_eye_position - near_point, along) / dot(along, along);
    else
        s = -at_near / slope;
    return clamp(s, 0.0, float(OIT_CANONICAL_DEPTH_MAX));
}
