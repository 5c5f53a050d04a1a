// blend_back.frag: hand this pass's back layer (rgb = C, a = T) to the blender,
// which puts it over the back layers so far. Full-screen pass.
#include "common/oit_shared.h"

layout(binding = OIT_TEXUNIT_PEEL_LAYER) uniform sampler2D back_layer;

layout(location = 0) out vec4 out_colour;

void main()
{
    out_colour = texelFetch(back_layer, ivec2(gl_FragCoord.xy), 0);
}
