#!/usr/bin/env bash
# break_shaders.sh SHADER_DIR OUT_DIR: a copy of the shader tree with deliberate,
# plausible bugs, for the broken-shader tests (tests/approx_bounds.cmake): with
# OIT_SHADER_DIR=OUT_DIR, blend, wboit and mboit must then fall outside their
# recorded error bounds. Only their own shaders change (common/ stays).
#  - blend/draw.frag: the colour leaves premultiplied by alpha while the blender
#    (GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA) multiplies by alpha again, a
#    straight/premultiplied mix-up: every translucent fragment adds a times too little.
#  - wboit/accumulate.frag: the weight's depth runs the wrong way (gl_FragCoord.z
#    instead of 1 - z), so the far surfaces outweigh the near ones.
#  - mboit/common.glsl: the power moments' depth warp reversed (1 - 2 s instead of
#    2 s - 1, in both passes), so the reconstruction puts the far layers in front.
#  - wavelet/common.glsl: the Haar detail coefficients' sign flipped, so the
#    rebuilt absorbance in front of a fragment rises where it should fall.
#  - stochastic/accumulate.frag: a sample counts as passed only strictly behind
#    the fragment (< for <=), so a fragment never sees its own samples: the front
#    layer's visibility is its uncovered share, the rest get too little.
#  - adaptive/resolve.frag: the node whose removal changes the area MOST goes
#    (> for <), so past k nodes the visibility keeps the least telling steps.
# The last three break only where their twins run (APPROX_BROKEN_SCENES_<label>).
set -eu
source "$(dirname "$0")/lib.sh"
src=$1 out=$2
rm -rf "$out"
mkdir -p "$(dirname "$out")"
cp -R "$src" "$out"
# replace FILE OLD NEW: OLD must occur exactly once, and NEW afterwards
replace() {
    replace_once "$out/$1" "$2" "$3"
    echo "broke $1: $3"
}
replace blend/draw.frag "o_colour = oit_shade_fragment();" \
    "o_colour = oit_shade_fragment(); o_colour.rgb *= o_colour.a; // BROKEN: premultiplied twice"
replace wboit/accumulate.frag "float d = 1.0 - gl_FragCoord.z;" \
    "float d = gl_FragCoord.z; // BROKEN: depth reversed"
replace mboit/common.glsl "return 2.0 * s - 1.0;" \
    "return 1.0 - 2.0 * s; // BROKEN: warp reversed"
replace wavelet/common.glsl "= -a * exp2(-0.5 * float(j))" \
    "= a * exp2(-0.5 * float(j)) /* BROKEN: sign */"
replace stochastic/accumulate.frag "if (depth <= depth_slots[base + uint(s)])" \
    "if (depth < depth_slots[base + uint(s)]) // BROKEN: own samples not counted"
replace adaptive/resolve.frag "if (area < smallest_area) {" \
    "if (area > smallest_area) { // BROKEN: removes the largest"
