#!/usr/bin/env python3
"""caps_scene.py OUT.obj: the section caps test's scene (issue 28; tests/caps.cmake,
docs/sections.md "Caps"). Boxes with outward-wound faces, each face split in
two triangles, every part translucent and its own colour:

  block  [-1, 1]^3, closed
  inner  [-0.4, 0.4]^3, closed, inside the block's volume
  bar    x [1.3, 1.7], y [-1, 1], z [-0.3, 0.3], closed
  tray   x [-1.8, -1.3], y [-1, 1], z [-0.5, 0.5] missing its top (+y): open

A plane z = D for -0.3 < D < 0.3 cuts all four; its cross-sections have the
areas 4 (block), 0.64 (inner), 0.8 (bar) and the tray's outline."""
import sys

PARTS = [
    # name, lo, hi, colour, opacity, faces left out
    ("block", (-1.0, -1.0, -1.0), (1.0, 1.0, 1.0), (0.9, 0.2, 0.15), 0.45, ()),
    ("inner", (-0.4, -0.4, -0.4), (0.4, 0.4, 0.4), (0.1, 0.8, 0.2), 0.6, ()),
    ("bar", (1.3, -1.0, -0.3), (1.7, 1.0, 0.3), (0.15, 0.3, 0.95), 0.5, ()),
    ("tray", (-1.8, -1.0, -0.5), (-1.3, 1.0, 0.5), (0.95, 0.85, 0.1), 0.5, ("+y",)),
]

# faces: (name, axis, side, the other two axes in counter-clockwise order seen from outside)
FACES = [("+x", 0, 1, 1, 2), ("-x", 0, 0, 2, 1), ("+y", 1, 1, 2, 0), ("-y", 1, 0, 0, 2),
         ("+z", 2, 1, 0, 1), ("-z", 2, 0, 1, 0)]


def main():
    out = sys.argv[1]
    mtl = out[:-4] + ".mtl"
    vertices, lines = [], []
    with open(mtl, "w") as f:
        for name, _, _, colour, opacity, _ in PARTS:
            f.write("newmtl %s\nKd %g %g %g\nd %g\n\n" % ((name,) + colour + (opacity,)))
    for name, lo, hi, _, _, left_out in PARTS:
        lines.append("g %s\nusemtl %s" % (name, name))
        for face, axis, side, a, b in FACES:
            if face in left_out:
                continue
            corners = []
            for ua, ub in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[a] = hi[a] if ua else lo[a]
                p[b] = hi[b] if ub else lo[b]
                vertices.append(p)
                corners.append(len(vertices))
            lines.append("f %d %d %d" % (corners[0], corners[1], corners[2]))
            lines.append("f %d %d %d" % (corners[0], corners[2], corners[3]))
    with open(out, "w") as f:
        f.write("mtllib %s\n" % mtl.split("/")[-1])
        for p in vertices:
            f.write("v %r %r %r\n" % tuple(p))
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
