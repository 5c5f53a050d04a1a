#!/usr/bin/env python3
"""error_figures.py OIT WORK SCENES: `oit render --error-vs-reference` agrees with
an independent comparison of the PNGs it wrote.

For each case the candidate image (--out) and the reference image (oit render
--algorithm reference, same camera) are written, and this script computes rmse,
psnr, ssim, max and share_over_2 from the two PNGs itself (standard library:
its own PNG reader, tests/ib_png.py, and its own SSIM, written from Wang et al.
2004 without looking at src/core/image_error.c's loops: a direct, non-separable
window sum). The figures must agree to 1e-6 relative (ssim 1e-6 absolute), and
--error-map must colour every pixel by its largest channel difference as
docs/cli.md says (black exactly where the pixel is exact). Then the error must
not be trivially zero: the cases include approximations with real error.
"""
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402

SIZE = "48x40"  # small: the independent SSIM is a direct 11x11 window sum in Python


def channels(image):
    width, height, rows = image
    return [[[rows[y][4 * x + c] for x in range(width)] for y in range(height)] for c in range(3)]


def ssim(a, b, width, height):
    n, sigma = 11, 1.5
    weights = [[math.exp(-((i - 5) ** 2 + (j - 5) ** 2) / (2 * sigma * sigma)) for i in range(n)] for j in range(n)]
    total_weight = sum(sum(row) for row in weights)
    weights = [[w / total_weight for w in row] for row in weights]
    c1, c2 = (0.01 * 255) ** 2, (0.03 * 255) ** 2
    result = 0.0
    for c in range(3):
        x, y = a[c], b[c]
        channel, windows = 0.0, 0
        for top in range(height - n + 1):
            for left in range(width - n + 1):
                mx = my = sxx = syy = sxy = 0.0
                for j in range(n):
                    rx, ry, wr = x[top + j], y[top + j], weights[j]
                    for i in range(n):
                        w, p, q = wr[i], rx[left + i], ry[left + i]
                        mx += w * p
                        my += w * q
                        sxx += w * p * p
                        syy += w * q * q
                        sxy += w * p * q
                vx, vy, cov = sxx - mx * mx, syy - my * my, sxy - mx * my
                channel += ((2 * mx * my + c1) * (2 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2))
                windows += 1
        result += channel / windows
    return result / 3


def heat(t):
    t = min(max(t, 0.0), 1.0) * 3
    if t < 1:
        rgb = (0, t, 1 - t)
    elif t < 2:
        rgb = (t - 1, 1, 0)
    else:
        rgb = (1, 3 - t, 0)
    return tuple(int(math.floor(v * 255 + 0.5)) for v in rgb)


def map_colour(d):
    if d == 0:
        return (0, 0, 0)
    return heat(min(1.0, math.log2(1 + d) / math.log2(1 + 64)))


def run(oit, args):
    done = subprocess.run([oit] + args, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"FAIL: oit {' '.join(args)}: exit {done.returncode}: {done.stderr.strip()}")
    return done.stdout


def main():
    oit, work, scenes = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    cases = [("wboit", "spheres", []), ("blend", "gearbox", []), ("ll", "onion", []),
             ("wboit", "gearbox", ["--orbit", "30,20", "--shading", "headlight"])]
    failures = 0
    nonzero = 0
    for algorithm, scene, extra in cases:
        label = f"{algorithm}_{scene}{'_' + str(len(extra)) if extra else ''}"
        model = os.path.join(scenes, scene + ".obj")
        image_path = os.path.join(work, label + ".png")
        reference_path = os.path.join(work, label + "_reference.png")
        map_path = os.path.join(work, label + "_map.png")
        common = ["--model", model, "--size", SIZE] + extra
        out = run(oit, ["render", "--algorithm", algorithm, "--out", image_path, "--json", "--error-vs-reference",
                        "--error-map", map_path] + common)
        figures = json.loads(out)["error"]
        run(oit, ["render", "--algorithm", "reference", "--out", reference_path] + common)

        a, b = read_png(image_path), read_png(reference_path)
        width, height = a[0], a[1]
        ca, cb = channels(a), channels(b)
        squares, largest, over = 0, 0, 0
        pixel_max = [[0] * width for _ in range(height)]
        for y in range(height):
            for x in range(width):
                d = [abs(ca[c][y][x] - cb[c][y][x]) for c in range(3)]
                squares += sum(v * v for v in d)
                pixel_max[y][x] = max(d)
                largest = max(largest, max(d))
                over += max(d) > 2
        samples = width * height * 3
        rmse = math.sqrt(squares / samples)
        psnr = None if squares == 0 else 10 * math.log10(255 * 255 / (squares / samples))
        mine = {"rmse": rmse, "psnr": psnr, "ssim": ssim(ca, cb, width, height), "max": largest,
                "share_over_2": 100.0 * over / (width * height)}
        for key, value in mine.items():
            theirs = figures[key]
            if value is None or theirs is None:
                ok = value is None and theirs is None
            elif key == "ssim":
                ok = abs(value - theirs) <= 1e-6
            else:
                ok = abs(value - theirs) <= 1e-6 * max(1.0, abs(value))
            print(f"{label}: {key}: oit {theirs} independent {value}: {'ok' if ok else 'DIFFERENT'}")
            failures += not ok
        nonzero += largest > 0

        error_map = read_png(map_path)
        if error_map[0] != width or error_map[1] != height + 18:
            print(f"{label}: FAIL: error map is {error_map[0]}x{error_map[1]}, expected {width}x{height + 18}")
            failures += 1
        else:
            wrong = sum(tuple(error_map[2][y][4 * x:4 * x + 3]) != map_colour(pixel_max[y][x])
                        for y in range(height) for x in range(width))
            print(f"{label}: error map: {wrong} pixels coloured unlike their difference")
            failures += wrong > 0
    if nonzero < 3:
        print(f"FAIL: only {nonzero} cases had any error: the comparison would not notice a wrong formula")
        failures += 1
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
