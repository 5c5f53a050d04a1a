#!/usr/bin/env bash
# mboit_checks.sh OIT WORKDIR SCENES REFERENCE_DIR EGL_IMAGE_DIR: mboit beyond its image bounds.
#  - what it cannot express is refused before any work, one line, exit 2 (as wboit):
#    the distance modulation, the ib-only modulations, buffer views; and a bad --moments;
#  - uniformly coloured scenes: the composite's colour is exact (sum T a c / sum T a = c
#    whatever T) and its coverage 1 - exp(-b0) = 1 - prod (1 - a) is exact up to the
#    opacity clamp (never reached at alpha 0.5), so every variant matches the reference
#    on the one-colour wuson within the exact tolerance (2/255, no pixel over it);
#  - more moments err less on the deep scenes: power6's mean difference from the
#    reference is at most power4's on onion, spheres and menger (the images of the
#    main image tests: EGL_IMAGE_DIR/mboit_SCENE.png and mboit6_SCENE.png).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 reference=$4 images=$5
rm -rf "$work"; mkdir -p "$work"
r=("$oit" render --model "$scenes/gearbox.obj" --algorithm mboit --size 32x32 --out "$work/x.png")
expect_exit 2 "mboit: the distance modulation needs the next fragment" -- "${r[@]}" --modulation distance
for mode in curvature fields; do
    expect_exit 2 "mboit: opacity modulation '$mode' needs surface neighbours" -- "${r[@]}" --modulation $mode
done
expect_exit 2 "mboit: buffer views are ll's and ib's \(view 'heatmap'\)" -- "${r[@]}" --view heatmap
expect_exit 2 "mboit: buffer views are ll's and ib's \(view 'layer'\)" -- "${r[@]}" --view layer:0
expect_exit 2 "--moments must be power4, power6 or trig3" -- "${r[@]}" --moments power8

for moments in power4 power6 trig3; do
    "$oit" render --model /usr/share/assimp/models/OBJ/WusonOBJ.obj --algorithm mboit \
        --moments $moments --size 128x128 --shading flat --out "$work/wuson_$moments.png" --debug >/dev/null \
        || fail "wuson $moments"
    "$oit" compare "$work/wuson_$moments.png" "$reference/wuson_flat.png" --tolerance 2 --max-mismatch 0 \
        || fail "mboit $moments on the one-colour wuson must match the reference"
done

mean() { "$oit" compare "$1" "$2" --tolerance 2 --json | sed -n 's/.*"mean_diff": \([-0-9.e+]*\).*/\1/p'; }
for scene in onion spheres menger; do
    shading=flat; [ "$scene" = onion ] && shading=headlight
    four=$(mean "$images/mboit_$scene.png" "$reference/${scene}_$shading.png")
    six=$(mean "$images/mboit6_$scene.png" "$reference/${scene}_$shading.png")
    [ -n "$four" ] && [ -n "$six" ] || fail "$scene: no figures"
    awk -v a="$six" -v b="$four" 'BEGIN { exit !(a <= b) }' \
        || fail "$scene: power6 mean difference $six > power4's $four"
    echo "ok: $scene: power6 mean difference $six <= power4's $four"
done
echo "mboit checks passed"
