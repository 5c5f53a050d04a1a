#!/usr/bin/env python3
"""overlay.py: the orientation aids of `oit render` (issue 29; docs/cli.md,
--axes and --scale-bar), 128x128 images.

usage: overlay.py OIT WORKDIR GEARBOX.obj STEP_FILE

(a) the triad's arrows point where the modelview says: for the front, the top
    and a turned view, the red (X), green (Y) and blue (Z) pixels' weighted
    centroid, seen from the triad's origin, lies within 3 degrees of the
    direction the modelview's columns give (axes shorter than 0.3 of an arrow,
    nearly along the line of sight, are skipped); at azimuth -45 X points away
    and Z at the eye along the same screen line: no red pixel on the shared
    shaft (Z drawn over X); every corner puts the origin in its quarter;
(b) the scale bar with an orthographic projection: its value is 1, 2 or 5 x
    10^k, the longest that fits a quarter of the width; its pixels are the value
    times the projection's pixels per unit (to 1e-6), and the ink summed along
    the bar's fully covered row is that length within 1 px; the perspective
    bar says it is exact at the centre's depth; a centre behind the camera
    gives a warning and "scale_bar": null, not a crash; a STEP file's bar is
    in millimetres ("1 mm");
(c) EGL and OSMesa: where their frames agree, the frames with the aids agree
    byte for byte; without the flags the image equals the one with them outside
    the aids' boxes and --json has no "axes"/"scale_bar";
(d) bad values (--axes=nowhere, --axes=) are refused with one line, exit 2.
"""
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402

OIT, WORK, GEARBOX, STEP = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
os.makedirs(WORK, exist_ok=True)
SIZE = 128
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def render(name, *flags, expect=0, model=None):
    out = os.path.join(WORK, name + ".png")
    cmd = [OIT, "render", "--model", model or GEARBOX, "--size", f"{SIZE}x{SIZE}", "--out", out, "--json", *flags]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != expect:
        print(" ".join(cmd), "\n", p.stderr)
        raise SystemExit(f"FAIL {name}: exit {p.returncode}, expected {expect}")
    if expect != 0:
        return p
    w, h, rows = read_png(out)
    return json.loads(p.stdout), (w, h, rows), p.stderr


def pixel(img, x, y):
    row = img[2][y]
    return row[4 * x], row[4 * x + 1], row[4 * x + 2]


def hue_weight(rgb, axis):
    """How strongly a pixel is the axis's colour (0 when it is not)."""
    r, g, b = rgb
    if axis == 0:
        d = r - max(g, b)
        return max(0, d - 60)
    if axis == 1:
        d = g - max(r, b)
        return max(0, d - 40)
    d = b - max(r, g)
    return max(0, d - 60)


def centroid(img, axis, ox, oy, reach):
    sx = sy = sw = 0.0
    for y in range(max(0, int(oy - reach)), min(SIZE, int(oy + reach) + 1)):
        for x in range(max(0, int(ox - reach)), min(SIZE, int(ox + reach) + 1)):
            wgt = hue_weight(pixel(img, x, y), axis)
            if wgt:
                sx += wgt * (x + 0.5)
                sy += wgt * (y + 0.5)
                sw += wgt
    return (sx / sw - ox, sy / sw - oy) if sw else None


# a clear corner: the model small in the middle, white background
BASE = ["--algorithm", "ll", "--background", "1,1,1"]

# ------------------------------------------------------------- (a) the triad
turned = None
for view, orbit in (("front", "0,0"), ("top", "0,90"), ("turned", "30,20")):
    info, img, _ = render("axes-" + view, *BASE, "--orbit", orbit, "--axes")
    if view == "turned":
        turned = info, img
    axes = info["axes"]
    ox, oy = axes["origin"]
    length = axes["length"]
    rows = [info["modelview"][4 * r:4 * r + 4] for r in range(4)]  # row by row
    for a, name in enumerate("XYZ"):
        # the model's axis a in eye space: column a of the modelview's rotation
        col = [rows[r][a] for r in range(3)]
        norm = math.sqrt(sum(c * c for c in col))
        ex, ey = col[0] / norm, -col[1] / norm  # image y runs down
        planar = math.hypot(ex, ey)
        if planar < 0.3:
            continue
        c = centroid(img, a, ox, oy, length * 1.9)
        check(c is not None, f"{view}: {name} has pixels of its colour")
        if c is None:
            continue
        angle = math.degrees(math.atan2(c[1], c[0]) - math.atan2(ey, ex))
        angle = (angle + 180.0) % 360.0 - 180.0
        check(abs(angle) <= 3.0, f"{view}: {name} points within 3 degrees of the modelview's ({angle:+.2f})")

# X away, Z towards the eye on the same screen line: Z covers X's shaft
info, img, _ = render("axes-overlap", *BASE, "--orbit", "-45,0", "--axes")
ox, oy = info["axes"]["origin"]
length = info["axes"]["length"]
dx, dy = info["axes"]["directions"][2]
red = blue = 0
for y in range(SIZE):
    for x in range(SIZE):
        px, py = x + 0.5 - ox, y + 0.5 - oy
        along = px * dx + py * dy
        across = abs(-px * dy + py * dx)
        if 1.0 < along < length * math.hypot(dx, dy) - 1.0 and across < 3.0:  # the shared arrow, not the letters
            rgb = pixel(img, x, y)
            red += hue_weight(rgb, 0) > 0
            blue += hue_weight(rgb, 2) > 0
check(blue > 10 and red == 0, f"away X drawn under Z on their shared line (blue {blue}, red {red} pixels)")

for corner, (right, bottom) in (("bottom-left", (0, 1)), ("bottom-right", (1, 1)), ("top-left", (0, 0)),
                                ("top-right", (1, 0))):
    # bottom-left: the turned view's (--axes without a corner)
    info, img = turned if corner == "bottom-left" else render("axes-" + corner, *BASE, "--orbit", "30,20",
                                                               "--axes=" + corner)[:2]
    ox, oy = info["axes"]["origin"]
    check(info["axes"]["corner"] == corner and (ox > SIZE / 2) == bool(right) and (oy > SIZE / 2) == bool(bottom),
          f"--axes={corner}: origin ({ox:.1f}, {oy:.1f}) in that quarter")

# -------------------------------------------------------- (b) the scale bar
# orthographic: x in [-23, 23] eye units over 128 px; the model's centre at depth 5
half = 23.0
ortho = [1 / half, 0, 0, 0, 0, 1 / half, 0, 0, 0, 0, -2 / 100.0, -1.0, 0, 0, 0, 1]
# the gearbox's centre (the model's origin) 5 units in front of the eye
with open(GEARBOX) as f:
    xs = [[float(v) for v in line.split()[1:4]] for line in f if line.startswith("v ")]
centre = [(min(p[k] for p in xs) + max(p[k] for p in xs)) / 2 for k in range(3)]
scale = 0.4  # model units per eye unit: the bar's value is in model units
mv = [scale, 0, 0, -scale * centre[0], 0, scale, 0, -scale * centre[1], 0, 0, scale, -scale * centre[2] - 50, 0, 0, 0, 1]
info, img, _ = render("scale-ortho", *BASE, "--modelview", ",".join(map(repr, mv)), "--projection",
                      ",".join(map(repr, ortho)), "--scale-bar")
bar = info["scale_bar"]
ppu = SIZE / (2 * half) * scale
value = bar["length"]
k = math.floor(math.log10(value) + 1e-9)
mantissa = value / 10 ** k
check(any(abs(mantissa - m) < 1e-9 for m in (1, 2, 5)), f"scale bar value {value} is 1, 2 or 5 x 10^{k}")
nice = sorted(m * 10 ** e for m in (1, 2, 5) for e in range(k - 1, k + 2))
larger = [v for v in nice if v > value * (1 + 1e-9)][0]
check(value * ppu <= SIZE / 4 + 1e-9 < larger * ppu, f"{value} is the longest that fits a quarter width "
      f"({value * ppu:.3f} <= {SIZE / 4} < {larger * ppu:.3f} px)")
check(abs(bar["pixels"] - value * ppu) < 1e-6, f"its pixels {bar['pixels']:.6f} = value x {ppu:.6f} px per unit")
check(bar["units"] == "" and bar["exact"].startswith("everywhere"), f"units '' (OBJ), exact: {bar['exact']}")
# the ink along the row the bar covers fully: (255 - v) / (255 - 20) per pixel
x0, y0 = bar["start"]
row = int(math.ceil(y0))
check(row + 1 <= y0 + bar["thickness"], f"row {row} lies inside the bar")
ink = sum((255 - pixel(img, x, row)[0]) / 235.0 for x in range(SIZE))
check(abs(ink - bar["pixels"]) <= 1.0, f"the drawn bar is {ink:.3f} px long, stated {bar['pixels']:.3f} (within 1 px)")

behind = list(mv)
behind[11] = -scale * centre[2] + 50  # the centre behind the eye
persp = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, -1.002, -0.2002, 0, 0, -1, 0]
info, img, err = render("scale-behind", *BASE, "--modelview", ",".join(map(repr, behind)), "--projection",
                        ",".join(map(repr, persp)), "--scale-bar")
check(info["scale_bar"] is None and "behind the camera" in err and err.count("\n") == 1,
      "centre behind the camera: one warning, \"scale_bar\": null")

info, img, _ = render("scale-step", *BASE, "--orbit", "30,30", "--scale-bar", model=STEP)
bar = info["scale_bar"]
check(bar["units"] == "mm" and bar["label"] == f"{bar['length']:g} mm", f"STEP: the bar in mm ({bar['label']})")

# ------------------------------------------------- (c) backends, no flags
aids = ["--orbit", "30,20", "--axes", "--scale-bar"]
info, egl, _ = render("egl-aids", *BASE, "--backend", "egl", *aids)
check(info["scale_bar"]["exact"] == "at the model's centre's depth", "perspective: exact at the centre's depth")
_, osm, _ = render("osmesa-aids", *BASE, "--backend", "osmesa", *aids)
info_plain, egl_plain, _ = render("egl-plain", *BASE, "--backend", "egl", "--orbit", "30,20")
_, osm_plain, _ = render("osmesa-plain", *BASE, "--backend", "osmesa", "--orbit", "30,20")
changed = same = differ = outside = 0
for y in range(SIZE):
    for x in range(SIZE):
        if pixel(egl, x, y) != pixel(egl_plain, x, y):
            changed += 1
        if pixel(egl_plain, x, y) == pixel(osm_plain, x, y):
            if pixel(egl, x, y) == pixel(osm, x, y):
                same += 1
            else:
                differ += 1
check(changed > 100 and differ == 0 and same > SIZE * SIZE // 2,
      f"EGL and OSMesa aids agree byte for byte where their frames do ({same} pixels, {differ} differ; "
      f"the aids changed {changed})")
check("axes" not in info_plain and "scale_bar" not in info_plain, "no flags: --json has no axes or scale_bar")
info_axes, egl_axes = turned  # EGL, orbit 30,20, --axes
ox, oy = info_axes["axes"]["origin"]
reach = 1.9 * info_axes["axes"]["length"]
for y in range(SIZE):
    for x in range(SIZE):
        if not (abs(x + 0.5 - ox) <= reach and abs(y + 0.5 - oy) <= reach):
            outside += pixel(egl_axes, x, y) != pixel(egl_plain, x, y)
check(outside == 0, f"--axes changes nothing outside the triad's box ({outside} pixels)")

# ------------------------------------------------------- (d) bad values
for bad in ("--axes=nowhere", "--axes="):
    p = render("bad", *BASE, bad, expect=2)
    line = p.stderr.strip()
    check(p.stderr.count("\n") == 1 and line.startswith("oit: error: --axes=") and "corner" in line,
          f"{bad} refused in one line: {line}")

if failures:
    print(f"{len(failures)} check(s) failed")
    sys.exit(1)
print("all checks passed")
