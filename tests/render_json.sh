#!/usr/bin/env bash
# render_json.sh OIT WORKDIR SCENES: the --json contract, --frames medians,
# and that the fragment pool grows instead of dropping fragments.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
check_json() { # FILE KEY...
    local file=$1; shift
    python3 - "$file" "$@" <<'PY' || fail "JSON check failed for $1"
import json, sys
data = json.load(open(sys.argv[1]))
for key in sys.argv[2:]:
    assert key in data, f"missing key {key} in {data}"
assert data["gpu_ms"] >= 0 and data["cpu_ms"] > 0, data
assert abs(sum(s["gpu_ms"] for s in data["stages"]) - data["gpu_ms"]) < 1e-2 + 1e-3 * data["gpu_ms"], data
assert all(s["name"] for s in data["stages"]), data
print(sys.argv[1], "ok:", {k: data[k] for k in sys.argv[2:] if k != "stages"})
PY
}
common="algorithm width height frames gpu_ms cpu_ms stages memory_bytes"
"$oit" render --model "$scenes/onion.obj" --algorithm ll --size 64x64 --frames 3 --json >"$work/ll.json" || fail "ll render"
check_json "$work/ll.json" $common fragments max_list overflow_retries
python3 -c "import json,sys; d=json.load(open('$work/ll.json')); assert d['frames']==3 and d['max_list']==8 and d['fragments']>0, d" \
    || fail "ll on onion (4 nested spheres) must report frames 3 and a longest list of 8"
"$oit" render --model "$scenes/onion.obj" --algorithm dp --size 64x64 --json >"$work/dp.json" || fail "dp render"
check_json "$work/dp.json" $common layers
python3 -c "import json; d=json.load(open('$work/dp.json')); assert d['layers']==8, d; assert [s['name'] for s in d['stages']][:2]==['peel_0','peel_1'], d" \
    || fail "dp on onion must peel 8 layers, one stage per peel"
# every algorithm the build lists (`oit algorithms --json`: a new one is checked without a line here)
every_algorithm=$("$oit" algorithms --json | python3 -c "import json, sys; print(' '.join(a['name'] for a in json.load(sys.stdin)))") \
    || fail "oit algorithms --json"
for algorithm in $every_algorithm; do
    "$oit" render --model "$scenes/onion.obj" --algorithm $algorithm --size 64x64 --json >"$work/$algorithm.json" || fail "$algorithm render"
    check_json "$work/$algorithm.json" $common
done
"$oit" render --model "$scenes/onion.obj" --algorithm mlab --size 64x64 --frames 3 --json \
    >"$work/mlab.json" || fail "mlab render"
check_json "$work/mlab.json" $common fragments max_list mean_list bytes_per_pixel

# Overflow: a tiny initial pool makes ll grow the pool and render the frame
# again; the image must be the same and the retries must be counted.
for sort in insertion array; do
    "$oit" render --model "$scenes/menger.obj" --algorithm ll --sort $sort --size 128x128 --json --out "$work/menger_$sort.png" >"$work/menger_$sort.json" || fail "menger ll $sort"
    "$oit" render --model "$scenes/menger.obj" --algorithm ll --sort $sort --size 128x128 --fragment-pool 1000 --json --out "$work/menger_small_$sort.png" >"$work/menger_small_$sort.json" || fail "menger ll small pool $sort"
    "$oit" compare "$work/menger_$sort.png" "$work/menger_small_$sort.png" || fail "pool growth changed the image ($sort)"
    python3 -c "
import json
big = json.load(open('$work/menger_$sort.json')); small = json.load(open('$work/menger_small_$sort.json'))
assert small['overflow_retries'] >= 1, small
assert small['fragments'] == big['fragments'] and small['max_list'] == big['max_list'], (big, small)
print('$sort: pool grew', small['overflow_retries'], 'time(s); fragments', small['fragments'])
" || fail "overflow was not reported ($sort)"
done
"$oit" compare "$work/menger_insertion.png" "$work/menger_array.png" || fail "the two sort variants differ"
echo "json contract ok"
