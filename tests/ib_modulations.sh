#!/usr/bin/env bash
# ib_modulations.sh OIT WORK MODEL NAME: every modulation and view on one model.
# Each must run, report only the stages it needs (passes that are off do not
# run), change the image (modulations) or show something other than the
# background (views), stay within 64 bytes per fragment and 12 per pixel, and
# give the same image on both back ends.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 model=$3 name=$4
rm -rf "$work"; mkdir -p "$work"
ib_render "$work/none.png" --model "$model"
"$oit" render --model "$model" --algorithm ll --size 128x128 --out "$work/ll.png" >/dev/null || fail "ll render"
"$oit" compare "$work/none.png" "$work/ll.png" --tolerance 2 --max-mismatch 1 \
    || fail "$name: ib without modulation must match ll"
for modulation in curvature distance dist-curv fields edges; do
    ib_render "$work/$modulation.png" --model "$model" --modulation $modulation
    "$oit" compare "$work/$modulation.png" "$work/none.png" --tolerance 2 --max-mismatch 0.5 \
        && fail "$name: --modulation $modulation does not change the image"
done
ib_render "$work/fields_osmesa.png" --model "$model" --modulation fields --backend osmesa
"$oit" compare "$work/fields_osmesa.png" "$work/fields.png" || fail "$name: back ends differ"
for view in heatmap peel-limit:1 layer:1 neighbours curvature distance fields; do
    ib_render "$work/view_${view%%:*}.png" --model "$model" --view $view
done
ib_py '
import json, sys
from ib_png import read_png, pixel
work, name = sys.argv[1], sys.argv[2]
needs = {"none": set(), "curvature": {"curvature_distance"}, "distance": {"curvature_distance"},
         "dist-curv": {"curvature_distance"}, "fields": {"fields", "diffusion", "blur"}, "edges": set()}
# the default search is welded: its epsilon fallback is a stage of its own
construction = ["clear", "fill", "sort", "neighbours", "neighbours_epsilon", "neighbour_stats"]
n = len(construction)
for modulation, extra in needs.items():
    d = json.load(open(f"{work}/{modulation}.json"))
    stages = [s["name"] for s in d["stages"]]
    assert stages[:n] == construction and stages[-1] == "compose", (modulation, stages)
    assert set(stages[n:-1]) == extra, (modulation, stages)
    # per pixel: heads, counts and output 12, the tile list 4 per 8x8 tile
    assert d["bytes_per_fragment"] <= 64 and d["bytes_per_pixel"] <= 12 + 4 / 64, d
    assert 0 <= d["psi"] <= 1 and d["mean_list"] >= 1 and sum(d["list_histogram"]) == 128 * 128, d
    print(name, modulation, "stages", stages[n:-1], d["fragments"], "fragments, gpu ms", d["gpu_ms"])
for view in ("heatmap", "peel-limit", "layer", "neighbours", "curvature", "distance", "fields"):
    image = read_png(f"{work}/view_{view}.png")
    shown = sum(1 for y in range(image[1]) for x in range(image[0]) if pixel(image, x, y) != (255, 255, 255))
    print(f"{name} view {view}: {shown} pixels shown")
    assert shown > 100, view
' "$work" "$name"
echo ok
