// kbuffer/store.frag: the second geometry pass. A fragment among its pixel's k
// closest takes its slot (closest_layers_store); the others are the tail,
// blended "over" in submission order into a float target by the fixed-function
// blender (ONE, ONE_MINUS_SRC_ALPHA: premultiplied, the later fragment in front),
// as blend does with every fragment. Order-dependent.
#extension GL_ARB_ES3_1_compatibility : enable
#include "closest_layers/fragment.glsl"

layout(location = 0) out vec4 out_tail; // premultiplied: (c a, a)

void main()
{
    vec4 colour;
    if (closest_layers_store(colour))
        out_tail = vec4(0.0); // in the core (or no layer): leaves the tail as it is
    else
        out_tail = vec4(colour.rgb * colour.a, colour.a);
}
