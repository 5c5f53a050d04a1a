#!/usr/bin/env bash
# ll_bands.sh OIT WORKDIR SCENES: a frame whose fragments exceed what one GL
# buffer can address (GL_MAX_SHADER_STORAGE_BLOCK_SIZE; 8M fragments on
# llvmpipe) is drawn in bands of rows, each filled, sorted and composed alone,
# and comes out as the whole frame would (docs/algorithms.md, "Limits").
# --buffer-fragment-limit N (tests only) lowers that limit to N so that small
# frames need bands. Checked: the image is identical (tolerance 0) to the frame
# drawn in one piece, for the colour image, a buffer view that reads one layer
# and the per-part opacity; the fragments, the longest list, the mean list and
# psi are the same; bands > 1 are reported; a band that still overflows is
# halved (a limit smaller than some bands need); later frames reuse the
# bands of the first; a view that needs the whole
# frame's figures, and a row that alone needs more than the limit, are
# one-line errors.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
figure() { python3 -c "import json,sys; d=json.load(sys.stdin); print(d.get('$1', 'none'))"; }

check_case() { # name model limit [render options]
    local name=$1 model=$2 limit=$3
    shift 3
    local r=("$oit" render --model "$model" --algorithm ll --size 160x128 "$@")
    "${r[@]}" --out "$work/$name-whole.png" --json >"$work/$name-whole.json" || fail "$name: whole frame failed"
    "${r[@]}" --out "$work/$name-bands.png" --json --buffer-fragment-limit "$limit" >"$work/$name-bands.json" ||
        fail "$name: banded frame failed"
    local bands
    bands=$(figure bands <"$work/$name-bands.json")
    [ "$bands" -gt 1 ] || fail "$name: limit $limit gave $bands bands, expected more than 1"
    [ "$(figure bands <"$work/$name-whole.json")" = 1 ] || fail "$name: the whole frame reports bands != 1"
    for key in fragments max_list mean_list psi; do
        local whole banded
        whole=$(figure $key <"$work/$name-whole.json")
        banded=$(figure $key <"$work/$name-bands.json")
        [ "$whole" = "$banded" ] || fail "$name: $key is $banded in bands, $whole whole"
    done
    "$oit" compare "$work/$name-whole.png" "$work/$name-bands.png" --tolerance 0 >/dev/null ||
        fail "$name: the banded image differs from the whole frame"
    echo "ok: $name in $bands bands, identical (fragments $(figure fragments <"$work/$name-whole.json"))"
}

fragments=$("$oit" render --model "$scenes/onion.obj" --algorithm ll --size 160x128 --out "$work/x.png" --json | figure fragments)
[ "$fragments" -gt 20000 ] || fail "onion has only $fragments fragments at 160x128"
check_case onion "$scenes/onion.obj" $((fragments / 5))
# a limit that leaves no headroom: equal shares overflow where the rows are deep, and are halved
check_case onion-halved "$scenes/onion.obj" $((fragments / 3))
check_case menger "$scenes/menger.obj" 9000 --orbit 30,20
# frames after the first start from its bands (no counting fill), halved ones included
check_case frames "$scenes/onion.obj" $((fragments / 3)) --frames 3
check_case layer "$scenes/gearbox.obj" 8000 --view layer:1
check_case parts "$scenes/gearbox.obj" 8000 --component-alpha 0=0.2 --alpha 0.6
check_case distance "$scenes/onion.obj" 15000 --modulation distance --focus-region 1.5

r=("$oit" render --model "$scenes/onion.obj" --algorithm ll --size 160x128 --out "$work/x.png")
expect_exit 3 "^oit: error: ll: the frame needs [0-9]+ fragments, more than this GL can address in one shader storage buffer or buffer texture \(5000\); it could be drawn in bands of rows, but not with the heat map view, which needs the whole frame's figures$" -- \
    "${r[@]}" --buffer-fragment-limit 5000 --view heatmap
expect_exit 3 "^oit: error: ll: .*but not with the distance modulation's automatic region" -- \
    "${r[@]}" --buffer-fragment-limit 5000 --modulation distance
expect_exit 3 "^oit: error: ll: row [0-9]+ of the image alone needs [0-9]+ fragments, more than this GL can address in one buffer \(100\)$" -- \
    "${r[@]}" --buffer-fragment-limit 100
expect_exit 2 "buffer-fragment-limit must be a whole number of fragments in \[1, 2\^30\], got '0'" -- \
    "${r[@]}" --buffer-fragment-limit 0
echo "ok: bands"
