#!/usr/bin/env python3
"""step_import.py OIT DIR WORK: the STEP (AP214 in mm and inches, AP242, AP203)
and IGES files tests/step_gen.cpp wrote
into DIR load as DIR/expected.json says: bounds (millimetres, also from the
file in inches), the parts with their assembly paths (the bolt part placed four
times appears four times), colours and opacities, the file's unit; --tessellation
changes the triangle count (also in a bench scene line); an assembly whose parts are files of their own
loads whole, and without one of them fails naming it; and every exact algorithm (`oit algorithms --json`)
renders the millimetre STEP like the reference (2/255 on all but 0.1% of the
pixels, as tests/cad_exact.sh), on both back ends. The housing's top face and
the cover's bottom face are coincident in the B-rep and must share a coplanar
plane (tie exactly): lifting the cover and its bolts 1 mm (gearbox_apart.step) adds a plane."""
import json
import os
import shutil
import subprocess
import sys

oit, directory, work = sys.argv[1:4]
os.makedirs(work, exist_ok=True)
expected = json.load(open(os.path.join(directory, "expected.json")))
failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL: " + message)


def info(path, *extra):
    run = subprocess.run([oit, "info", "--model", path, "--json", *extra], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("FAIL: oit info %s: exit %d: %s" % (path, run.returncode, run.stderr.strip()))
    return json.loads(run.stdout)


# the bounds' extremes are all on planar faces (box sides, the shaft's ends, the
# bolts' tops), which the tessellation keeps exactly; float rounding of the
# inch file's scaled coordinates is far below this
BOUNDS_TOLERANCE = 1e-3
for entry in expected["files"]:
    name = entry["name"]
    got = info(os.path.join(directory, name))
    for k in range(3):
        check(abs(got["bounds_min"][k] - expected["bounds_min"][k]) <= BOUNDS_TOLERANCE
              and abs(got["bounds_max"][k] - expected["bounds_max"][k]) <= BOUNDS_TOLERANCE,
              "%s: bounds %s .. %s, expected %s .. %s" % (name, got["bounds_min"], got["bounds_max"],
                                                         expected["bounds_min"], expected["bounds_max"]))
    check(got.get("unit") == entry["unit"] and abs(got.get("unit_to_mm", 0) - entry["unit_to_mm"]) < 1e-9,
          "%s: unit %s (%s mm), expected %s (%s mm)" % (name, got.get("unit"), got.get("unit_to_mm"),
                                                     entry["unit"], entry["unit_to_mm"]))
    tessellation = got.get("tessellation", {})
    check(tessellation.get("triangles") == got["triangles"] and tessellation.get("ms", -1) >= 0,
          "%s: tessellation figures missing or wrong: %s" % (name, tessellation))
    parts = {p["path"]: p for p in got["parts"]}
    is_step = entry["tree"]  # the tree, names and every part's colour: STEP
    if is_step:
        check(len(got["parts"]) == len(expected["parts"]),
              "%s: %d parts, expected %d (%s)" % (name, len(got["parts"]), len(expected["parts"]), sorted(parts)))
        check(got["nodes"] == expected["nodes"], "%s: %d assembly nodes, expected %d" % (name, got["nodes"],
                                                                                       expected["nodes"]))
    for want in expected["parts"]:
        if is_step:
            part = parts.get(want["path"])
            check(part is not None, "%s: no part %s (got %s)" % (name, want["path"], sorted(parts)))
        else:
            # OCCT writes IGES flattened (one compound of faces, no names, no
            # transparency): every expected colour must be on some part
            part = next((p for p in got["parts"]
                         if all(abs(a - b) < 0.01 for a, b in zip(p["colour"], want["colour"]))), None)
            check(part is not None, "%s: no part with %s's colour %s" % (name, want["path"], want["colour"]))
        if part is None or entry["colours"] != "parts" or not is_step:
            continue
        check(all(abs(a - b) < 0.005 for a, b in zip(part["colour"], want["colour"])),
              "%s: %s colour %s, expected %s" % (name, want["path"], part["colour"], want["colour"]))
        check(abs(part["opacity"] - want["opacity"]) < 0.005,
              "%s: %s opacity %s, expected %s" % (name, want["path"], part["opacity"], want["opacity"]))

# an assembly whose parts are files of their own, given by a relative path: all
# of it; without one part file, one line naming that file and exit 2
external = os.path.relpath(os.path.join(directory, "external", "gearbox.step"))
check(len(info(external)["parts"]) == len(expected["parts"]), "external/gearbox.step: parts missing")
incomplete = os.path.join(work, "incomplete")
shutil.rmtree(incomplete, ignore_errors=True)
shutil.copytree(os.path.join(directory, "external"), incomplete)
os.remove(os.path.join(incomplete, "bolt.stp"))
run = subprocess.run([oit, "info", "--model", os.path.join(incomplete, "gearbox.step")], capture_output=True, text=True)
check(run.returncode == 2 and run.stderr.count("\n") == 1 and "refers to the file 'bolt.stp'" in run.stderr,
      "without bolt.stp: exit %d, %r" % (run.returncode, run.stderr))

# the tessellation option reaches the worker: coarse < normal < fine triangles, and
# a deflection in millimetres is used as given
step = os.path.join(directory, "gearbox.step")
counts = {level: info(step, "--tessellation", level)["triangles"] for level in ("coarse", "normal", "fine")}
check(counts["coarse"] < counts["normal"] < counts["fine"], "--tessellation: triangles %s" % counts)
check(info(step, "--tessellation", "0.05")["tessellation"]["linear_deflection_mm"] == 0.05,
      "--tessellation 0.05: not the linear deflection used")
print("triangles by --tessellation: %s" % counts)
# and from a bench scene line
scene_list = os.path.join(work, "scenes.txt")
with open(scene_list, "w") as f:
    f.write("coarse %s --tessellation coarse\nfine %s --tessellation fine\n" % (os.path.abspath(step), os.path.abspath(step)))
bench = subprocess.run([oit, "bench", "--scene-list", scene_list, "--algorithms", "ll", "--sizes", "32x32", "--frames", "1"],
                       capture_output=True, text=True)
rows = {line.split(",")[0]: line.split(",") for line in bench.stdout.splitlines()[1:]}
header = bench.stdout.splitlines()[0].split(",") if bench.stdout else []
column = header.index("triangles") if "triangles" in header else None
check(bench.returncode == 0 and column is not None and
      [int(rows[n][column]) for n in ("coarse", "fine")] == [counts["coarse"], counts["fine"]],
      "bench scene lines with --tessellation: exit %d, %s" % (bench.returncode, bench.stdout[-300:] + bench.stderr[-300:]))

# mating faces are coplanar: the housing's top and the cover's bottom share one of
# the model's coplanar planes (they tie exactly), so lifting the cover (with its bolts) 1 mm off
# the housing makes one plane more
planes = info(step)["planes"]
planes_apart = info(os.path.join(directory, "gearbox_apart.step"))["planes"]
check(planes_apart == planes + 1, "mating faces: %d planes, %d with the cover lifted 1 mm (expected one more)"
      % (planes, planes_apart))

# every exact algorithm against the reference, both back ends, two views
algorithms = json.loads(subprocess.run([oit, "algorithms", "--json"], capture_output=True, text=True,
                                       check=True).stdout)
exact = [a["name"] for a in algorithms if a.get("exact") and a["name"] != "reference"]
check(len(exact) >= 4, "fewer than 4 exact algorithms: %s" % exact)
for orbit in ("0,0", "30,25"):
    common = ["--model", step, "--size", "128x128", "--shading", "flat", "--orbit", orbit]
    reference = os.path.join(work, "reference_%s.png" % orbit)
    subprocess.run([oit, "render", *common, "--algorithm", "reference", "--out", reference], check=True,
                   stdout=subprocess.DEVNULL)
    for backend in ("egl", "osmesa"):
        for algorithm in exact:
            image = os.path.join(work, "%s_%s_%s.png" % (algorithm, backend, orbit))
            subprocess.run([oit, "render", *common, "--algorithm", algorithm, "--backend", backend, "--out", image],
                           check=True, stdout=subprocess.DEVNULL)
            compare = subprocess.run([oit, "compare", reference, image, "--tolerance", "2", "--max-mismatch", "0.1"],
                                     capture_output=True, text=True)
            print("%s %s %s: %s" % (algorithm, backend, orbit, compare.stdout.strip()))
            check(compare.returncode == 0, "%s (%s, orbit %s) differs from the reference" % (algorithm, backend, orbit))

if failures:
    sys.exit("FAIL: %d checks failed" % len(failures))
print("STEP/IGES import: %d files, %d parts each, every exact algorithm (%s) matches the reference"
      % (len(expected["files"]), len(expected["parts"]), ", ".join(exact)))
