// select.frag: the first geometry pass of kbuffer and hybrid (depth test and
// colour writes off): every fragment inserts its key among its pixel's k
// smallest (closest_layers_insert, lock-free). Writes no colour.
#extension GL_ARB_ES3_1_compatibility : enable
#include "closest_layers/fragment.glsl"

void main()
{
    uint key = closest_layers_fragment_key();
    if (key != OIT_CLOSEST_EMPTY_KEY)
        closest_layers_insert(ivec2(gl_FragCoord.xy), key);
}
