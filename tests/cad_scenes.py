#!/usr/bin/env python3
"""cad_scenes.py OUTDIR: CAD-like scenes whose faces coincide, as OBJ + MTL
(issue "Exact means exact on real assemblies"). Every coincident pair is cut
into different triangles, so the rasterizer's per-triangle depth differs by
rounding where the surfaces are one plane:

  flush_pad       a pad sitting flush on a plate (pad bottom = plate top)
  cover           a box with a cover plate on one side, the cover's inner face
                  a 6x6 grid on the box's 2-triangle side
  discs           two meshing discs (16-gons fanned from different points)
                  sharing both end planes
  sheets_T        two square sheets in one plane tilted by T degrees, one in 2
                  triangles, one a 7x7 grid, overlapping by half
"""
import math
import os
import sys


class Obj:
    def __init__(self):
        self.vertices, self.parts = [], []

    def part(self, name, colour):
        self.parts.append((name, colour, []))

    def vertex(self, p):
        self.vertices.append(p)
        return len(self.vertices)

    def triangle(self, a, b, c):
        self.parts[-1][2].append((a, b, c))

    def quad_grid(self, origin, u, v, n):
        """An n x n grid of quads over origin + s u + t v, two triangles each."""
        index = {}
        for i in range(n + 1):
            for j in range(n + 1):
                index[i, j] = self.vertex(tuple(origin[k] + u[k] * i / n + v[k] * j / n for k in range(3)))
        for i in range(n):
            for j in range(n):
                a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
                self.triangle(a, b, c)
                self.triangle(a, c, d)

    def box(self, lo, hi, grid=1):
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
        for origin, u, v in (((x0, y0, z0), (dx, 0, 0), (0, dy, 0)), ((x0, y0, z1), (dx, 0, 0), (0, dy, 0)),
                             ((x0, y0, z0), (dx, 0, 0), (0, 0, dz)), ((x0, y1, z0), (dx, 0, 0), (0, 0, dz)),
                             ((x0, y0, z0), (0, dy, 0), (0, 0, dz)), ((x1, y0, z0), (0, dy, 0), (0, 0, dz))):
            self.quad_grid(origin, u, v, grid)

    def write(self, path, digits=9):
        base = os.path.splitext(path)[0]
        with open(base + ".mtl", "w") as f:
            for name, colour, _ in self.parts:
                f.write("newmtl %s\nKd %g %g %g\nd 1\n" % ((name,) + colour))
        with open(path, "w") as f:
            f.write("mtllib %s\n" % os.path.basename(base + ".mtl"))
            for p in self.vertices:
                f.write("v %s %s %s\n" % tuple("%.*g" % (digits, c) for c in p))
            for name, _, triangles in self.parts:
                f.write("o %s\nusemtl %s\n" % (name, name))
                for t in triangles:
                    f.write("f %d %d %d\n" % t)


def flush_pad():
    m = Obj()
    m.part("plate", (0.2, 0.5, 0.9))
    m.box((-1.0, -1.0, -0.2), (1.0, 1.0, 0.0))
    m.part("pad", (0.9, 0.4, 0.2))
    m.box((-0.37, -0.53, 0.0), (0.61, 0.29, 0.3), grid=3)
    return m


def cover():
    m = Obj()
    m.part("housing", (0.3, 0.7, 0.4))
    m.box((-0.8, -0.6, -0.5), (0.8, 0.6, 0.5))
    m.part("cover", (0.8, 0.3, 0.6))
    m.box((0.8, -0.6, -0.5), (0.9, 0.6, 0.5), grid=6)
    return m


def disc(m, centre, radius, z0, z1, sides, fan_from, phase):
    cx, cy = centre
    for z in (z0, z1):
        ring = [m.vertex((cx + radius * math.cos(phase + 2 * math.pi * k / sides),
                          cy + radius * math.sin(phase + 2 * math.pi * k / sides), z)) for k in range(sides)]
        for k in range(1, sides - 1):  # a fan from corner fan_from
            a, b, c = ring[fan_from], ring[(fan_from + k) % sides], ring[(fan_from + k + 1) % sides]
            m.triangle(a, b, c)
    lower = [m.vertex((cx + radius * math.cos(phase + 2 * math.pi * k / sides),
                       cy + radius * math.sin(phase + 2 * math.pi * k / sides), z0)) for k in range(sides)]
    upper = [m.vertex((cx + radius * math.cos(phase + 2 * math.pi * k / sides),
                       cy + radius * math.sin(phase + 2 * math.pi * k / sides), z1)) for k in range(sides)]
    for k in range(sides):
        a, b, c, d = lower[k], lower[(k + 1) % sides], upper[(k + 1) % sides], upper[k]
        m.triangle(a, b, c)
        m.triangle(a, c, d)


def discs():
    m = Obj()
    m.part("wheel", (0.9, 0.6, 0.2))
    disc(m, (-0.45, 0.0), 0.6, -0.15, 0.15, 16, 0, 0.0)
    m.part("pinion", (0.3, 0.4, 0.9))
    disc(m, (0.5, 0.05), 0.45, -0.15, 0.15, 16, 5, 0.2)
    return m


def sheets(tilt):
    m = Obj()
    t = math.radians(tilt)

    def rotate(p):  # about x by t, then about y by t / 2
        x, y, z = p
        y, z = y * math.cos(t) - z * math.sin(t), y * math.sin(t) + z * math.cos(t)
        s = t / 2
        return (x * math.cos(s) + z * math.sin(s), y, -x * math.sin(s) + z * math.cos(s))

    m.part("coarse", (0.9, 0.3, 0.3))
    a, b, c, d = (m.vertex(rotate(p)) for p in ((-1, -1, 0), (0.5, -1, 0), (0.5, 0.5, 0), (-1, 0.5, 0)))
    m.triangle(a, b, c)
    m.triangle(a, c, d)
    m.part("fine", (0.2, 0.6, 0.9))
    n = 7
    index = {}
    for i in range(n + 1):
        for j in range(n + 1):
            index[i, j] = m.vertex(rotate((-0.5 + 1.5 * i / n, -0.5 + 1.5 * j / n, 0)))
    for i in range(n):
        for j in range(n):
            p, q, r, s = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            m.triangle(p, q, s)
            m.triangle(q, r, s)
    return m


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    scenes = {"flush_pad": flush_pad(), "cover": cover(), "discs": discs()}
    for tilt in (0, 17, 35, 61):
        scenes["sheets_%d" % tilt] = sheets(tilt)
    for name, model in scenes.items():
        model.write(os.path.join(out, name + ".obj"))
    print(" ".join(scenes))


if __name__ == "__main__":
    main()
