#!/usr/bin/env python3
"""caps.py OIT SCENE.obj GEARBOX.obj WORK: section caps in the image (issue 28;
docs/sections.md "Caps"), on tests/caps_scene.py's scene: a closed block with a
closed inner part inside it, a closed bar and an open tray, cut by z = 0.1 and
seen orthographically along the plane's normal from the removed side (+z),
128x128:
- every exact algorithm (dp, ddp, ll, ib on EGL, dp on OSMesa) matches the
  reference within 2/255 on 99.9% of the pixels;
- the caps cover the cross-sections: inside the block's, the bar's and the
  inner part's, the image with caps differs from --caps off (which shows the
  interior, so it differs from the uncut model too), and with flat shading it
  is the uncut model's within 1/255: a cap in the part's colour and opacity
  stands in for the removed face parallel to it;
- the open tray is not capped (its pixels are the same with caps on and off),
  and the render names it;
- --section-parts bar cuts only the bar: the block's and the inner part's
  pixels are the uncut model's, the bar is capped (not the --caps off pixel);
- two and three planes together, and the gearbox cut by z = 0.05, still match
  the reference (dp; ll and ib).
Prints each comparison; exit 1 on the first failure."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402

SIZE = "128x128"
# camera at z = +5 looking down -z; orthographic x, y in [-2, 2], depth 1..9 (row by row)
MODELVIEW = "1,0,0,0,0,1,0,0,0,0,1,-5,0,0,0,1"
PROJECTION = "0.5,0,0,0,0,0.5,0,0,0,0,-0.25,-1.25,0,0,0,1"
# flat shading: a cap parallel to a box's removed face, in its colour and
# opacity, composites to the uncut box's colour exactly
VIEW = ["--size", SIZE, "--modelview", MODELVIEW, "--projection", PROJECTION, "--shading", "flat"]
CUT = ["--section", "0,0,1,0.1"]
EXACT = ["dp", "ddp", "ll", "ib"]


def fail(what):
    print("FAIL: " + what)
    sys.exit(1)


def render(oit, work, name, model, algorithm, *args, backend="egl"):
    out = os.path.join(work, name + ".png")
    run = subprocess.run([oit, "render", "--model", model, "--algorithm", algorithm, "--backend", backend,
                          "--out", out, "--json"] + VIEW + list(args), capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{name}: render exited {run.returncode}: {run.stderr.strip()}")
    return out, run.stdout + run.stderr


def matches(oit, image, reference, what):
    run = subprocess.run([oit, "compare", image, reference, "--tolerance", "2", "--max-mismatch", "0.1"],
                         capture_output=True, text=True)
    print(f"{what}: {run.stdout.strip()}")
    if run.returncode != 0:
        fail(f"{what} does not match the reference within 2/255 on 99.9% of the pixels")


def pixel(image, x, y):
    """The pixel at file coordinates (x, y) in the view above."""
    width, height, rows = image
    column = int((x + 2.0) / 4.0 * width)
    row = int((2.0 - y) / 4.0 * height)
    return tuple(rows[row][4 * column:4 * column + 4])


def exact_set(oit, work, label, model, args, algorithms):
    reference, said = render(oit, work, label + "_reference", model, "reference", *args)
    for algorithm in algorithms:
        image, _ = render(oit, work, f"{label}_{algorithm}", model, algorithm, *args)
        matches(oit, image, reference, f"{label} {algorithm}")
    return reference, said


def main():
    oit, scene, gearbox, work = sys.argv[1:5]
    os.makedirs(work, exist_ok=True)

    # one plane, caps on: every exact algorithm against the reference, and OSMesa
    reference, said = exact_set(oit, work, "cut", scene, CUT, EXACT)
    image, _ = render(oit, work, "cut_dp_osmesa", scene, "dp", *CUT, backend="osmesa")
    matches(oit, image, reference, "cut dp osmesa")

    # caps cover the cross-sections; the tray is not capped, and it is named
    off, _ = render(oit, work, "cut_caps_off", scene, "reference", *CUT, "--caps", "off")
    whole, _ = render(oit, work, "whole", scene, "reference")
    on_img, off_img, whole_img = read_png(reference), read_png(off), read_png(whole)
    for part, (x, y) in {"block": (-0.7, 0.7), "inner": (0.0, 0.0), "bar": (1.5, -0.5)}.items():
        on_p, off_p, whole_p = pixel(on_img, x, y), pixel(off_img, x, y), pixel(whole_img, x, y)
        print(f"{part} at ({x}, {y}): caps on {on_p}, off {off_p}, uncut {whole_p}")
        if on_p == off_p:
            fail(f"the {part}'s cross-section looks the same with and without caps")
        if max(abs(a - b) for a, b in zip(on_p, whole_p)) > 1:
            fail(f"the {part}'s cap does not composite as the removed face did (uncut) within 1/255")
        if off_p == whole_p:
            fail(f"--caps off: the {part}'s cross-section shows no interior (as uncut)")
    tray_on, tray_off = pixel(on_img, -1.55, 0.0), pixel(off_img, -1.55, 0.0)
    print(f"tray at (-1.55, 0): caps on {tray_on}, off {tray_off}")
    if tray_on != tray_off:
        fail("the open tray got a cap")
    if "tray" not in said:
        fail("the render does not name the open tray it did not cap")

    # --section-parts bar: only the bar is cut
    only_bar = CUT + ["--section-parts", "bar"]
    bar_ref, _ = exact_set(oit, work, "bar_only", scene, only_bar, ["dp"])
    bar_img = read_png(bar_ref)
    if pixel(bar_img, -0.7, 0.7) != pixel(whole_img, -0.7, 0.7):
        fail("--section-parts bar cut the block")
    if pixel(bar_img, 1.5, -0.5) == pixel(off_img, 1.5, -0.5) or pixel(bar_img, 0.0, 0.0) != pixel(
            whole_img, 0.0, 0.0):
        fail("--section-parts bar: the bar has no cap, or the inner part was cut")

    # two and three planes
    two = CUT + ["--section", "1,0,0,0.5"]
    three = two + ["--section", "0,-1,0,0.6"]
    exact_set(oit, work, "two", scene, two, ["dp"])
    exact_set(oit, work, "three", scene, three, ["dp", "ll", "ib"])

    # the gearbox
    exact_set(oit, work, "gearbox", gearbox, ["--section", "0,0,1,0.05"], ["dp", "ll", "ib"])
    print("caps: ok")


if __name__ == "__main__":
    main()
