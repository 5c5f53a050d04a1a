#!/usr/bin/env bash
# bench.sh OIT WORKDIR SCENES: `oit bench` at tiny sizes: the CSV and JSON shape,
# one row per scene x algorithm x size, medians within min..max, the reference
# difference of the exact algorithms, --scenes filtering, failed runs as rows,
# and bad arguments. No timing assertions.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"

"$oit" bench --model "$scenes/onion.obj" --algorithms blend,dp,ll,ll-array,ib --sizes 32,40x24 \
    --frames 3 --warmup 1 --reference-max-pixels 1024 --csv "$work/one.csv" --json "$work/one.json" \
    2>"$work/one.err" || { cat "$work/one.err"; fail "bench on onion"; }
grep -q "bench \[10/10\] onion ib 40x24" "$work/one.err" || { cat "$work/one.err"; fail "no progress lines on stderr"; }
python3 - "$work/one.csv" "$work/one.json" <<'PY' || fail "bench CSV/JSON shape"
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1])))
expected = ["scene", "model", "view", "algorithm", "width", "height", "vertices", "triangles", "components",
            "warmup", "frames", "cpu_ms_median", "cpu_ms_min", "cpu_ms_max", "gpu_ms_median", "gpu_ms_min",
            "gpu_ms_max", "memory_bytes", "scene_bytes", "fragments", "max_list", "mean_list", "psi", "layers",
            "overflow_retries", "bytes_per_fragment", "ref_max_diff", "ref_mean_diff",
            "ref_over_tolerance_percent", "error_rmse", "error_psnr", "error_ssim", "error_max",
            "error_share_over_2", "error_flip", "flicker", "flicker_max", "orbit_rmse_mean", "stages",
            "list_histogram", "scene_histogram", "error"]
assert list(rows[0].keys()) == expected, list(rows[0].keys())
assert len(rows) == 10, len(rows)
assert [(r["algorithm"], r["width"]) for r in rows[:5]] == [(a, "32") for a in ["blend", "dp", "ll", "ll-array", "ib"]], rows
for r in rows:
    assert r["error"] == "" and r["scene"] == "onion" and r["frames"] == "3" and r["warmup"] == "1", r
    for k in ("cpu_ms", "gpu_ms"):
        lo, med, hi = float(r[k + "_min"]), float(r[k + "_median"]), float(r[k + "_max"])
        assert 0 <= lo <= med <= hi, (k, r)
    assert int(r["memory_bytes"]) > 0 and int(r["scene_bytes"]) > 0, r
    stages = dict(s.split("=") for s in r["stages"].split(";"))
    for v in stages.values():
        lo_hi = [float(x) for x in v.split("/")]
        assert lo_hi[1] <= lo_hi[0] <= lo_hi[2], r
    if r["algorithm"] in ("ll", "ll-array", "ib"):
        assert int(r["fragments"]) > 0 and int(r["max_list"]) == 8 and 0 <= float(r["psi"]) <= 1, r
    if r["algorithm"] == "ib":
        assert {"fill", "sort", "neighbours", "compose"} <= set(stages), stages
        # the neighbour-quality pass is a diagnostic: not in timed frames
        assert "neighbour_stats" not in stages, stages
    same = [q for q in rows if q["algorithm"] == "ll" and q["width"] == r["width"] and q["height"] == r["height"]]
    if r["algorithm"] in ("ll-array", "ib") and same:
        # the same lists, counted by different passes
        for k in ("fragments", "max_list", "psi"):
            assert r[k] == same[0][k], (k, r[k], same[0][k])
    if r["algorithm"] == "dp":
        assert int(r["layers"]) == 8 and "peel_0" in stages, r
    # 32x32 = 1024 pixels: compared with the reference; 40x24 = 960 too
    assert r["ref_max_diff"] != "", r
    if r["algorithm"] != "blend":
        assert int(r["ref_max_diff"]) <= 2 and float(r["ref_over_tolerance_percent"]) <= 1.0, r
data = json.load(open(sys.argv[2]))
for key in ("date", "renderer", "backend", "machine", "command", "warmup", "frames", "results", "failures"):
    assert key in data, key
assert data["failures"] == 0 and len(data["results"]) == 10, data["failures"]
ib = [r for r in data["results"] if r["algorithm"] == "ib"][0]
for key in ("scene", "model", "view", "width", "height", "vertices", "triangles", "cpu_ms", "gpu_ms", "stages",
            "memory_bytes", "fragments", "max_list", "psi", "bytes_per_fragment", "reference"):
    assert key in ib, key
assert set(ib["cpu_ms"]) == {"median", "min", "max"} and all(set(s) == {"name", "median", "min", "max"} for s in ib["stages"])
print("bench CSV and JSON ok:", len(rows), "rows")
PY

# a scene list, --scenes patterns, a view per scene, a scene that fails
cat >"$work/scenes.txt" <<LIST
# name model options
onion-front $scenes/onion.obj --orbit 0,0
onion-side  $scenes/onion.obj --orbit 90,30   # a comment
spheres     $scenes/spheres.obj --alpha 0.3
LIST
"$oit" bench --scene-list "$work/scenes.txt" --scenes 'onion-*' --algorithms ll --sizes 24 --frames 1 --warmup 0 \
    --quiet --reference-max-pixels 0 >"$work/list.csv" || fail "bench with a scene list"
python3 - "$work/list.csv" <<'PY' || fail "scene list rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["scene"] for r in rows] == ["onion-front", "onion-side"], rows
assert rows[1]["view"] == "--orbit 90,30" and rows[0]["ref_max_diff"] == "", rows
print("scene list ok")
PY
# a model path relative to the list's folder (whatever the working directory), a quoted path
# with a blank, a quoted name, a UTF-8 byte order mark before the first line
mkdir -p "$work/lists/my models"
cp "$scenes/onion.obj" "$scenes/onion.mtl" "$work/lists/my models/"
printf '\xef\xbb\xbfbom-first "my models/onion.obj" --alpha 0.3\nrelative '"'"'my models/onion.obj'"'"'  # a comment\n"with blank" "my models/onion.obj" --orbit "30,20"\n' \
    >"$work/lists/quoted.txt"
oit_path=$(realpath "$oit")
( cd / && "$oit_path" bench --scene-list "$work/lists/quoted.txt" --algorithms ll --sizes 16 --frames 1 --warmup 0 \
      --quiet --reference-max-pixels 0 ) >"$work/quoted.csv" || fail "bench with a quoted, relative scene list"
python3 - "$work/quoted.csv" "$work/lists/my models/onion.obj" <<'PY' || fail "quoted, relative scene list rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["scene"] for r in rows] == ["bom-first", "relative", "with blank"], [r["scene"] for r in rows]
assert all(r["model"] == sys.argv[2] and r["error"] == "" for r in rows), rows
assert [r["view"] for r in rows] == ["--alpha 0.3", "", "--orbit 30,20"], [r["view"] for r in rows]
print("quoted, relative scene list ok")
PY
printf 'open "my models/onion.obj\n' >"$work/lists/open.txt"
expect_exit 2 "open.txt:1: a quote is not closed" -- "$oit" bench --scene-list "$work/lists/open.txt"
printf 'missing %s/missing.obj\nonion %s/onion.obj\n' "$work" "$scenes" >"$work/failing.txt"
expect_exit 3 "1 run\(s\) failed" -- "$oit" bench --scene-list "$work/failing.txt" --algorithms ll --sizes 16 \
    --frames 1 --warmup 0 --quiet --csv "$work/failing.csv"
python3 - "$work/failing.csv" <<'PY' || fail "a failed run must be a row with its error"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 2 and "missing.obj" in rows[0]["error"] and rows[1]["error"] == "" and rows[1]["fragments"], rows
print("failed run recorded")
PY

# bad arguments: exit 2, one line
expect_exit 2 "scene-list|--model" -- "$oit" bench --algorithms ll
expect_exit 2 "unknown algorithm 'nope'" -- "$oit" bench --model "$scenes/onion.obj" --algorithms ll,nope
expect_exit 2 "sizes" -- "$oit" bench --model "$scenes/onion.obj" --sizes 0x10
expect_exit 2 "sizes" -- "$oit" bench --model "$scenes/onion.obj" --sizes 99999
expect_exit 2 "frames" -- "$oit" bench --model "$scenes/onion.obj" --frames 0
expect_exit 2 "matches none" -- "$oit" bench --scene-list "$work/scenes.txt" --scenes 'zzz*'
expect_exit 2 "scenes.txt" -- "$oit" bench --scene-list "$work/nonexistent/scenes.txt"
printf 'onion %s/onion.obj --orbit banana\n' "$scenes" >"$work/bad.txt"
expect_exit 2 "bad.txt:1: scene 'onion'.*orbit" -- "$oit" bench --scene-list "$work/bad.txt"
printf 'lonely\n' >"$work/short.txt"
expect_exit 2 "short.txt:1.*NAME MODEL" -- "$oit" bench --scene-list "$work/short.txt"
printf 'a %s/onion.obj\na %s/onion.obj\n' "$scenes" "$scenes" >"$work/twice.txt"
expect_exit 2 "named twice" -- "$oit" bench --scene-list "$work/twice.txt"
expect_exit 2 "not a bench option" -- "$oit" bench --model "$scenes/onion.obj" --algorithm ll
expect_exit 2 "unknown option" -- "$oit" bench --model "$scenes/onion.obj" --bogus
expect_exit 2 "--csv .*/x.csv: the directory .*/no/such/dir does not exist" -- "$oit" bench --model "$scenes/onion.obj" --csv "$work/no/such/dir/x.csv"
expect_exit 2 "--json .*/x.json: the directory .*/no/such/dir does not exist" -- "$oit" bench --model "$scenes/onion.obj" --json "$work/no/such/dir/x.json"
printf 'onion %s/onion.obj --hide 0\n' "$scenes" >"$work/local.txt"
expect_exit 2 "local.txt:1: scene 'onion': --hide applies to every scene" -- "$oit" bench --scene-list "$work/local.txt"
echo "bench ok"
