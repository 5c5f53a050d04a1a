#!/usr/bin/env python3
"""deep_pixel.py OUT.obj LAYERS: LAYERS triangles stacked along z over the
model's centre, so one pixel there has a list of LAYERS fragments
(tests/counter_limits.sh: ib's 16-bit layer indices). The triangles form a
chain (triangle k uses vertices k, k+1, k+2; vertex k sits on corner k mod 3
of one large triangle at z = k * DZ), so the file stays small. Part "layers"
holds triangles 0..LAYERS-2, part "last" the nearest one: --hide last gives
LAYERS - 1. Drawn back to front, so the lists (newest first) come out front to
back and ib's insertion sort is linear."""
import sys

out, layers = sys.argv[1], int(sys.argv[2])
corners = ((-3.0, -2.0), (3.0, -2.0), (0.0, 3.0))  # contains the bounding box's centre
dz = 1.0 / layers
with open(out, "w") as f:
    f.write(f"# deep_pixel.py: {layers} stacked triangles\n")
    for k in range(layers + 2):
        x, y = corners[k % 3]
        f.write(f"v {x} {y} {k * dz:.9f}\n")
    f.write("g layers\n")
    for k in range(layers):
        if k == layers - 1:
            f.write("g last\n")
        f.write(f"f {k + 1} {k + 2} {k + 3}\n")
