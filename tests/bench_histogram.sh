#!/usr/bin/env bash
# bench_histogram.sh OIT WORKDIR SCENES: the depth-complexity histograms of
# `oit bench`'s rows. list_histogram is the algorithm's own (ll, ib, kbuffer,
# hybrid, reference; none for blend, dp, wboit ...), scene_histogram the CPU
# reference frame's, on every row of the scene and size when bench rendered
# the reference. Both sum to width x height, are equal to each other where an
# exact algorithm has one, and equal `oit render --json`'s list_histogram for
# the same scene; the CSV holds the same counts (';'-joined, trailing zero bins
# left out) as the JSON.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"

"$oit" bench --model "$scenes/spheres.obj" --algorithms blend,ll,kbuffer:4 --sizes 64 --frames 1 --warmup 0 --quiet \
    --csv "$work/bench.csv" --json "$work/bench.json" || fail "bench"
"$oit" render --model "$scenes/spheres.obj" --algorithm ll --size 64x64 --json >"$work/render.json" || fail "render"
"$oit" bench --model "$scenes/spheres.obj" --algorithms blend,ll --sizes 64 --frames 1 --warmup 0 --quiet \
    --reference-max-pixels 0 --csv "$work/noref.csv" --json "$work/noref.json" || fail "bench without the reference"
python3 - "$work" <<'PY' || fail "bench histograms"
import csv, json, os, sys
work = sys.argv[1]
BINS = 65  # OIT_HISTOGRAM_BINS
render = json.load(open(os.path.join(work, "render.json")))["list_histogram"]
pixels = 64 * 64
assert len(render) == BINS and sum(render) == pixels, render
assert sum(1 for c in render[2:] if c) >= 2, ("a scene with several depths wanted", render)

def from_csv(field):
    counts = [int(c) for c in field.split(";")] if field else []
    assert not counts or counts[-1] != 0 or len(counts) == 1, field  # trailing zero bins left out
    return counts + [0] * (BINS - len(counts)) if counts else None

rows = {r["algorithm"]: r for r in csv.DictReader(open(os.path.join(work, "bench.csv")))}
results = {r["algorithm"]: r for r in json.load(open(os.path.join(work, "bench.json")))["results"]}
assert set(rows) == set(results) == {"blend", "ll", "kbuffer:4"}, (rows.keys(), results.keys())
for name in rows:
    scene_csv, scene_json = from_csv(rows[name]["scene_histogram"]), results[name]["scene_histogram"]
    assert scene_csv == scene_json == render, (name, scene_csv, scene_json, render)
    if name == "blend":  # no lists: no histogram of its own
        assert rows[name]["list_histogram"] == "" and "list_histogram" not in results[name], name
    else:  # ll's lists, and kbuffer's count every fragment (not only the 4 it keeps)
        assert from_csv(rows[name]["list_histogram"]) == results[name]["list_histogram"] == render, name
# the histogram's fragments (no list reaches the open last bin here): ll's fragment count
assert render[-1] == 0 and sum(i * c for i, c in enumerate(render)) == int(rows["ll"]["fragments"]), render
rows = list(csv.DictReader(open(os.path.join(work, "noref.csv"))))
results = json.load(open(os.path.join(work, "noref.json")))["results"]
for r, j in zip(rows, results):  # no reference rendered: no scene histogram
    assert r["scene_histogram"] == "" and "scene_histogram" not in j, r
    assert (r["list_histogram"] != "") == (r["algorithm"] == "ll") == ("list_histogram" in j), r
print("bench histograms ok:", pixels, "pixels,", sum(1 for c in render if c), "non-empty bins")
PY
