// hybrid/store.frag: the second geometry pass. A fragment among its pixel's k
// closest takes its slot (closest_layers_store); the others are the tail,
// accumulated order-independently (Maule et al. 2013): target 0 adds (c a, a),
// target 1 multiplies by 1 - a (ZERO, ONE_MINUS_SRC_COLOR), as wboit with weight 1.
#extension GL_ARB_ES3_1_compatibility : enable
#include "closest_layers/fragment.glsl"

layout(location = 0) out vec4 out_tail_sum;     // (sum c a, sum a)
layout(location = 1) out vec4 out_tail_product; // product of (1 - a)

void main()
{
    vec4 colour;
    if (closest_layers_store(colour)) {
        out_tail_sum = vec4(0.0); // in the core (or no layer): adds 0
        out_tail_product = vec4(0.0); // multiplies by 1
    } else {
        out_tail_sum = vec4(colour.rgb * colour.a, colour.a);
        out_tail_product = vec4(colour.a);
    }
}
