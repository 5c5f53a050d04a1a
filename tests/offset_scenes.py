#!/usr/bin/env python3
"""offset_scenes.py OUTDIR [SIZE]: one CAD-like assembly with coincident faces,
and two crossing cylinders, placed far from the origin (issue "Exact anywhere
and at any scale"): the same scene, rotated, at offsets 0, 1e3, 1e4 and 1e5
along (1, 0.7, -0.4), as parts drawn in millimetres lie in a large assembly.

  assembly_OFFSET.obj  a plate; a pad flush on it; a housing with a cover
                       plate on one side (the cover's inner face a 2x2 grid
                       on the housing's 2-triangle side); two 12-sided discs
                       standing on the plate, overlapping, fanned from
                       different corners, sharing both end planes; a
                       label: one small triangle on the plate
  crossing_OFFSET.obj  two cylinders crossing at right angles (silhouettes)

Every distinct plane of the assembly is at least 0.05 from every vertex of a
face on another plane near it (the model is about 2 units across), more than
the coplanar tolerance at 1e5 (two float ulps of 1e5: 0.0156) and the float
input's rounding there (under 0.007 off a plane), so the planes are the same
at every offset.

For each scene and offset it writes NAME.camera: the --modelview and
--projection rows (SIZE square, 96 by default) of one view computed in double
from the exact centre, so that every offset is seen from the same relative
camera, and NAME.exact: the exact (double) positions, for measuring how far
the file's float32 input moves them."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cad_scenes import Obj, disc  # noqa: E402

OFFSETS = {"0": 0.0, "1e3": 1e3, "1e4": 1e4, "1e5": 1e5}
DIRECTION = (1.0, 0.7, -0.4)
TILT_X, TILT_Y = 23.0, 37.0  # the rotation, degrees: about x, then about y
AZIMUTH, ELEVATION = 30.0, 25.0  # the view


def assembly():
    m = Obj()
    m.part("plate", (0.2, 0.5, 0.9))
    m.box((-1.0, -1.0, -0.2), (1.0, 1.0, 0.0))
    m.part("pad", (0.9, 0.4, 0.2))
    m.box((-0.5, -0.6, 0.0), (0.3, 0.1, 0.3), grid=3)
    m.part("housing", (0.3, 0.7, 0.4))
    m.box((0.45, 0.15, 0.0), (0.9, 0.9, 0.4))
    m.part("cover", (0.8, 0.3, 0.6))
    m.box((0.9, 0.15, 0.0), (1.0, 0.9, 0.4), grid=2)
    m.part("wheel", (0.9, 0.6, 0.2))
    disc(m, (-0.5, 0.5), 0.3, 0.0, 0.2, 12, 0, 0.1)
    m.part("pinion", (0.3, 0.4, 0.9))
    disc(m, (-0.05, 0.55), 0.25, 0.0, 0.2, 12, 5, 0.2)
    # one small triangle on the plate: far out its own normal is too uncertain
    # to look its plane up by, so it must find the plate's by where it is
    m.part("label", (0.95, 0.95, 0.3))
    m.triangle(m.vertex((0.45, -0.65, 0.0)), m.vertex((0.62, -0.6, 0.0)), m.vertex((0.5, -0.48, 0.0)))
    return m


def cylinder(m, axis, radius, length, segments):
    """A closed cylinder about the origin along axis (0: x, 1: y, 2: z)."""
    def point(k, t):
        a = 2 * math.pi * k / segments
        p = [radius * math.cos(a), radius * math.sin(a)]
        p.insert(axis, t)
        return tuple(p)
    ends = []
    for t in (-length / 2, length / 2):
        centre = [0.0, 0.0]
        centre.insert(axis, t)
        ends.append((m.vertex(tuple(centre)), [m.vertex(point(k, t)) for k in range(segments)]))
    for k in range(segments):
        k1 = (k + 1) % segments
        (c0, r0), (c1, r1) = ends
        m.triangle(c0, r0[k1], r0[k])
        m.triangle(c1, r1[k], r1[k1])
        m.triangle(r0[k], r0[k1], r1[k1])
        m.triangle(r0[k], r1[k1], r1[k])


def crossing():
    m = Obj()
    m.part("along_x", (0.9, 0.3, 0.2))
    cylinder(m, 0, 0.3, 2.0, 32)
    m.part("along_y", (0.2, 0.5, 0.9))
    cylinder(m, 1, 0.25, 2.0, 32)
    return m


def rotate(p):
    x, y, z = p
    a, b = math.radians(TILT_X), math.radians(TILT_Y)
    y, z = y * math.cos(a) - z * math.sin(a), y * math.sin(a) + z * math.cos(a)
    x, z = x * math.cos(b) + z * math.sin(b), -x * math.sin(b) + z * math.cos(b)
    return (x, y, z)


def camera(vertices, size):
    """The default camera's construction (oit_default_camera) about the exact
    box centre, in double: modelview and projection, row by row."""
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    centre = [0.5 * (lo[k] + hi[k]) for k in range(3)]
    radius = max(math.dist(v, centre) for v in vertices)
    fov = math.radians(40.0)
    distance = 1.05 * radius / math.sin(fov / 2)
    near, far = max(distance - 1.1 * radius, distance * 1e-3), distance + 1.1 * radius
    ca, sa = math.cos(math.radians(-AZIMUTH)), math.sin(math.radians(-AZIMUTH))
    ce, se = math.cos(math.radians(ELEVATION)), math.sin(math.radians(ELEVATION))
    rotation = [[ca, 0.0, sa], [se * sa, ce, -se * ca], [-ce * sa, se, ce * ca]]
    modelview = []
    for row in range(3):
        moved = -sum(rotation[row][col] * centre[col] for col in range(3)) - (distance if row == 2 else 0.0)
        modelview += rotation[row] + [moved]
    modelview += [0.0, 0.0, 0.0, 1.0]
    f = 1.0 / math.tan(fov / 2)
    projection = [f, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), 2 * far * near / (near - far),
                  0, 0, -1, 0]
    del size  # square: the aspect is 1
    return modelview, projection


def main():
    out = sys.argv[1]
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 96
    os.makedirs(out, exist_ok=True)
    for name, build in (("assembly", assembly), ("crossing", crossing)):
        for label, offset in OFFSETS.items():
            m = build()
            m.vertices = [tuple(c + offset * d for c, d in zip(rotate(p), DIRECTION)) for p in m.vertices]
            base = os.path.join(out, "%s_%s" % (name, label))
            m.write(base + ".obj", digits=17)  # only the import's float32 rounds
            modelview, projection = camera(m.vertices, size)
            with open(base + ".camera", "w") as f:
                f.write(",".join(repr(v) for v in modelview) + "\n")
                f.write(",".join(repr(v) for v in projection) + "\n")
            with open(base + ".exact", "w") as f:
                for p in m.vertices:
                    f.write("%r %r %r\n" % p)


if __name__ == "__main__":
    main()
