// accumulate.frag: weighted blended OIT's geometry pass (depth test off).
// Target 0 (additive): (w a c, w a). Target 1 (multiplied by 1 - src): a.
// Weight: McGuire & Bavoil 2013, the variant on window depth d = gl_FragCoord.z
// (eq. 10 of the JCGT paper): w = a * max(1e-2, 3e3 * (1 - d)^3). It needs no
// scene scale, unlike the eye-space z variants (eqs. 7 to 9), since models
// come in any unit.
#include "common/oit_shared.h"
#include "common/shade.glsl"

layout(location = 0) out vec4 out_accumulation;
layout(location = 1) out vec4 out_revealage;

void main()
{
    vec4 colour = oit_shade_fragment();
    if (colour.a <= 0.0)
        discard; // hidden parts (opacity 0) contribute nothing
    float d = 1.0 - gl_FragCoord.z;
    float weight = colour.a * max(1e-2, 3e3 * d * d * d);
    out_accumulation = vec4(colour.rgb * colour.a, colour.a) * weight;
    out_revealage = vec4(colour.a);
}
