#!/usr/bin/env python3
"""flip_figures.py OIT WORK SCENES: the perceptual error FLIP (src/core/flip.c).

1. Identical images give exactly 0 (`oit compare --json`'s "flip").
2. A graded series (one image plus the same noise pattern at amplitudes 4, 8, 16, 32, 64 and 128
   of 255) gives a strictly increasing mean FLIP.
3. Known values: uniform black against uniform white, whose FLIP is the paper's colour term alone
   (no features on a constant image) and follows in closed form; and a 32x32 colour checkerboard
   against itself shifted by 2 pixels, computed here from the paper's formulas (standard library
   only: direct 2-D kernels, not the core's separable passes; the XYZ matrix derived from the sRGB
   primaries). Both agree with oit within 1e-6.
4. `oit render --error-map M.png --error-metric flip`: the map is the image's size plus the 18-row
   legend, every pixel is a magma colour, pixels whose whole filter neighbourhood is exact are
   magma's first colour (0, 0, 4), and the mean of the map's values (index / 255) is the JSON's
   "flip" within 1/255. A bad --error-metric, or one without --error-map, is exit 2 with one line.
"""
import json
import math
import os
import random
import struct
import subprocess
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402

PPD = 0.7 * 3840 / 0.7 * math.pi / 180  # the paper's default viewing: 0.7 m wide 4K monitor at 0.7 m
QC, PC, PT, QF = 0.7, 0.4, 0.95, 0.5
FEATURE_WIDTH = 0.082
CSF = {"a": [(1.0, 0.0047)], "rg": [(1.0, 0.0053)], "by": [(34.1, 0.04), (13.5, 0.025)]}


def write_png(path, width, height, pixel):
    raw = b"".join(b"\x00" + bytes(v for x in range(width) for v in (*pixel(x, y), 255)) for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def run(oit, args, expect=0):
    done = subprocess.run([oit] + args, capture_output=True, text=True)
    if expect is not None and done.returncode != expect:
        sys.exit(f"FAIL: oit {' '.join(args)}: exit {done.returncode}, expected {expect}: {done.stderr.strip()}")
    return done


def oit_flip(oit, a, b):
    done = run(oit, ["compare", a, b, "--json"], expect=None)
    if done.returncode not in (0, 1):
        sys.exit(f"FAIL: oit compare {a} {b}: exit {done.returncode}: {done.stderr.strip()}")
    return json.loads(done.stdout)["flip"]


# ---------------------------------------------------------------- the paper's formulas, directly

def solve3(m, v):
    """m (3x3 rows) x = v by Cramer's rule."""
    def det(a):
        return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))
    d = det(m)
    return [det([[v[r] if c == k else m[r][c] for c in range(3)] for r in range(3)]) / d for k in range(3)]


def inverse3(m):
    cols = [solve3(m, [1.0 if r == k else 0.0 for r in range(3)]) for k in range(3)]
    return [[cols[c][r] for c in range(3)] for r in range(3)]


def srgb_matrix():
    """linear sRGB -> XYZ from the primaries' and D65's chromaticities (IEC 61966-2-1)."""
    prim = [(0.64, 0.33), (0.30, 0.60), (0.15, 0.06)]
    wx, wy = 0.3127, 0.3290
    white = [wx / wy, 1.0, (1 - wx - wy) / wy]
    p = [[x / y for x, y in prim], [1.0] * 3, [(1 - x - y) / y for x, y in prim]]
    s = solve3(p, white)
    return [[p[r][c] * s[c] for c in range(3)] for r in range(3)], white


M, WHITE = srgb_matrix()
MI = inverse3(M)


def mul(m, v):
    return [m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2] for r in range(3)]


def linear(c):
    c /= 255.0
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def hunt_lab(rgb):
    d = 6 / 29
    f = [t ** (1 / 3) if t > d ** 3 else t / (3 * d * d) + 4 / 29 for t in (v / w for v, w in zip(mul(M, rgb), WHITE))]
    lum = 116 * f[1] - 16
    return [lum, 0.01 * lum * 500 * (f[0] - f[1]), 0.01 * lum * 200 * (f[1] - f[2])]


def hyab(a, b):
    return abs(a[0] - b[0]) + math.hypot(a[1] - b[1], a[2] - b[2])


def cmax():
    return hyab(hunt_lab([0, 1, 0]), hunt_lab([0, 0, 1])) ** QC


def compress(e, top):
    return PT / (PC * top) * e if e < PC * top else PT + (e - PC * top) / (top - PC * top) * (1 - PT)


def convolve(plane, kernel, r):
    """2-D correlation with a (2r+1)^2 kernel, edges clamped."""
    h, w = len(plane), len(plane[0])
    out = [[0.0] * w for _ in range(h)]
    xs = [[min(max(x + i, 0), w - 1) for i in range(-r, r + 1)] for x in range(w)]
    for y in range(h):
        rows = [plane[min(max(y + j, 0), h - 1)] for j in range(-r, r + 1)]
        for x in range(w):
            idx = xs[x]
            total = 0.0
            for row, krow in zip(rows, kernel):
                total += sum(k * row[i] for k, i in zip(krow, idx))
            out[y][x] = total
    return out


def csf_kernel(terms, r):
    k = [[sum(a * math.sqrt(math.pi / b) * math.exp(-math.pi ** 2 * ((x / PPD) ** 2 + (y / PPD) ** 2) / b)
              for a, b in terms) for x in range(-r, r + 1)] for y in range(-r, r + 1)]
    total = sum(map(sum, k))
    return [[v / total for v in row] for row in k]


def feature_kernels(r, sd):
    def signed(k):
        pos = sum(v for row in k for v in row if v > 0)
        neg = -sum(v for row in k for v in row if v < 0)
        return [[v / pos if v > 0 else v / neg for v in row] for row in k]
    g = [[math.exp(-(x * x + y * y) / (2 * sd * sd)) for x in range(-r, r + 1)] for y in range(-r, r + 1)]
    edge = signed([[-x * g[j][i] for i, x in enumerate(range(-r, r + 1))] for j in range(2 * r + 1)])
    point = signed([[(x * x / (sd * sd) - 1) * g[j][i] for i, x in enumerate(range(-r, r + 1))]
                    for j in range(2 * r + 1)])
    return edge, point


def transpose(k):
    return [list(row) for row in zip(*k)]


def flip_mean(img_a, img_b):
    """img: rows of (r, g, b) 0..255 tuples."""
    h, w = len(img_a), len(img_a[0])
    r = math.ceil(3 * math.sqrt(0.04 / (2 * math.pi ** 2)) * PPD)
    kernels = {c: csf_kernel(t, r) for c, t in CSF.items()}
    sd = 0.5 * FEATURE_WIDTH * PPD
    fr = math.ceil(3 * sd)
    edge, point = feature_kernels(fr, sd)
    top = cmax()
    labs, feats = [], []
    for img in (img_a, img_b):
        xyz = [[[v / wt for v, wt in zip(mul(M, [linear(c) for c in img[y][x]]), WHITE)] for x in range(w)]
               for y in range(h)]
        yy = [[116 * p[1] - 16 for p in row] for row in xyz]
        cx = [[500 * (p[0] - p[1]) for p in row] for row in xyz]
        cz = [[200 * (p[1] - p[2]) for p in row] for row in xyz]
        fy, fx, fz = convolve(yy, kernels["a"], r), convolve(cx, kernels["rg"], r), convolve(cz, kernels["by"], r)
        lab = [[None] * w for _ in range(h)]
        for y in range(h):
            for x in range(w):
                ly = (fy[y][x] + 16) / 116
                back = mul(MI, [(ly + fx[y][x] / 500) * WHITE[0], ly, (ly - fz[y][x] / 200) * WHITE[2]])
                lab[y][x] = hunt_lab([min(max(v, 0.0), 1.0) for v in back])
        labs.append(lab)
        lum = [[(v + 16) / 116 for v in row] for row in yy]
        ex, ey = convolve(lum, edge, fr), convolve(lum, transpose(edge), fr)
        px, py = convolve(lum, point, fr), convolve(lum, transpose(point), fr)
        feats.append(([[math.hypot(ex[y][x], ey[y][x]) for x in range(w)] for y in range(h)],
                      [[math.hypot(px[y][x], py[y][x]) for x in range(w)] for y in range(h)]))
    total = 0.0
    for y in range(h):
        for x in range(w):
            colour = compress(hyab(labs[0][y][x], labs[1][y][x]) ** QC, top)
            f = max(abs(feats[0][0][y][x] - feats[1][0][y][x]), abs(feats[0][1][y][x] - feats[1][1][y][x]))
            total += colour ** (1 - (f / math.sqrt(2)) ** QF)
    return total / (w * h)


# ---------------------------------------------------------------- the checks

def main():
    oit, work, scenes = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    failures = 0

    def check(ok, what):
        nonlocal failures
        print(f"{'ok' if ok else 'FAIL'}: {what}")
        failures += not ok

    def path(name):
        return os.path.join(work, name + ".png")

    # 1. identical images
    def base(x, y):
        return ((x * 4) % 256, (y * 4) % 256, 255 if (x // 8 + y // 8) % 2 else 40)
    write_png(path("base"), 64, 64, base)
    write_png(path("base_copy"), 64, 64, base)
    same = oit_flip(oit, path("base"), path("base_copy"))
    check(same == 0.0, f"identical images: flip {same} == 0")

    # 2. graded noise
    rng = random.Random(30)
    noise = [[[rng.uniform(-1, 1) for _ in range(3)] for _ in range(64)] for _ in range(64)]
    series = []
    for amplitude in (4, 8, 16, 32, 64, 128):
        def noisy(x, y, a=amplitude):
            return tuple(min(255, max(0, round(v + a * n))) for v, n in zip(base(x, y), noise[y][x]))
        write_png(path(f"noise_{amplitude}"), 64, 64, noisy)
        series.append((amplitude, oit_flip(oit, path("base"), path(f"noise_{amplitude}"))))
    print("graded noise: " + ", ".join(f"{a}: {f:.5f}" for a, f in series))
    check(all(b[1] > a[1] for a, b in zip(series, series[1:])), "flip increases strictly with the noise amplitude")
    check(series[0][1] > 0.0 and series[-1][1] < 1.0, "the series lies inside (0, 1)")

    # 3a. black against white: no features; HyAB of L* 0 and 100 (a*, b* of the white point are 0)
    write_png(path("black"), 16, 16, lambda x, y: (0, 0, 0))
    write_png(path("white"), 16, 16, lambda x, y: (255, 255, 255))
    expected = compress(hyab(hunt_lab([0, 0, 0]), hunt_lab([1, 1, 1])) ** QC, cmax())
    got = oit_flip(oit, path("black"), path("white"))
    check(abs(got - expected) <= 1e-6, f"black vs white: oit {got:.9f}, closed form {expected:.9f}")

    # 3b. a colour checkerboard against itself shifted by 2 pixels, by the direct 2-D formulas
    def board(shift):
        return [[(220, 40, 30) if ((x + shift) // 8 + y // 8) % 2 else (30, 60, 200) for x in range(32)]
                for y in range(32)]
    a, b = board(0), board(2)
    write_png(path("board"), 32, 32, lambda x, y: a[y][x])
    write_png(path("board_shifted"), 32, 32, lambda x, y: b[y][x])
    got = oit_flip(oit, path("board"), path("board_shifted"))
    expected = flip_mean(a, b)
    check(abs(got - expected) <= 1e-6, f"checkerboard vs shifted: oit {got:.9f}, independent {expected:.9f}")
    swapped = oit_flip(oit, path("board_shifted"), path("board"))
    check(swapped == got, f"symmetric: {swapped} == {got}")

    # 4. the map
    model = os.path.join(scenes, "spheres.obj")
    image, reference, flip_map = path("wboit"), path("wboit_reference"), path("wboit_flip_map")
    common = ["--model", model, "--size", "48x40"]
    out = run(oit, ["render", "--algorithm", "wboit", "--out", image, "--json", "--error-vs-reference",
                    "--error-map", flip_map, "--error-metric", "flip"] + common).stdout
    figure = json.loads(out)["error"]["flip"]
    run(oit, ["render", "--algorithm", "reference", "--out", reference] + common)
    width, height, rows = read_png(flip_map)
    check((width, height) == (48, 40 + 18), f"map is {width}x{height}, expected 48x58")
    try:
        import matplotlib
        cmap = matplotlib.colormaps["magma"]
        magma = [tuple(round(255 * v) for v in cmap(i)[:3]) for i in range(256)]
        print("magma from matplotlib")
    except ImportError:  # the map's own colours must still form one ramp starting at (0, 0, 4)
        magma = None
        print("matplotlib not found: the map's colours are checked against the JSON mean only")
    img, ref = read_png(image), read_png(reference)
    equal = [[tuple(img[2][y][4 * x:4 * x + 3]) == tuple(ref[2][y][4 * x:4 * x + 3]) for x in range(48)]
             for y in range(40)]
    r = math.ceil(3 * math.sqrt(0.04 / (2 * math.pi ** 2)) * PPD)
    calm = [(x, y) for y in range(40) for x in range(48)
            if all(equal[yy][xx] for yy in range(max(0, y - r), min(40, y + r + 1))
                   for xx in range(max(0, x - r), min(48, x + r + 1)))]
    colours = [[tuple(rows[y][4 * x:4 * x + 3]) for x in range(48)] for y in range(40)]
    not_black = sum(colours[y][x] != (0, 0, 4) for x, y in calm)
    check(len(calm) > 0 and not_black == 0, f"{len(calm)} pixels with an exact neighbourhood, {not_black} of them not (0, 0, 4)")
    check(sum(not e for row in equal for e in row) > 0, "the wboit image differs from the reference somewhere")
    if magma:
        index = {c: i for i, c in enumerate(magma)}
        outside = sum(c not in index for row in colours for c in row)
        check(outside == 0, f"every map pixel is a magma colour ({outside} are not)")
        mean = sum(index.get(c, 0) for row in colours for c in row) / (48 * 40) / 255
        check(abs(mean - figure) <= 1 / 255, f"map mean {mean:.5f} vs --json flip {figure:.5f} (within 1/255)")

    # bad values
    for args, words in ((["--error-map", path("x"), "--error-metric", "ssim"], "--error-metric must be abs or flip"),
                        (["--error-metric", "flip"], "--error-metric goes with --error-map")):
        done = run(oit, ["render", "--algorithm", "wboit"] + common + args, expect=2)
        lines = done.stderr.strip().splitlines()
        check(len(lines) == 1 and words in lines[0], f"{' '.join(args)}: exit 2, {lines}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
