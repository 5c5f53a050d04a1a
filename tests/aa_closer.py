#!/usr/bin/env python3
"""aa_closer.py BIG.png N ONE.png MANY.png: anti-aliasing converges on the box filter.

BIG is the frame rendered at N times the width and height (one sample per
pixel); box-averaged over N x N blocks it is the pixel's mean colour over its
square, the image an anti-aliased frame approximates. ONE and MANY are the
frame at 1 and at several samples per pixel. Prints the RMSE (RGB, 0..255) of
each against the averaged BIG and fails unless MANY's is smaller than ONE's
(docs/testing.md, antialiasing). Standard library only (ib_png.read_png)."""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ib_png import read_png  # noqa: E402


def box_average(path, n):
    width, height, rows = read_png(path)
    if width % n or height % n:
        sys.exit(f"FAIL: {path} is {width}x{height}, not a multiple of {n}")
    out = []
    for y in range(height // n):
        row = []
        for x in range(width // n):
            for c in range(3):
                total = sum(rows[y * n + j][(x * n + i) * 4 + c] for j in range(n) for i in range(n))
                row.append(total / (n * n))
        out.append(row)
    return width // n, height // n, out


def rmse(path, width, height, target):
    w, h, rows = read_png(path)
    if (w, h) != (width, height):
        sys.exit(f"FAIL: {path} is {w}x{h}, expected {width}x{height}")
    total = 0.0
    for y in range(h):
        for x in range(w):
            for c in range(3):
                d = rows[y][x * 4 + c] - target[y][x * 3 + c]
                total += d * d
    return math.sqrt(total / (w * h * 3))


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    big, n, one, many = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
    width, height, target = box_average(big, n)
    e1, e_many = rmse(one, width, height, target), rmse(many, width, height, target)
    print(f"RMSE against the {n}x box-averaged frame: 1 sample {e1:.3f}, {os.path.basename(many)} {e_many:.3f}")
    if not e_many < e1:
        sys.exit("FAIL: the anti-aliased frame is not closer to the box-averaged one than 1 sample")


if __name__ == "__main__":
    main()
