#!/usr/bin/env bash
# ib_neighbours.sh OIT WORK SCENES: neighbour quality where the truth is known.
# On onion (4 nested UV spheres, poles towards the camera, one seam meridian
# whose vertices are duplicated) the front sphere's interior fragments must
# have four neighbours, links must be symmetric and stay on their sphere.
# index cannot cross the seam (duplicated vertices), welded and epsilon can.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
for search in index welded epsilon; do
    ib_render "$work/stats_$search.png" --model "$scenes/onion.obj" --neighbours $search
    # alpha 1: each pixel shows its front fragment, coloured by its neighbour count
    ib_render "$work/view_$search.png" --model "$scenes/onion.obj" --neighbours $search \
        --view neighbours --alpha 1 --shading flat
done
ib_py '
import json, sys
from ib_png import read_png, pixel
work = sys.argv[1]
stats = {s: json.load(open(f"{work}/stats_{s}.json")) for s in ("index", "welded", "epsilon")}
for s, d in stats.items():
    print(s, {k: d[k] for k in ("fragments", "neighbours_four_share", "neighbours_symmetric_share",
                                "neighbours_same_component_share", "bytes_per_fragment")})
    assert d["neighbours_same_component_share"] == 1.0, (s, "links must stay on their sphere")
    assert d["neighbours_symmetric_share"] >= 0.99, (s, "links must be symmetric")
    assert d["neighbours_four_share"] >= 0.85, (s, "most fragments must have four neighbours")
    # per pixel: heads, counts and output 12, the tile list 4 per 8x8 tile
    assert d["bytes_per_fragment"] <= 64 and d["bytes_per_pixel"] <= 12 + 4 / 64, d
def interior_not_four(search):
    image = read_png(f"{work}/view_{search}.png")
    w, h, _ = image
    cx = cy = (w - 1) / 2
    bg = pixel(image, 0, 0)
    row = [x for x in range(w) if pixel(image, x, h // 2) != bg]
    radius = (row[-1] - row[0] + 1) / 2
    bad = 0
    for y in range(h):
        for x in range(w):
            if (x - cx) ** 2 + (y - cy) ** 2 < (0.85 * radius) ** 2 and pixel(image, x, y) != (0, 204, 0):
                bad += 1
    return bad
bad = {s: interior_not_four(s) for s in stats}
print("interior front pixels without four neighbours:", bad)
assert bad["welded"] == 0 and bad["epsilon"] == 0, bad
assert bad["index"] > 0, "index should lose neighbours across the seam (duplicated vertices)"
assert stats["index"]["neighbours_four_share"] < stats["welded"]["neighbours_four_share"], stats
' "$work"
echo "ok"
