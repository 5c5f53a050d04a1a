#!/usr/bin/env python3
"""kicad_step.py OIT DATA WORK: real KiCad STEP models (tests/data/kicad, with
their .wrl twins from the same Debian package) load with their real size and
colours: the bounding box within 2% (of the box's diagonal) of the .wrl's, whose
unit is 0.1 inch = 2.54 mm; every colour the .wrl's shapes use (diffuseColor
of a material that is USEd) on some part within 0.01; and the resistor renders like the reference with each exact
algorithm (2/255, at most 0.1% of the pixels over, as tests/cad_exact.sh)."""
import json
import math
import os
import re
import subprocess
import sys

oit, data, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
WRL_UNIT_MM = 2.54
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)


def wrl_box_and_colours(path):
    text = open(path).read()
    lo, hi = [math.inf] * 3, [-math.inf] * 3
    for block in re.findall(r"point\s*\[([^\]]*)\]", text):
        numbers = [float(x) for x in re.split(r"[\s,]+", block.strip()) if x]
        for i in range(0, len(numbers) - 2, 3):
            for k in range(3):
                lo[k] = min(lo[k], numbers[i + k] * WRL_UNIT_MM)
                hi[k] = max(hi[k], numbers[i + k] * WRL_UNIT_MM)
    # the materials the shapes use (a .wrl may define one it never uses)
    used = set(re.findall(r"USE\s+([\w-]+)", text))
    colours = [tuple(float(x) for x in m[1:]) for m in
               re.findall(r"DEF\s+([\w-]+)\s+Material\s*\{[^}]*?diffuseColor\s+(\S+)\s+(\S+)\s+(\S+)", text)
               if m[0] in used]
    return lo, hi, colours


models = sorted(f for f in os.listdir(data) if f.endswith(".step"))
check(len(models) >= 3, "fewer than 3 models in %s" % data)
for model in models:
    path = os.path.join(data, model)
    run = subprocess.run([oit, "info", "--model", path, "--json"], capture_output=True, text=True)
    if run.returncode != 0:
        check(False, "%s: exit %d: %s" % (model, run.returncode, run.stderr.strip()))
        continue
    got = json.loads(run.stdout)
    lo, hi, colours = wrl_box_and_colours(path[:-5] + ".wrl")
    diagonal = math.dist(lo, hi)
    worst = max(max(abs(got["bounds_min"][k] - lo[k]), abs(got["bounds_max"][k] - hi[k])) for k in range(3))
    print("%s: bounds %s .. %s, .wrl %s .. %s: off by %.2f%% of the diagonal; unit %s; %d triangles in %.1f ms"
          % (model, got["bounds_min"], got["bounds_max"], [round(x, 4) for x in lo], [round(x, 4) for x in hi],
             100 * worst / diagonal, got.get("unit"), got["triangles"], got["tessellation"]["ms"]))
    check(worst <= 0.02 * diagonal, "%s: bounds off the .wrl's by %g mm (more than 2%% of %g)" % (model, worst, diagonal))
    check(len(colours) > 0, "%s: the .wrl has no colours" % model)
    for colour in set(colours):
        check(any(all(abs(a - b) <= 0.01 for a, b in zip(p["colour"], colour)) for p in got["parts"]),
              "%s: no part has the .wrl's colour %s (parts: %s)" % (model, colour, [p["colour"] for p in got["parts"]]))

algorithms = json.loads(subprocess.run([oit, "algorithms", "--json"], capture_output=True, text=True,
                                       check=True).stdout)
exact = [a["name"] for a in algorithms if a.get("exact") and a["name"] != "reference"]
resistor = os.path.join(data, "R_0603_1608Metric.step")
common = ["--model", resistor, "--size", "128x128", "--shading", "flat", "--orbit", "30,25"]
reference = os.path.join(work, "reference.png")
subprocess.run([oit, "render", *common, "--algorithm", "reference", "--out", reference], check=True,
               stdout=subprocess.DEVNULL)
for algorithm in exact:
    image = os.path.join(work, algorithm + ".png")
    subprocess.run([oit, "render", *common, "--algorithm", algorithm, "--out", image], check=True,
                   stdout=subprocess.DEVNULL)
    compare = subprocess.run([oit, "compare", reference, image, "--tolerance", "2", "--max-mismatch", "0.1"],
                             capture_output=True, text=True)
    print("R_0603 %s: %s" % (algorithm, compare.stdout.strip()))
    check(compare.returncode == 0, "R_0603: %s differs from the reference" % algorithm)
if failures:
    sys.exit("FAIL: %d checks failed" % len(failures))
print("KiCad STEP: %d models within 2%% of their .wrl with their colours; %s exact on R_0603"
      % (len(models), ", ".join(exact)))
