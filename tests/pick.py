#!/usr/bin/env python3
"""pick.py OIT WORK: `oit pick` on a scene whose answer is known.

The scene (written here): a closed box "shell" (file coordinates centre
(100, 50, -20), half size 2) around a closed box "core" (half size 0.5), far
from the origin so that the point must come back in file coordinates. The
default camera looks down -z at the centre, so the centre pixel's ray meets
shell front, core front, core back, shell back in that order.
- shell at 5% (--component-alpha shell=0.05): the core is picked, with the
  contribution alpha * T computed here from the four opacities; rank 2 is the
  shell; the points lie on the front faces (z = -18 and -19.5);
- shell opaque: the shell, contribution 1; rank 2 the core with 0;
- --hide core: one part; a corner pixel: "part": null;
- with flat shading, the reference render's centre pixel equals the colour
  the pick's contributions mix (sum c_part * colour_part + T * background):
  the pick sees the fragments the reference composites; at the shell's
  silhouette the first covered pixel is the shell's and the one before it
  the background's; a plane of sub-pixel triangles is picked whole at six
  pixels (no covering triangle left out);
- --pixel outside the image: exit 2, one line on stderr, nothing on stdout.
"""
import json
import os
import struct
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402

CENTRE = (100.0, 50.0, -20.0)
SIZE = (64, 48)
PIXEL = "32,24"  # the centre: its ray runs along the axis through both boxes
COLOURS = {"shell": (0.2, 0.4, 1.0), "core": (1.0, 0.1, 0.1)}


def box(name, half, first_vertex):
    """A closed box's OBJ lines, 12 triangles."""
    lines = [f"g {name}", f"usemtl {name}"]
    for i in range(8):
        x, y, z = [(half if (i >> k) & 1 else -half) + CENTRE[k] for k in range(3)]
        lines.append(f"v {x} {y} {z}")
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    for a, b, c, d in quads:
        v = [first_vertex + k for k in (a, b, c, d)]
        lines.append(f"f {v[0]} {v[1]} {v[2]}")
        lines.append(f"f {v[0]} {v[2]} {v[3]}")
    return lines


def write_scene(work):
    os.makedirs(work, exist_ok=True)
    obj, mtl = os.path.join(work, "shell_core.obj"), os.path.join(work, "shell_core.mtl")
    with open(mtl, "w") as f:
        for name, (r, g, b) in COLOURS.items():
            f.write(f"newmtl {name}\nKd {r} {g} {b}\nd 1\n")
    with open(obj, "w") as f:
        f.write("\n".join(["mtllib shell_core.mtl"] + box("shell", 2.0, 1) + box("core", 0.5, 9)) + "\n")
    return obj


def write_grid(work, cells):
    """A square in z = 0 of cells x cells quads, two triangles each: one part, "grid"."""
    path = os.path.join(work, "grid.obj")
    lines = ["g grid"]
    for j in range(cells + 1):
        for i in range(cells + 1):
            lines.append(f"v {-1 + 2 * i / cells} {-1 + 2 * j / cells} 0")
    for j in range(cells):
        for i in range(cells):
            a = 1 + j * (cells + 1) + i
            b, c, d = a + 1, a + cells + 2, a + cells + 1
            lines.append(f"f {a} {b} {c}")
            lines.append(f"f {a} {c} {d}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def run(oit, *args):
    return subprocess.run([oit, *args], capture_output=True, text=True)


def pick(oit, model, *args):
    result = run(oit, "pick", "--model", model, "--size", f"{SIZE[0]}x{SIZE[1]}", "--json", *args)
    if result.returncode != 0:
        sys.exit(f"FAIL: oit pick {' '.join(args)} exited {result.returncode}: {result.stderr.strip()}")
    return json.loads(result.stdout)


def expect(condition, what):
    if not condition:
        sys.exit(f"FAIL: {what}")
    print(f"ok: {what}")


def weights(alphas):
    """Front-to-back alpha * T for the centre ray's fragments, in double as the reference."""
    out, transmittance = [], 1.0
    for a in alphas:
        out.append(transmittance * a)
        transmittance *= 1.0 - a
    return out, transmittance


def main():
    oit, work = sys.argv[1], sys.argv[2]
    model = write_scene(work)

    # shell at 5%, --alpha 0.5: the core shows through it
    faint = ["--pixel", PIXEL, "--alpha", "0.5", "--component-alpha", "shell=0.05"]
    shell_alpha, core_alpha = f32(f32(0.5) * f32(0.05)), f32(0.5)
    w, background = weights([shell_alpha, core_alpha, core_alpha, shell_alpha])
    first = pick(oit, model, *faint)
    expect(first["part"] == "core" and first["index"] == 1, f"shell at 5%: the core is picked ({first['part']})")
    expect(abs(first["contribution"] - (w[1] + w[2])) < 1e-6,
           f"the core's contribution {first['contribution']:.9g} is alpha*T summed ({w[1] + w[2]:.9g})")
    expect(abs(first["point"][2] - (CENTRE[2] + 0.5)) < 1e-3 and abs(first["point"][0] - CENTRE[0]) < 0.1 and
           abs(first["point"][1] - CENTRE[1]) < 0.1,
           f"the core's point {first['point']} is on its front face, file coordinates")
    second = pick(oit, model, *faint, "--rank", "2")
    expect(second["part"] == "shell" and abs(second["contribution"] - (w[0] + w[3])) < 1e-6,
           f"rank 2 is the shell ({second['part']}, {second['contribution']:.9g})")
    expect(abs(second["point"][2] - (CENTRE[2] + 2.0)) < 1e-3 and second["depth"] < first["depth"],
           f"the shell's point {second['point']} is on its front face, nearer than the core's")
    expect(abs(first["contribution"] + second["contribution"] + first["background"] - 1.0) < 1e-9,
           "the contributions and the background's share add up to 1")
    third = pick(oit, model, *faint, "--rank", "3")
    expect(third["part"] is None, "rank 3 of two parts: none")

    # the reference's centre pixel is the mix of the pick's contributions (flat shading)
    png = os.path.join(work, "faint.png")
    rendered = run(oit, "render", "--model", model, "--algorithm", "reference", "--size",
                   f"{SIZE[0]}x{SIZE[1]}", "--shading", "flat", "--background", "1,1,1", "--alpha", "0.5",
                   "--component-alpha", "shell=0.05", "--out", png)
    if rendered.returncode != 0:
        sys.exit(f"FAIL: oit render: {rendered.stderr.strip()}")
    width, height, rows = read_png(png)
    x, y = (int(v) for v in PIXEL.split(","))
    seen = [rows[y][4 * x + k] for k in range(3)]
    mixed = [round(255 * (first["contribution"] * COLOURS["core"][k] + second["contribution"] * COLOURS["shell"][k] +
                          first["background"] * 1.0)) for k in range(3)]
    expect(all(abs(a - b) <= 1 for a, b in zip(seen, mixed)),
           f"the reference's pixel {seen} is the pick's mix {mixed} (within 1/255)")

    # the silhouette: the first covered pixel of the centre row is the shell's, with the
    # reference's colour, and the one before it the background's (a pick that skipped
    # triangles near the pixel, e.g. a wrong candidate test, misses the edge)
    edge = next(px for px in range(width) if rows[y][4 * px:4 * px + 3] != bytes([255, 255, 255]))
    expect(0 < edge < x, f"the shell's left edge on row {y} is at x = {edge}")
    outside = pick(oit, model, *faint[2:], "--pixel", f"{edge - 1},{y}")
    expect(outside["part"] is None, f"pixel {edge - 1},{y} left of the edge: \"part\": null")
    inside = pick(oit, model, *faint[2:], "--pixel", f"{edge},{y}")
    seen = [rows[y][4 * edge + k] for k in range(3)]
    mixed = [round(255 * (inside["contribution"] * COLOURS["shell"][k] + inside["background"])) for k in range(3)]
    expect(inside["part"] == "shell" and inside["parts"] == 1 and all(abs(a - b) <= 1 for a, b in zip(seen, mixed)),
           f"pixel {edge},{y} on the edge: the shell, the reference's {seen} its mix {mixed}")

    # a plane of triangles under a pixel wide: every pixel has vertices within a pixel of
    # its centre, so a pick that left out a triangle covering it (a candidate test
    # that is too eager) finds nothing or too little there
    grid = write_grid(work, 96)
    for px in ("32,24", "30,22", "34,26", "31,25", "33,23", "20,30"):
        answer = pick(oit, grid, "--pixel", px, "--alpha", "0.5")
        if not (answer["part"] == "grid" and answer["parts"] == 1 and answer["contribution"] == f32(0.5)):
            sys.exit(f"FAIL: the fine grid at {px}: {answer}")
    print("ok: the fine grid (96x96 cells) is picked whole at 6 pixels")

    # shell opaque: the shell, and the core behind it with nothing
    opaque = ["--pixel", PIXEL, "--alpha", "1"]
    first = pick(oit, model, *opaque)
    expect(first["part"] == "shell" and abs(first["contribution"] - 1.0) < 1e-9,
           f"shell opaque: the shell is picked ({first['part']}, {first['contribution']})")
    second = pick(oit, model, *opaque, "--rank", "2")
    expect(second["part"] == "core" and second["contribution"] == 0.0,
           f"rank 2 behind the opaque shell is the core with 0 ({second['part']}, {second['contribution']})")

    hidden = pick(oit, model, *faint, "--hide", "core")
    expect(hidden["part"] == "shell" and hidden["parts"] == 1, "--hide core: only the shell is there")
    corner = pick(oit, model, "--pixel", "0,0")
    expect(corner["part"] is None and corner["background"] == 1.0, "a corner pixel: \"part\": null")

    for bad in ("64,0", "0,48", "-1,3"):
        result = run(oit, "pick", "--model", model, "--size", f"{SIZE[0]}x{SIZE[1]}", "--pixel", bad)
        lines = result.stderr.strip().splitlines()
        expect(result.returncode == 2 and len(lines) == 1 and "outside" in lines[0] and bad in lines[0] and
               result.stdout == "", f"--pixel {bad}: exit 2, one line: {lines[0] if lines else ''}")
    print("pick: all checks passed")


if __name__ == "__main__":
    main()
