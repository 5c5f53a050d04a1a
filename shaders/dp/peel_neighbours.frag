// peel_neighbours.frag: peel.frag that also writes the layer's normal and
// component (curvature and dist-curv: blend_curvature.frag reads them).
#define DP_NEIGHBOURS 1
#include "dp/peel.frag"
