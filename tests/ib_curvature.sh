#!/usr/bin/env bash
# ib_curvature.sh OIT WORK SCENES: curvature where the truth is known.
# coplanar (squares in z = 0): every fragment's curvature is exactly 0.
# onion: the front sphere's curvature is nearly constant in the middle of the
# image (it rises towards the rim, where a pixel step spans more of the
# surface); with diagonals (8 neighbours) the mean grows by about (1 + sqrt 2) / 2.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
# background blue: the view's grey values never look like it
for layer in 0 1; do
    ib_render "$work/plane_$layer.png" --model "$scenes/coplanar.obj" --view curvature:$layer \
        --curvature-effect 1000 --curvature-neighbours 8 --background 0,0,1
done
for n in 4 8; do
    ib_render "$work/sphere_$n.png" --model "$scenes/onion.obj" --view curvature \
        --curvature-effect 30 --curvature-neighbours $n --background 0,0,1
done
ib_py '
import sys, statistics
from ib_png import read_png, pixel
work = sys.argv[1]
for layer in (0, 1):
    image = read_png(f"{work}/plane_{layer}.png")
    values = [pixel(image, x, y) for y in range(image[1]) for x in range(image[0])]
    surface = [v for v in values if v != (0, 0, 255)]
    print(f"plane layer {layer}: {len(surface)} fragments, curvature values {sorted(set(surface))[:5]}")
    assert len(surface) > 1000, "the plane must cover the image"
    assert all(v == (0, 0, 0) for v in surface), "a plane must have zero curvature"
medians = {}
for n in (4, 8):
    image = read_png(f"{work}/sphere_{n}.png")
    w, h, _ = image
    row = [x for x in range(w) if pixel(image, x, h // 2) != (0, 0, 255)]
    radius = (row[-1] - row[0] + 1) / 2
    centre = (w - 1) / 2
    inner = [pixel(image, x, y)[0] for y in range(h) for x in range(w)
             if (x - centre) ** 2 + (y - centre) ** 2 < (0.5 * radius) ** 2]
    medians[n] = statistics.median(inner)
    spread = (max(inner) - min(inner)) / medians[n]
    print(f"sphere, {n} neighbours: median {medians[n]}, range {min(inner)}..{max(inner)} ({spread:.2f} of the median)")
    assert medians[n] > 20, "a sphere must have curvature"
    assert spread < 0.3, "a sphere must have nearly constant curvature"
ratio = medians[8] / medians[4]
print(f"8 / 4 neighbours: {ratio:.3f} (expected about {(1 + 2 ** 0.5) / 2:.3f})")
assert 1.1 < ratio < 1.3, ratio
' "$work"
echo ok
