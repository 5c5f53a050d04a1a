#!/usr/bin/env python3
"""many_parts.py OUT.obj [PARTS]: a model with more parts than the old per-part
opacity limit of 1024 (tests/many_parts.sh). PARTS (default 1331) squares, one
component each (g/usemtl part_I, component index I), on a 37-wide grid; each
square overlaps its neighbours and sits at its own depth (I mod 5), so
neighbours overlap at distinct depths. Parts 1200 and 1300 are large squares in
front, overlapping each other and the grid: changing their opacity changes a
large share of the image, so a GPU that ignored parts past 1024 fails the
comparison with the reference by far."""
import os
import sys

out = sys.argv[1]
parts = int(sys.argv[2]) if len(sys.argv) > 2 else 1331
columns = 37
big = {1200: (2.0, 2.0, 22.0, 1.5), 1300: (14.0, 12.0, 34.0, 2.5)}  # x0, y0, x1 (square), z

mtl = os.path.splitext(out)[0] + ".mtl"
with open(mtl, "w") as m:
    for i in range(parts):
        r = 0.2 + 0.6 * ((i * 37) % 101) / 100.0
        g = 0.2 + 0.6 * ((i * 59) % 103) / 102.0
        b = 0.2 + 0.6 * ((i * 83) % 107) / 106.0
        if i in big:
            r, g, b = (0.9, 0.1, 0.1) if i == 1200 else (0.1, 0.2, 0.9)
        m.write(f"newmtl part_{i}\nKd {r:.4f} {g:.4f} {b:.4f}\nd 1\nillum 1\n\n")

with open(out, "w") as f:
    f.write(f"# many_parts.py: {parts} parts\nmtllib {os.path.basename(mtl)}\n")
    vertex = 0
    for i in range(parts):
        if i in big:
            x0, y0, x1, z = big[i]
            x1, y1 = x1, y0 + (x1 - x0)
        else:
            cx, cy = i % columns, i // columns
            x0, y0, x1, y1 = cx - 0.2, cy - 0.2, cx + 1.2, cy + 1.2
            z = -0.05 * (i % 5)
        f.write(f"g part_{i}\nusemtl part_{i}\n")
        for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1)):
            f.write(f"v {x:.3f} {y:.3f} {z:.3f}\n")
        a = vertex + 1
        f.write(f"f {a} {a + 1} {a + 2}\nf {a} {a + 2} {a + 3}\n")
        vertex += 4
