#!/usr/bin/env python3
"""coverage_scene.py OUT.obj: sub-pixel triangles for the coverage rule (issue
"Exact anywhere and at any scale", part 3), one per 4x4-pixel cell of a 128x128
image, so no two share a pixel. Positions are integers in 1/1024 pixel: the
test's modelview (x / 65536 - 1) turns them into NDC exactly, in float as in
double, so the GL and the reference snap the same window positions and differ
only by their rules. Kinds, in turn:

  tiny      three vertices within a 2x2-pixel box, anywhere on the 1/1024 grid
  ties      on the 1/512 grid: half the coordinates lie half-way between two
            1/256 steps (the snap's rounding ties)
  centres   on the 1/256 grid: edges through pixel centres (the fill rule's ties)
  sliver    0.5-2.5 px long, 0.01-0.4 px wide, any direction
  near      about 0.3 px wide, one edge passing -4..4 / 1024 px from a pixel
            centre, any direction
  axis      right triangles whose legs lie on pixel-centre rows and columns

Half the triangles are wound clockwise. Prints how many coordinates lie on a
rounding tie and how many triangles have a pixel centre exactly on an edge,
and fails if either is 0 (the scene would not test the rules)."""
import math
import random
import sys

UNIT = 1024  # positions per pixel
SIZE = 128   # image side in pixels
CELL = 4     # pixels per cell side
KINDS = ("tiny", "ties", "centres", "sliver", "near", "axis")


def grid(value, step):
    """value (pixels) to the nearest multiple of 1/step pixel, in 1/UNIT units."""
    return round(value * step) * (UNIT // step)


def triangle(kind, cx, cy, rng):
    """Three (x, y) in 1/UNIT pixel, within 1.5 px of the cell centre (cx, cy)."""
    if kind in ("tiny", "ties", "centres"):
        step = {"tiny": UNIT, "ties": 512, "centres": 256}[kind]
        ox, oy = cx + rng.uniform(-0.5, 0.5), cy + rng.uniform(-0.5, 0.5)
        return [(grid(ox + rng.uniform(-1, 1), step), grid(oy + rng.uniform(-1, 1), step)) for _ in range(3)]
    if kind == "axis":
        # the right angle on a pixel centre, legs along its row and column
        px, py = math.floor(cx) + 0.5 + rng.choice((-1, 0)), math.floor(cy) + 0.5 + rng.choice((-1, 0))
        sx, sy = rng.choice((-1, 1)), rng.choice((-1, 1))
        lx, ly = rng.randint(2, 4) / 4, rng.randint(2, 4) / 4
        return [(grid(px, UNIT), grid(py, UNIT)), (grid(px + sx * lx, UNIT), grid(py, UNIT)),
                (grid(px, UNIT), grid(py + sy * ly, UNIT))]
    angle = rng.uniform(0, 2 * math.pi)
    ux, uy = math.cos(angle), math.sin(angle)  # along the edge
    nx, ny = -uy, ux                           # its normal, towards the third vertex
    if kind == "sliver":
        length, width = rng.uniform(0.5, 2.5), rng.uniform(0.01, 0.4)
        mx, my = cx + rng.uniform(-0.3, 0.3), cy + rng.uniform(-0.3, 0.3)
    else:  # near: the edge passes d / UNIT px from the pixel centre nearest the cell centre
        length, width = rng.uniform(0.6, 1.4), 0.3
        d = rng.randint(-4, 4) / UNIT
        mx, my = math.floor(cx) + 0.5 - nx * d, math.floor(cy) + 0.5 - ny * d
    along = rng.uniform(-0.3, 0.3) * length
    a = (mx - ux * length / 2, my - uy * length / 2)
    b = (mx + ux * length / 2, my + uy * length / 2)
    c = (mx + ux * along + nx * width, my + uy * along + ny * width)
    return [(grid(x, UNIT), grid(y, UNIT)) for x, y in (a, b, c)]


def centre_on_edge(points):
    """True if a pixel centre lies exactly on an edge of the triangle (all on the 1/256 grid)."""
    if any(v % (UNIT // 256) for p in points for v in p):
        return False  # off the 1/256 grid: snapping moves it, not counted
    half = UNIT // 2
    for i in range(3):
        (ax, ay), (bx, by) = points[i], points[(i + 1) % 3]
        for x in range(min(ax, bx) // UNIT, max(ax, bx) // UNIT + 1):
            for y in range(min(ay, by) // UNIT, max(ay, by) // UNIT + 1):
                px, py = x * UNIT + half, y * UNIT + half
                if ((bx - ax) * (py - ay) - (by - ay) * (px - ax) == 0
                        and min(ax, bx) <= px <= max(ax, bx) and min(ay, by) <= py <= max(ay, by)):
                    return True
    return False


def main():
    out = sys.argv[1]
    rng = random.Random(23)
    triangles = []
    cells = SIZE // CELL
    for j in range(cells):
        for i in range(cells):
            kind = KINDS[(j * cells + i) % len(KINDS)]
            points = triangle(kind, (i + 0.5) * CELL, (j + 0.5) * CELL, rng)
            if rng.random() < 0.5:
                points.reverse()
            triangles.append(points)
    ties = sum(1 for t in triangles for p in t for v in p if v % (UNIT // 256) == UNIT // 512)
    on_edge = sum(1 for t in triangles if centre_on_edge(t))
    with open(out, "w") as f:
        f.write("# coverage_scene.py: x, y in 1/%d pixel of a %dx%d image\n" % (UNIT, SIZE, SIZE))
        for t in triangles:
            for x, y in t:
                f.write("v %d %d 0\n" % (x, y))
        for k in range(len(triangles)):
            f.write("f %d %d %d\n" % (3 * k + 1, 3 * k + 2, 3 * k + 3))
    print("%d triangles, %d coordinates on a rounding tie, %d triangles with a pixel centre on an edge"
          % (len(triangles), ties, on_edge))
    if ties == 0 or on_edge == 0:
        sys.exit("coverage_scene.py: the scene has no ties to test")


main()
