// init.frag: dual depth peeling's first geometry pass. Writes (-z, z) into the
// min-max target (MAX blending), so it ends up holding (-nearest, farthest).
// The colour targets receive 0, which their under-blending leaves unchanged.
#include "common/oit_shared.h"
#include "common/shade.glsl"
#include "common/canonical_depth.glsl"

layout(location = 0) out vec2 out_minmax;
layout(location = 1) out vec4 out_front;
layout(location = 2) out vec4 out_back;

void main()
{
    if (oit_fragment_alpha() <= 0.0)
        discard; // hidden parts (opacity 0) are not layers
    float z = oit_canonical_depth();
    out_minmax = vec2(-z, z);
    out_front = vec4(0.0);
    out_back = vec4(0.0);
}
