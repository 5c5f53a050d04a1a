#!/usr/bin/env bash
# adaptive_checks.sh OIT WORKDIR SCENES REFERENCE_DIR: adaptive beyond its image bounds.
#  - exact where no list is longer than k: on cyclic, gearbox and menger (128x128, flat)
#    at k = the scene's longest list (read from --json): within 2/255 of the reference
#    on 99.9% of the pixels (tighter than the exact algorithms' 1%, so that it can tell:
#    at a k shorter than the longest list, the same comparison must fail: k = 1 on
#    cyclic, whose lists hold 2, and the default 8 on the deep two). (k = longest - 1
#    is no test on the deep scenes: the node it loses is one at the back, and the image
#    does not change; on cyclic the one node left must stand for both fragments.)
#  - the error does not grow with k: on menger (lists up to 20) the RMSE against the
#    reference at k = 1, 2, 4, 8, 16 never rises from one k to the next;
#  - refusals: one line and exit 2 (or 3 for the memory budget).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 reference=$4
rm -rf "$work"; mkdir -p "$work"

render() { # SCENE K OUT [render args...]: adaptive at 128x128, flat
    local scene=$1 k=$2 out=$3; shift 3
    "$oit" render --model "$scenes/$scene.obj" --size 128x128 --shading flat --algorithm adaptive \
        --layers "$k" --out "$out" "$@"
}
rmse() { # IMAGE SCENE: the RMSE (0..255) against the scene's reference, from compare's PSNR
    "$oit" compare "$1" "$reference/$2_flat.png" --tolerance 255 | sed -n 's/.*PSNR \([0-9.inf]*\) dB.*/\1/p' |
        awk '{ if ($1 == "inf") print "0.0000"; else printf "%.4f\n", 255 * 10 ^ (-$1 / 20) }'
}

for case in cyclic:1 gearbox:8 menger:8; do
    scene=${case%:*} short=${case#*:}
    longest=$(render $scene "$short" "$work/${scene}_short.png" --json | sed -n 's/.*"max_list": \([0-9]*\).*/\1/p')
    [ -n "$longest" ] && [ "$longest" -gt "$short" ] || fail "$scene: no list longer than $short in --json ($longest)"
    render $scene "$longest" "$work/${scene}_longest.png" >/dev/null || fail "render $scene k=$longest"
    "$oit" compare "$work/${scene}_longest.png" "$reference/${scene}_flat.png" --tolerance 2 --max-mismatch 0.1 \
        || fail "$scene: k = $longest (its longest list) is not the reference's image"
    "$oit" compare "$work/${scene}_short.png" "$reference/${scene}_flat.png" --tolerance 2 --max-mismatch 0.1 &&
        fail "$scene: k = $short, shorter than its longest list ($longest), passes as exact: the check cannot tell"
done

last=1000
for k in 1 2 4 8 16; do
    if [ $k -eq 8 ]; then # rendered above
        cp "$work/menger_short.png" "$work/menger_k8.png"
    else
        render menger $k "$work/menger_k$k.png" >/dev/null || fail "render menger k=$k"
    fi
    e=$(rmse "$work/menger_k$k.png" menger)
    echo "menger k=$k: rmse $e"
    awk -v a="$e" -v b="$last" 'BEGIN { exit !(a <= b) }' || fail "menger: rmse at k=$k ($e) is above the last ($last)"
    last=$e
done

r=("$oit" render --model "$scenes/gearbox.obj" --size 128x128 --algorithm adaptive --out "$work/x.png")
expect_exit 2 "--layers must be a whole number from 1 to 64" -- "${r[@]}" --layers 65
expect_exit 2 "--layers must be a whole number from 1 to 64" -- "${r[@]}" --layers 0
expect_exit 2 "adaptive: buffer views are ll's and ib's" -- "${r[@]}" --view heatmap
expect_exit 2 "adaptive: the distance modulation needs" -- "${r[@]}" --modulation distance
expect_exit 2 "adaptive: opacity modulation 'curvature' needs surface neighbours" -- "${r[@]}" --modulation curvature
expect_exit 3 "adaptive: the frame needs [0-9]+ fragments .*over the --max-memory budget of 1.0 MB" -- \
    "$oit" render --model "$scenes/menger.obj" --size 256x256 --algorithm adaptive --max-memory 1 --out "$work/x.png"
echo "adaptive_checks: ok"
