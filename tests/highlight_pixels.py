#!/usr/bin/env python3
"""highlight_pixels.py PLAIN.png HIGHLIGHTED.png PART_ALONE.png: the selection
highlight changes the image only where the highlighted part is (docs/modulation.md).

PART_ALONE is the same frame with every other part hidden: its pixels that are
not the background are where the part can be seen. Fails (exit 1) when a pixel
outside them differs between PLAIN and HIGHLIGHTED, or when fewer than a tenth
of them changed (the highlight would be invisible). Prints the counts."""
import sys

from ib_png import read_png


def main():
    plain, highlighted, alone = (read_png(path) for path in sys.argv[1:4])
    width, height, _ = plain
    if highlighted[:2] != (width, height) or alone[:2] != (width, height):
        sys.exit("FAIL: the images differ in size")
    background = tuple(alone[2][0][0:3])  # the corner: the frame leaves a margin
    part = changed = outside = 0
    for y in range(height):
        for x in range(width):
            i = 4 * x
            covered = tuple(alone[2][y][i:i + 3]) != background
            differs = plain[2][y][i:i + 4] != highlighted[2][y][i:i + 4]
            part += covered
            changed += differs and covered
            outside += differs and not covered
    print(f"part pixels {part}, changed there {changed}, changed elsewhere {outside}")
    if outside:
        sys.exit(f"FAIL: the highlight changed {outside} pixels where the part is not")
    if part == 0 or changed * 10 < part:
        sys.exit(f"FAIL: the highlight changed only {changed} of the part's {part} pixels")


if __name__ == "__main__":
    main()
