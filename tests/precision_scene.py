#!/usr/bin/env python3
"""precision_scene.py OUT.obj: plane pairs 1e-3 apart about 800 units in front
of an eye at the origin looking down -z (issue "Exact means exact", part 2).
Each pair is two squares, tilted differently per pair; in every pair the
farther square comes first in the file (the lower triangle indices), so an
algorithm whose depths cannot tell them apart orders them by triangle and gets
every pair backwards. With near 0.01 and far 1000, window depths of a pair
differ by about 2e-11: the same float."""
import math
import sys

out = sys.argv[1]
pairs = [  # centre x, y, distance, tilt about x, tilt about y (degrees), colours far / near
    (-180, 120, 800.0, 10, 25, (0.9, 0.2, 0.2), (0.2, 0.4, 0.9)),
    (150, 130, 810.0, -20, 5, (0.2, 0.8, 0.3), (0.9, 0.7, 0.1)),
    (-140, -150, 790.0, 35, -15, (0.8, 0.3, 0.8), (0.1, 0.8, 0.8)),
    (160, -120, 805.0, 0, 0, (0.6, 0.6, 0.6), (0.9, 0.4, 0.1)),
]
gap = 1e-3
half = 140.0
vertices, faces, materials = [], [], []


def rotate(p, ax, ay):
    x, y, z = p
    a, b = math.radians(ax), math.radians(ay)
    y, z = y * math.cos(a) - z * math.sin(a), y * math.sin(a) + z * math.cos(a)
    x, z = x * math.cos(b) + z * math.sin(b), -x * math.sin(b) + z * math.cos(b)
    return x, y, z


for k, (cx, cy, distance, ax, ay, far_colour, near_colour) in enumerate(pairs):
    for which, offset, colour in (("far", -gap / 2, far_colour), ("near", gap / 2, near_colour)):
        name = "pair%d_%s" % (k, which)
        materials.append((name, colour))
        base = len(vertices)
        for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            x, y, z = rotate((sx * half, sy * half, offset), ax, ay)
            vertices.append((cx + x, cy + y, -distance + z))
        faces.append((name, [(base + 1, base + 2, base + 3), (base + 1, base + 3, base + 4)]))
mtl = out[:-4] + ".mtl"
with open(mtl, "w") as f:
    for name, colour in materials:
        f.write("newmtl %s\nKd %g %g %g\nd 1\n" % ((name,) + colour))
with open(out, "w") as f:
    f.write("mtllib %s\n" % mtl.rsplit("/", 1)[-1])
    for v in vertices:
        f.write("v %.9g %.9g %.9g\n" % v)
    for name, triangles in faces:
        f.write("o %s\nusemtl %s\n" % (name, name))
        for t in triangles:
            f.write("f %d %d %d\n" % t)
