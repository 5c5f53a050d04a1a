// probe.frag: survives (for an occlusion query) where the min-max target has
// layers left (mode 0) or two distinct depths left (mode 1). Writes nothing.
#include "common/oit_shared.h"

layout(location = OIT_UNIFORM_DDP_PROBE_TWO) uniform int two;
layout(binding = OIT_TEXUNIT_DEPTH_MINMAX) uniform sampler2D minmax;

void main()
{
    vec2 left = texelFetch(minmax, ivec2(gl_FragCoord.xy), 0).xy;
    float near = -left.x, far = left.y;
    bool keep = two != 0 ? near < far : near <= far;
    if (!keep)
        discard;
}
