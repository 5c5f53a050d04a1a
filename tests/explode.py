#!/usr/bin/env python3
"""explode.py OIT WORK GEARBOX ASSEMBLY_GLTF_PY: the exploded view (docs/sections.md,
"Exploded view"), at 128x128.

- bad --explode factors (-1, 11, nan, abc, none) fail with one line naming the flag;
- --explode 0 writes the same PNG bytes as no flag (ll and the reference);
- every part's offset in `render --json` follows the rule, recomputed here from
  `info --json`'s per-part bounds (relative coordinates, float exact): without a
  tree on the gearbox, along the assembly tree on tests/assembly_gltf.py's glTF
  (nodes read off the parts' paths); within 1e-5 of the model's size times F;
- exploded, the exact algorithms (dp, ll, ib) match the reference within the
  exact tolerance (2/255 on all but 1% of pixels);
- pick follows the moved parts: at a pixel inside one exploded part's screen
  box and no other's (nor its own unexploded one), the pick with --explode
  names that part, and without it does not.
"""
import json
import os
import subprocess
import sys

OIT, WORK, GEARBOX, ASSEMBLY_PY = sys.argv[1:5]
SIZE = "128x128"
EXACT_TOLERANCE, EXACT_MISMATCH = "2", "1.0"
os.makedirs(WORK, exist_ok=True)
failures = []


def fail(message):
    print("FAIL:", message)
    failures.append(message)


def run(*args, expect=0):
    p = subprocess.run([OIT, *args], capture_output=True, text=True)
    if p.returncode != expect:
        fail(f"oit {' '.join(args)}: exit {p.returncode} (expected {expect}): {p.stderr.strip()}")
    return p


def render(model, *args):
    p = run("render", "--model", model, "--size", SIZE, *args)
    return p


def read(path):
    with open(path, "rb") as f:
        return f.read()


# --- bad factors: one line, exit 2, naming the flag
for bad in ["-1", "11", "nan", "abc", "inf", "10.0001"]:
    p = run("render", "--model", GEARBOX, "--explode", bad, expect=2)
    lines = p.stderr.strip().splitlines()
    if len(lines) != 1 or "--explode" not in lines[0] or p.stdout:
        fail(f"--explode {bad}: expected one error line naming --explode, got {p.stderr!r}")
p = run("render", "--model", GEARBOX, "--explode", expect=2)
if "--explode needs a value" not in p.stderr:
    fail(f"--explode without a value: {p.stderr!r}")
p = run("pick", "--model", GEARBOX, "--pixel", "1,1", "--explode", "-1", expect=2)
if len(p.stderr.strip().splitlines()) != 1 or "--explode" not in p.stderr:
    fail(f"pick --explode -1: {p.stderr!r}")

# --- --explode 0 is the model as built, byte for byte
for algorithm in ["ll", "reference"]:
    plain, zero = f"{WORK}/{algorithm}_plain.png", f"{WORK}/{algorithm}_zero.png"
    render(GEARBOX, "--algorithm", algorithm, "--out", plain)
    p = render(GEARBOX, "--algorithm", algorithm, "--explode", "0", "--out", zero, "--json")
    zero_json = json.loads(p.stdout) if p.returncode == 0 else {}
    if zero_json.get("explode") != 0 or "parts" in zero_json:
        fail(f"{algorithm}: --explode 0 --json: \"explode\" {zero_json.get('explode')}, parts' offsets listed: "
             f"{'parts' in zero_json}")
    if not (os.path.exists(plain) and os.path.exists(zero)) or read(plain) != read(zero):
        fail(f"{algorithm}: --explode 0 is not byte-identical to no --explode")


# --- the rule, recomputed from the parts' bounding boxes
def info(model):
    p = run("info", "--model", model, "--json")
    return json.loads(p.stdout)


def union(boxes):
    boxes = [b for b in boxes if b]
    if not boxes:
        return None
    return ([min(b[0][k] for b in boxes) for k in range(3)], [max(b[1][k] for b in boxes) for k in range(3)])


def centre(box):
    return [0.5 * (box[0][k] + box[1][k]) for k in range(3)]


def expected_offsets(model_info, factor):
    """oit.h's rule: no tree, part - model; with one, the sum from the top of
    child - parent, nodes being the parts' paths' prefixes."""
    parts = model_info["parts"]
    boxes = [(p["relative_bounds_min"], p["relative_bounds_max"]) if "relative_bounds_min" in p else None
             for p in parts]
    top = union(boxes)
    nodes = {}  # node path -> box of every part under it
    chains = []
    for p, box in zip(parts, boxes):
        segments = p["path"].split("/")[:-1] if model_info["nodes"] else []
        chain = ["/".join(segments[:i + 1]) for i in range(len(segments))]
        chains.append(chain)
        for node in chain:
            nodes[node] = union([nodes.get(node), box])
    result = []
    for box, chain in zip(boxes, chains):
        offset = [0.0, 0.0, 0.0]
        parent = top
        for child in [nodes[n] for n in chain] + [box]:
            if child and parent:
                c, q = centre(child), centre(parent)
                offset = [offset[k] + factor * (c[k] - q[k]) for k in range(3)]
            parent = child
        result.append(offset)
    return result, top


def check_offsets(label, model, factor, has_tree, out):
    model_info = info(model)
    if has_tree != (model_info["nodes"] > 0):
        fail(f"{label}: expected {'a' if has_tree else 'no'} assembly tree, info says {model_info['nodes']} nodes")
    p = render(model, "--algorithm", "reference", "--explode", str(factor), "--json", "--out", out)
    try:
        result = json.loads(p.stdout)
    except ValueError:
        fail(f"{label}: render --json printed no JSON: {p.stdout!r}")
        return None
    if result.get("explode") != factor:
        fail(f"{label}: \"explode\" is {result.get('explode')}, expected {factor}")
    expected, top = expected_offsets(model_info, factor)
    size = max(top[1][k] - top[0][k] for k in range(3))
    got = result.get("parts", [])
    if len(got) != len(expected):
        fail(f"{label}: {len(got)} parts' offsets for {len(expected)} parts")
        return None
    worst = 0.0
    moved = 0
    for part, info_part, want in zip(got, model_info["parts"], expected):
        if part["name"] != info_part["name"]:
            fail(f"{label}: part {part['name']} where info has {info_part['name']}")
        error = max(abs(part["offset"][k] - want[k]) for k in range(3))
        worst = max(worst, error / (factor * size))
        moved += any(abs(w) > 1e-3 * size for w in want)
        if error > 1e-5 * factor * size:
            fail(f"{label}: part {part['name']}: offset {part['offset']}, the rule gives {want}")
    if moved < 2:
        fail(f"{label}: only {moved} parts move: the check shows nothing")
    print(f"{label}: {len(got)} parts' offsets checked against the rule (worst {worst:.2e} of F x size {size:.4g}); "
          f"{moved} move")
    return result, model_info


assembly = f"{WORK}/assembly.gltf"
subprocess.run([sys.executable, ASSEMBLY_PY, assembly], check=True, capture_output=True)
cases = [("gearbox", GEARBOX, 1.5, False), ("assembly", assembly, 0.75, True)]
exploded = None
for label, model, factor, has_tree in cases:
    reference = f"{WORK}/{label}_exploded_reference.png"
    checked = check_offsets(label, model, factor, has_tree, reference)
    if has_tree:
        exploded = checked

# --- exploded, the exact algorithms are the reference's image (the one the
# offsets' render wrote); and not the image of the assembly as built
for label, model, factor, _ in cases:
    reference = f"{WORK}/{label}_exploded_reference.png"
    for algorithm in ["dp", "ll", "ib"]:
        image = f"{WORK}/{label}_exploded_{algorithm}.png"
        render(model, "--algorithm", algorithm, "--explode", str(factor), "--out", image)
        p = run("compare", image, reference, "--tolerance", EXACT_TOLERANCE, "--max-mismatch", EXACT_MISMATCH)
        print(f"{label} --explode {factor}, {algorithm} vs reference: {p.stdout.strip()}")
    plain = f"{WORK}/reference_plain.png" if model == GEARBOX else f"{WORK}/{label}_plain_reference.png"
    if model != GEARBOX:
        render(model, "--algorithm", "reference", "--out", plain)
    if os.path.exists(plain) and os.path.exists(reference) and read(plain) == read(reference):
        fail(f"{label}: --explode {factor} drew the same image as the assembly as built")


# --- pick follows the moved parts
def project(rows_mv, rows_p, point):
    """pixel (x from the left, y from the top) of a file-coordinates point"""
    v = [point[0], point[1], point[2], 1.0]
    eye = [sum(rows_mv[r][c] * v[c] for c in range(4)) for r in range(4)]
    clip = [sum(rows_p[r][c] * eye[c] for c in range(4)) for r in range(4)]
    w = 128
    return ((clip[0] / clip[3] * 0.5 + 0.5) * w, (1.0 - (clip[1] / clip[3] * 0.5 + 0.5)) * w)


def screen_box(rows_mv, rows_p, origin, box, offset):
    xs, ys = [], []
    for i in range(8):
        corner = [origin[k] + (box[1][k] if i >> k & 1 else box[0][k]) + offset[k] for k in range(3)]
        x, y = project(rows_mv, rows_p, corner)
        xs.append(x)
        ys.append(y)
    return min(xs), min(ys), max(xs), max(ys)


def inside(rect, x, y, margin=1.5):
    return rect[0] - margin <= x <= rect[2] + margin and rect[1] - margin <= y <= rect[3] + margin


if exploded:
    result, model_info = exploded
    mv = [result["modelview"][r * 4:(r + 1) * 4] for r in range(4)] if len(result["modelview"]) == 16 \
        else result["modelview"]
    pr = [result["projection"][r * 4:(r + 1) * 4] for r in range(4)] if len(result["projection"]) == 16 \
        else result["projection"]
    origin = model_info["centre"]
    parts = model_info["parts"]
    boxes = [(p["relative_bounds_min"], p["relative_bounds_max"]) for p in parts]
    offsets = [p["offset"] for p in result["parts"]]
    moved = [screen_box(mv, pr, origin, b, o) for b, o in zip(boxes, offsets)]
    still = [screen_box(mv, pr, origin, b, [0, 0, 0]) for b in boxes]
    matrix = lambda rows: ",".join(repr(float(x)) for row in rows for x in row)
    tried = 0
    for i, part in enumerate(parts):
        x = round(0.5 * (moved[i][0] + moved[i][2]) - 0.5)
        y = round(0.5 * (moved[i][1] + moved[i][3]) - 0.5)
        cx, cy = x + 0.5, y + 0.5
        if not (0 <= x < 128 and 0 <= y < 128) or inside(still[i], cx, cy):
            continue
        if any(inside(moved[j], cx, cy) for j in range(len(parts)) if j != i):
            continue
        tried += 1
        if tried > 2:
            break
        camera = ["--modelview", matrix(mv), "--projection", matrix(pr), "--size", SIZE]
        p = run("pick", "--model", assembly, "--explode", "0.75", "--pixel", f"{x},{y}", "--json", *camera)
        got = json.loads(p.stdout).get("part") if p.returncode == 0 else None
        if got != part["name"]:
            fail(f"pick at {x},{y}, --explode 0.75: {got}, expected the moved part {part['name']}")
        p = run("pick", "--model", assembly, "--pixel", f"{x},{y}", "--json", *camera)
        still_got = json.loads(p.stdout).get("part") if p.returncode == 0 else None
        if still_got == part["name"]:
            fail(f"pick at {x},{y} without --explode also names {part['name']}: the check shows nothing")
        print(f"pick at {x},{y}: {got} when exploded, {still_got} as built")
    if tried == 0:
        fail("no part of the exploded assembly has a pixel of its own to pick")

if failures:
    print(f"{len(failures)} failures")
    sys.exit(1)
print("explode: all checks passed")
