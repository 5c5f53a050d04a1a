// octahedral.glsl: unit normals in 32 bits (octahedral, 2 x snorm16): ib's
// fragment normals, and dp's curvature approximation, which thereby sees the
// very same quantised values as ib.
#ifndef OIT_OCTAHEDRAL_GLSL
#define OIT_OCTAHEDRAL_GLSL

const uint OIT_NO_NORMAL = 0x80008000u; // packSnorm2x16 never yields -32768

vec2 oit_sign_not_zero(vec2 v)
{
    return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0);
}

uint oit_pack_normal(vec3 n)
{
    float l1 = abs(n.x) + abs(n.y) + abs(n.z);
    if (!(l1 > 0.0))
        return OIT_NO_NORMAL;
    n /= l1;
    vec2 p = n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * oit_sign_not_zero(n.xy);
    return packSnorm2x16(p);
}

// Unit normal, or vec3(0) where the fragment had none.
vec3 oit_unpack_normal(uint bits)
{
    if (bits == OIT_NO_NORMAL)
        return vec3(0.0);
    vec2 p = unpackSnorm2x16(bits);
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (n.z < 0.0)
        n.xy = (1.0 - abs(n.yx)) * oit_sign_not_zero(n.xy);
    return normalize(n);
}

#endif
