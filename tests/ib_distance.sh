#!/usr/bin/env bash
# ib_distance.sh OIT WORK SCENES: distance along the ray on onion, whose
# spheres have radii 1/4, 2/4, 3/4, 1: the ray through the centre meets them
# at eye depths D -+ r, so the distances are known exactly.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
onion="$scenes/onion.obj"
for layer in 0 1 2 3 4 5 6 7; do
    ib_render "$work/adjacent_$layer.png" --model "$onion" --view distance:$layer --focus-region 1
    ib_render "$work/skip_$layer.png" --model "$onion" --view distance:$layer --focus-region 1 --distance skip:2
    ib_render "$work/far_$layer.png" --model "$onion" --view distance:$layer --distance far
    # the modulated opacity, composited alone over the white background
    ib_render "$work/opacity_$layer.png" --model "$onion" --modulation distance --focus-region 0.5 \
        --view layer:$layer --shading flat
done
"$oit" info --model "$onion" --json >"$work/info.json" || fail "info"
ib_py '
import json, sys
from ib_png import read_png, pixel
work = sys.argv[1]
radii = [1.0, 0.75, 0.5, 0.25]                      # front to back along the centre ray
depths = [-r for r in radii] + [r for r in reversed(radii)]   # relative to the centre
def grey(name, layer):
    return pixel(read_png(f"{work}/{name}_{layer}.png"), 64, 64)[0]
def check(name, expected):
    got = [grey(name, layer) for layer in range(8)]
    want = [round(255 * min(e, 1.0)) for e in expected]
    print(f"{name}: got {got}, want {want}")
    assert all(abs(g - w) <= 3 for g, w in zip(got, want)), name
n = len(depths)
check("adjacent", [depths[i + 1] - depths[i] if i + 1 < n else 0.0 for i in range(n)])
check("skip", [depths[min(i + 2, n - 1)] - depths[i] for i in range(n)])
# auto normalisation: the largest distance in the frame is the outer sphere diameter (2)
check("far", [(depths[-1] - depths[i]) / 2.0 for i in range(n)])
# opacity = distance / 0.5: layers 0..2 half transparent, layer 3 opaque
parts = {p["name"]: p["colour"] for p in json.load(open(f"{work}/info.json"))["parts"]}
colour = [parts["sphere_4"], parts["sphere_3"], parts["sphere_2"], parts["sphere_1"]]
colour = colour + list(reversed(colour))
for layer in range(8):
    d = depths[layer + 1] - depths[layer] if layer + 1 < n else 0.0
    alpha = min(d / 0.5, 1.0)
    want = [round(255 * (alpha * c + (1 - alpha))) for c in colour[layer]]
    got = pixel(read_png(f"{work}/opacity_{layer}.png"), 64, 64)
    print(f"layer {layer}: opacity {alpha}, got {got}, want {want}")
    assert all(abs(g - w) <= 3 for g, w in zip(got, want)), layer
' "$work"
echo ok
