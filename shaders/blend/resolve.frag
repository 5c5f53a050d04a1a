// blend/resolve.frag: copy the float accumulation (already over the
// background) into the RGBA8 output; the only quantization happens here.
#include "common/oit_shared.h"

layout(binding = OIT_TEXUNIT_ACCUM) uniform sampler2D u_accumulation;

layout(location = 0) out vec4 o_colour;

void main()
{
    o_colour = vec4(texelFetch(u_accumulation, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
