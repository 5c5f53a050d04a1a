#!/usr/bin/env python3
"""turntable_check.py TURNTABLE.json SINGLE.json N [view]: the matrices of
`oit render --turntable N --json` are the orbit (docs/cli.md, "Turntables"):
frame 0 is the camera of the single render (SINGLE.json, the same flags
without --turntable), frame i is frame 0 turned by 360 i/N degrees about the
up axis (model y, or with "view" the direction frame 0 shows as up) through
the model's centre, and the centre's eye position and the axis's eye direction
stay; each step turns by 360/N. Within 1e-9 (relative to the matrix's size).
Prints each frame's modelview and projection, row by row, comma-separated."""
import json
import math
import sys

turntable = json.load(open(sys.argv[1]))
single = json.load(open(sys.argv[2]))
n = int(sys.argv[3])
up = sys.argv[4] if len(sys.argv) > 4 else "y"


def matrix(rows):  # row by row -> m[r][c]
    return [rows[r * 4:r * 4 + 4] for r in range(4)]


def apply(m, v, w):
    return [sum(m[r][c] * (v[c] if c < 3 else w) for c in range(4)) for r in range(3)]


def close(a, b, scale, what):
    if abs(a - b) > 1e-9 * scale:
        sys.exit(f"{what}: {a!r} vs {b!r}")


frames = turntable["frames"]
assert len(frames) == n, f"{len(frames)} frames, expected {n}"
assert turntable["projection"] == single["projection"], "the projection is not the camera's"
m0 = matrix(frames[0]["modelview"])
assert frames[0]["modelview"] == single["modelview"], "frame 0 is not the camera given (bit for bit)"
centre = turntable["centre"]
axis = turntable["axis"]
if up == "view":  # the direction M0 takes to eye +y
    linear = [row[:3] for row in m0[:3]]
    want = [linear[1][c] for c in range(3)]  # rows of a rotation: its inverse's column 1
    length = math.sqrt(sum(x * x for x in want))
    want = [x / length for x in want]
else:
    want = [0.0, 1.0, 0.0]
for c in range(3):
    close(axis[c], want[c], 1.0, "the axis")
scale = max(abs(x) for x in frames[0]["modelview"])
eye_centre = apply(m0, centre, 1.0)
eye_axis = apply(m0, axis, 0.0)
for i, frame in enumerate(frames):
    assert frame["index"] == i
    m = matrix(frame["modelview"])
    close(frame["degrees"], 360.0 * i / n, 1.0, f"frame {i}'s angle")
    # the centre and the axis stay where they are in the image
    for a, b in zip(apply(m, centre, 1.0), eye_centre):
        close(a, b, scale, f"frame {i}: the centre's eye position")
    for a, b in zip(apply(m, axis, 0.0), eye_axis):
        close(a, b, scale, f"frame {i}: the axis's eye direction")
    # a direction across the axis turns by 360 i / N (the camera's orbit: the model by -angle)
    across = [axis[1] * 1.0 - axis[2] * 0.0, axis[2] * 0.0 - axis[0] * 1.0, 0.0]  # axis x (0, 0, 1)
    if math.sqrt(sum(x * x for x in across)) < 0.5:
        across = [0.0, axis[2], -axis[1]]  # axis x (1, 0, 0)
    length = math.sqrt(sum(x * x for x in across))
    across = [x / length for x in across]
    other = [axis[1] * across[2] - axis[2] * across[1], axis[2] * across[0] - axis[0] * across[2],
             axis[0] * across[1] - axis[1] * across[0]]
    angle = -2.0 * math.pi * i / n
    turned = [math.cos(angle) * across[k] + math.sin(angle) * other[k] for k in range(3)]
    for a, b in zip(apply(m, across, 0.0), apply(m0, turned, 0.0)):
        close(a, b, scale, f"frame {i}: the turn")
    print(",".join(repr(x) for x in frame["modelview"]), ",".join(repr(x) for x in turntable["projection"]))
print(f"ok: {n} frames turn by {360.0 / n} degrees about {axis} through {centre}", file=sys.stderr)
