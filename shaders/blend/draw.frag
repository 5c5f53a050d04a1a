// blend/draw.frag: the shaded fragment, blended "over" the accumulation
// target by the fixed-function blender in submission order.
#include "common/shade.glsl"

layout(location = 0) out vec4 o_colour;

void main()
{
    o_colour = oit_shade_fragment();
}
