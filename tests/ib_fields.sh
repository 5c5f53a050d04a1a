#!/usr/bin/env bash
# ib_fields.sh OIT WORK SCENES: transparency fields on onion.
# Initial values: the front sphere's silhouette fragments (fewer than four
# neighbours) have alpha = beta = 1, its middle 0; on layer 1 the outer
# sphere's back, just outside the third sphere's contour, has gamma = 1.
# Spreading: max-diffusion with lambda_beta = 0.1 for 5 iterations gives
# beta = 1 - 0.1 k at k pixels from the silhouette, 0 beyond 5.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
onion="$scenes/onion.obj"
# where the layers are: the first (two) fragments, opaque (sphere colours are never white)
for layer in 0 1; do
    ib_render "$work/initial_$layer.png" --model "$onion" --view fields:$layer \
        --diffusion-iterations 0 --blur-iterations 0
    ib_render "$work/where_$layer.png" --model "$onion" --view peel-limit:$((layer + 1)) --alpha 1 \
        --shading flat
done
ib_render "$work/spread.png" --model "$onion" --view fields --fields beta --diffusion-iterations 5 \
    --lambda-beta 0.1 --blur-iterations 0 
ib_render "$work/blurred.png" --model "$onion" --view fields --fields beta --diffusion-iterations 5 \
    --lambda-beta 0.1 --blur-iterations 1 
ib_py '
import json, sys
from ib_png import read_png, pixel
work = sys.argv[1]
image = read_png(f"{work}/initial_0.png")
w, h, _ = image
y = h // 2
where = read_png(f"{work}/where_0.png")
row = [pixel(image, x, y) for x in range(w)]
inside = [x for x in range(w) if pixel(where, x, y) != (255, 255, 255)]
left = inside[0]
print("layer 0, centre row from the left silhouette:", row[left:left + 4], "centre:", row[w // 2])
assert row[left][:2] == (255, 255), "silhouette: alpha = beta = 1"
while row[left + 1][:2] == (255, 255):
    left += 1   # the last silhouette fragment: beta spreads from here
assert row[w // 2] == (0, 0, 0), "middle of the front sphere: all fields 0"
image1 = read_png(f"{work}/initial_1.png")
where1 = read_png(f"{work}/where_1.png")
gamma = [x for x in range(w) if pixel(image1, x, y)[2] == 255 and pixel(where1, x, y) != (255, 255, 255)]
print("layer 1, gamma = 1 at x =", gamma)
assert any(x < w // 2 for x in gamma) and any(x > w // 2 for x in gamma), "halo on both sides"
assert pixel(image1, w // 2, y)[2] == 0
spread = read_png(f"{work}/spread.png")
beta = [pixel(spread, left + k, y)[1] for k in range(10)]
want = [round(255 * max(0.0, 1 - 0.1 * k)) if k <= 5 else 0 for k in range(10)]
print("beta from the silhouette:", beta, "want", want)
assert all(abs(b - c) <= 2 for b, c in zip(beta, want)), "max-diffusion: beta = 1 - lambda k"
blurred = read_png(f"{work}/blurred.png")
beta_blurred = [pixel(blurred, left + k, y)[1] for k in range(10)]
print("after one blur:", beta_blurred)
assert beta_blurred[0] == 255, "fixed values stay"
assert beta_blurred[6] > 0, "the blur spreads beta past the diffusion front"
' "$work"
echo ok
