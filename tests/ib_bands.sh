#!/usr/bin/env bash
# ib_bands.sh OIT WORKDIR SCENES: the Illustration Buffer draws a frame whose
# fragments exceed what one pool holds (one GL buffer's reach, 8M fragments on
# llvmpipe, or the --max-memory budget) in bands of rows, each storing its rows
# and the rows either side that its neighbour passes read, and the frame comes
# out as if drawn whole (docs/illustration-buffer.md, "Bands").
# --buffer-fragment-limit N (tests only) lowers the GL's limit to N so that
# small frames need bands. Checked, for every modulation and every view, the
# three neighbour searches, the long runs of the histogram's open bin, later
# frames that start from the first one's bands and both back ends: the PNG is
# byte for byte the whole frame's (cmp), and so are the fragments, the longest
# and mean list, psi, the list-length histogram and the neighbour shares; the
# frame reports bands > 1. A row that alone, with its overlap, needs more than
# the limit, and a frame whose rows need more than the limit on average, are
# one-line errors.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
size=128x96
figure() { python3 -c "import json,sys; d=json.load(sys.stdin); print(d.get('$1', 'none'))"; }
fragments_of() { # model [render options]: the frame's fragments at $size
    "$oit" render --model "$1" --algorithm ib --size $size "${@:2}" --out "$work/count.png" --json | figure fragments
}

check_case() { # name model limit [render options]
    local name=$1 model=$2 limit=$3
    shift 3
    local r=("$oit" render --model "$model" --algorithm ib --size $size "$@")
    "${r[@]}" --out "$work/$name-whole.png" --json >"$work/$name-whole.json" || fail "$name: whole frame failed"
    "${r[@]}" --out "$work/$name-bands.png" --json --buffer-fragment-limit "$limit" >"$work/$name-bands.json" ||
        fail "$name: banded frame failed"
    python3 - "$work/$name-whole.json" "$work/$name-bands.json" "$name" <<'PY' || fail "$name: statistics differ"
import json, sys
whole, bands = (json.load(open(p)) for p in sys.argv[1:3])
name = sys.argv[3]
assert whole["bands"] == 1, f"{name}: the whole frame reports {whole['bands']} bands"
assert 1 < bands["bands"] <= 8, f"{name}: {bands['bands']} bands, expected 2 to 8"
for key in ("fragments", "max_list", "mean_list", "psi", "list_histogram", "neighbours_four_share",
            "neighbours_symmetric_share", "neighbours_same_component_share"):
    assert key in whole, f"{name}: no {key}"
    assert whole[key] == bands.get(key), f"{name}: {key} is {bands.get(key)} in bands, {whole[key]} whole"
PY
    cmp -s "$work/$name-whole.png" "$work/$name-bands.png" ||
        fail "$name: the banded image differs from the whole frame"
    echo "ok: $name in $(figure bands <"$work/$name-bands.json") bands, identical (fragments $(figure fragments <"$work/$name-whole.json"))"
}

onion=$scenes/onion.obj gearbox=$scenes/gearbox.obj menger=$scenes/menger.obj
f=$(fragments_of "$onion")
[ "$f" -gt 20000 ] || fail "onion has only $f fragments at $size"
g=$(fragments_of "$gearbox" --orbit 30,20)
m=$(fragments_of "$menger" --orbit 30,20)
# every modulation (the overlap: 1 row, fields 1 + diffusion + 2 x blur iterations)
check_case none "$onion" $((f / 2))
stage_count() { python3 -c "import json,sys; print([s['name'] for s in json.load(sys.stdin)['stages']].count('$1'))"; }
# no headroom: equal shares overflow where the rows are deep and are halved
[ "$(stage_count band_fill <"$work/none-bands.json")" -gt "$(figure bands <"$work/none-bands.json")" ] ||
    fail "none: no band was halved"
check_case curvature "$onion" $((f / 2)) --modulation curvature --curvature-neighbours 8 --backend osmesa
# the automatic region: a first sweep finds the frame's largest distance; frames after the
# first start from its bands (no fill that only counts)
check_case distance "$onion" $((f / 2)) --modulation distance --frames 2
[ "$(stage_count fill <"$work/distance-bands.json")" = 0 ] || fail "distance: the second frame counted again"
check_case dist-curv "$gearbox" $((g / 2)) --orbit 30,20 --modulation dist-curv --curvature-neighbours 8
check_case fields "$onion" $((f / 2)) --modulation fields --diffusion-iterations 4
check_case fields-default "$onion" $((f * 3 / 4)) --modulation fields
check_case fields-menger "$menger" $((m / 2)) --orbit 30,20 --modulation fields --diffusion-iterations 3 \
    --neighbours epsilon
check_case edges "$gearbox" $((g / 2)) --orbit 30,20 --modulation edges --component-alpha 0=0.2
# every view; the heat map's longest list from the first sweep, on runs of 64 and more
# (the histogram's open bin: psi and the fragments from the runs by length)
"$oit" gen onion --complexity 40 --out "$work/onion40.obj" >/dev/null || fail "oit gen onion"
d=$(fragments_of "$work/onion40.obj")
check_case view-heatmap "$work/onion40.obj" $((d / 2)) --view heatmap
[ "$(figure max_list <"$work/view-heatmap-whole.json")" -ge 64 ] || fail "view-heatmap: no run of 64 or more"
check_case view-peel-limit "$onion" $((f / 2)) --view peel-limit:2
check_case view-layer "$onion" $((f / 2)) --view layer:1 --modulation curvature
check_case view-neighbours "$onion" $((f / 2)) --view neighbours --alpha 1 --neighbours index
check_case view-curvature "$menger" $((m / 2)) --orbit 30,20 --view curvature:1 --neighbours epsilon
check_case view-distance "$onion" $((f / 2)) --view distance:1 --distance skip:2 --focus-region 1.5
check_case view-fields "$onion" $((f / 2)) --view fields:1 --diffusion-iterations 2 --blur-iterations 2 \
    --backend osmesa

r=("$oit" render --model "$onion" --algorithm ib --size $size --out "$work/x.png")
expect_exit 3 "^oit: error: ib: row [0-9]+ of the image, with the 1 row either side that its neighbour passes read, needs [0-9]+ fragments, more than this GL can address in one shader storage buffer \($((f / 60))\)$" -- \
    "${r[@]}" --buffer-fragment-limit $((f / 60))
expect_exit 3 "^oit: error: ib: row [0-9]+ of the image alone needs [0-9]+ fragments, more than this GL can address in one shader storage buffer \($((f / 60))\)$" -- \
    "${r[@]}" --buffer-fragment-limit $((f / 60)) --view heatmap
expect_exit 3 "^oit: error: ib: the frame needs $f fragments, more than bands of rows can hold: its 96 rows need more on average than this GL can address in one shader storage buffer \(100\)$" -- \
    "${r[@]}" --buffer-fragment-limit 100
echo "ok: ib bands"
