#!/usr/bin/env bash
# measure.sh OIT WORKDIR SCENES: `oit measure`, the source's measuring command line:
# every task appends one result line of the documented shape; bad arguments are
# exit 2 with one line; 3 rounds of 8 runs at once keep all 24 lines. No timing
# assertions. About 15 s.
source "$(dirname "$0")/lib.sh"
oit=$(cd "$(dirname "$1")" && pwd)/$(basename "$1") work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
# a camera 3 units from the unit-radius onion, row by row as the source's .bat files gave it
mv="1 0 0 0  0 1 0 0  0 0 1 -3  0 0 0 1"
p="1.8 0 0 0  0 1.8 0 0  0 0 -1.2 -2.2  0 0 -1 0"
results=$work/results.txt
for task in 1 2 3 4 5; do
    # shellcheck disable=SC2086
    "$oit" measure --results "$results" --frames 2 --warmup 1 $task 1 "Onion" "$model" $mv $p 32 \
        >"$work/out$task.txt" || fail "measure task $task"
done
# shellcheck disable=SC2086
"$oit" measure --results "$results" --frames 1 --warmup 0 2 2 "Onion" "$model" $mv $p 40x24 >/dev/null \
    || fail "measure with WxH"
python3 - "$results" <<'PY' || fail "measure result lines"
import sys
lines = open(sys.argv[1]).read().splitlines()
assert lines[0].startswith("# oit measure results") and lines[1].startswith("# task\tname\tcounter"), lines[:2]
header = lines[1][2:].split("\t")
assert header == ["task", "name", "counter", "width", "height", "vertices", "triangles", "fragments", "max_list",
                  "psi_percent", "task_ms", "frame_ms", "fps", "stages"], header
rows = [dict(zip(header, l.split("\t"))) for l in lines[2:]]
assert [r["task"] for r in rows] == ["1", "2", "3", "4", "5", "2"], rows
for r in rows:
    assert len(r) == 14 and r["name"] == "Onion", r
    assert int(r["fragments"]) > 0 and int(r["max_list"]) == 8 and float(r["task_ms"]) >= 0 and float(r["fps"]) > 0, r
stages = [dict(s.split("=") for s in r["stages"].split(";")) for r in rows]
assert "neighbours" not in stages[0] and "neighbours" in stages[1], stages[:2]
assert "diffusion" in stages[2] and "blur" not in stages[2], stages[2]
assert "diffusion" in stages[3] and "blur" in stages[3], stages[3]
assert "curvature_distance" in stages[4], stages[4]
assert (rows[0]["width"], rows[0]["height"], rows[5]["width"], rows[5]["height"], rows[5]["counter"]) == ("32", "32", "40", "24", "2")
print("measure lines ok")
PY
grep -q "results.txt" "$work/out1.txt" || fail "measure prints where the line went"
# the default results file: measure_task<TASK>.txt in the working directory, or $OIT_MEASURE_RESULTS
( cd "$work" && "$oit" measure --frames 1 --warmup 0 1 1 Onion "$model" $mv $p 16 >/dev/null ) || fail "default results file"
[ "$(grep -vc '^#' "$work/measure_task1.txt")" = 1 ] || fail "measure_task1.txt must hold one result line"
OIT_MEASURE_RESULTS=$work/env.txt "$oit" measure --frames 1 --warmup 0 1 1 Onion "$model" $mv $p 16 >/dev/null \
    || fail "OIT_MEASURE_RESULTS"
[ -s "$work/env.txt" ] || fail "OIT_MEASURE_RESULTS was not used"

# bad arguments: exit 2, one line, and no result line
before=$(wc -l <"$results")
expect_exit 2 "36 or 37 arguments.*got 4" -- "$oit" measure --results "$results" 1 1 Onion "$model"
expect_exit 2 "got 38" -- "$oit" measure --results "$results" 1 1 Onion "$model" $mv $p 32 extra
expect_exit 2 "TASK must be 1" -- "$oit" measure --results "$results" 6 1 Onion "$model" $mv $p
expect_exit 2 "TASK must be 1" -- "$oit" measure --results "$results" two 1 Onion "$model" $mv $p
expect_exit 2 "COUNTER" -- "$oit" measure --results "$results" 1 -1 Onion "$model" $mv $p
expect_exit 2 "modelview element 5 .*row 1, column 1.*'x'" -- "$oit" measure --results "$results" 1 1 Onion "$model" \
    1 0 0 0 0 x 0 0 0 0 1 -3 0 0 0 1 $p
expect_exit 2 "projection.*not a finite number" -- "$oit" measure --results "$results" 1 1 Onion "$model" $mv 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 nan
expect_exit 2 "projection" -- "$oit" measure --results "$results" 1 1 Onion "$model" $mv 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0
expect_exit 2 "VIEWPORT" -- "$oit" measure --results "$results" 1 1 Onion "$model" $mv $p 0
expect_exit 2 "VIEWPORT" -- "$oit" measure --results "$results" 1 1 Onion "$model" $mv $p 600y600
expect_exit 2 "missing.obj" -- "$oit" measure --results "$results" 1 1 Onion "$work/missing.obj" $mv $p 16
expect_exit 2 "unknown option" -- "$oit" measure --bogus 1 1 Onion "$model" $mv $p
expect_exit 2 "measure: results file .*/no/such/dir/r.txt: the directory .* does not exist" -- "$oit" measure --results "$work/no/such/dir/r.txt" 1 1 Onion "$model" $mv $p 16
[ "$(wc -l <"$results")" = "$before" ] || fail "a refused measure must not append a line"

# runs at once keep every line: 3 rounds of 8 concurrent runs append 24 whole lines, one header
shared=$work/shared.txt
for round in 1 2 3; do
    pids=()
    for k in 1 2 3 4 5 6 7 8; do
        # shellcheck disable=SC2086
        "$oit" measure --results "$shared" --frames 1 --warmup 0 1 "$round$k" Onion "$model" $mv $p 16 >/dev/null &
        pids+=($!)
    done
    for pid in "${pids[@]}"; do wait "$pid" || fail "a concurrent measure failed"; done
done
[ "$(grep -c '^# task' "$shared")" = 1 ] || fail "concurrent runs: the header must be there once"
counters=$(grep -v '^#' "$shared" | awk -F'\t' 'NF == 14 { print $3 }' | sort -n | tr '\n' ' ')
expected=$(for round in 1 2 3; do for k in 1 2 3 4 5 6 7 8; do echo "$round$k"; done; done | sort -n | tr '\n' ' ')
[ "$counters" = "$expected" ] || fail "concurrent runs lost or broke lines: kept $(grep -vc '^#' "$shared") of 24: $counters"
[ -z "$(find "$work" -name '*.tmp.*')" ] || fail "temporary files left by concurrent runs"
echo "measure ok"
