// blend_layer.frag: hand the peeled layer to the blender, which puts it under
// the accumulation (rgb += T * a c, T *= 1 - a). Full-screen pass.
#include "common/oit_shared.h"

layout(binding = OIT_TEXUNIT_PEEL_LAYER) uniform sampler2D layer_colour;

layout(location = 0) out vec4 out_colour;

void main()
{
    out_colour = texelFetch(layer_colour, ivec2(gl_FragCoord.xy), 0);
}
