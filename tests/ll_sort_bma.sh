#!/usr/bin/env bash
# ll_sort_bma.sh OIT WORKDIR SCENES GEARBOX: ll's --sort bma (Knowles et al.'s
# backwards memory allocation with the register-block sort) and --sort merge
# (the same without the private arrays, the default) give the insertion sort's
# lists node for node, and lift its worst-order limit (docs/algorithms.md, ll
# and Limits).
#  1. byte-identical PNGs (cmp) to --sort insertion at 128x128 on the gearbox
#     (resources/models), coplanar squares (ties at equal depth), 40 nested
#     spheres (lists of 1 to 80: every interval, registers, arrays of 16/32/64,
#     and past 64 the merge in the lists), and at 48x48 300 sheets from behind
#     (every list 300 long in the insertion sort's worst order, which it still
#     sorts: the merge in the lists against it);
#  2. 1,200 sheets seen from behind (every list arrives front to back, the
#     insertion sort's worst order) at 32x32: ll (default, bma, merge) match the
#     reference within the exact tolerance (2/255 on 99.9% of pixels), while
#     --sort insertion still fails the frame with the sort error (exit 3).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 gearbox=$4
rm -rf "$work"; mkdir -p "$work"
sheets() { # COUNT FILE: parallel sheets numbered from the back (seen from behind, the last drawn is nearest)
    python3 - "$1" "$2" <<'PY'
import sys
sheets = int(sys.argv[1])
with open(sys.argv[2], "w") as f:
    for k in range(sheets):
        z = 1 - 2 * k / (sheets - 1)
        half = 1.0 + 0.3 * (k % 7) / 7  # sizes vary, so the edges differ in depth
        for x, y in ((-half, -half), (half, -half), (half, half), (-half, half)):
            f.write(f"v {x} {y} {z}\n")
        b = 4 * k
        f.write(f"f {b + 1} {b + 2} {b + 3}\nf {b + 1} {b + 3} {b + 4}\n")
PY
}
sheets 300 "$work/sheets300.obj"
sheets 1200 "$work/sheets1200.obj"
"$oit" gen onion --complexity 40 --out "$work/onion40.obj" >/dev/null || fail "oit gen onion"

same() { # NAME MODEL [render args...]: --sort bma, merge and insertion write the same bytes
    local name=$1 model=$2
    shift 2
    for sort in insertion bma merge; do
        "$oit" render --model "$model" --algorithm ll --sort $sort --size 128x128 --out "$work/$name-$sort.png" "$@" \
            >/dev/null || fail "$name: ll --sort $sort failed"
    done
    cmp -s "$work/$name-insertion.png" "$work/$name-bma.png" || fail "$name: --sort bma differs from --sort insertion"
    cmp -s "$work/$name-insertion.png" "$work/$name-merge.png" || fail "$name: --sort merge differs from --sort insertion"
    echo "ok: $name byte-identical"
}
same gearbox "$gearbox" --shading headlight --orbit 30,20
same coplanar "$scenes/coplanar.obj" --shading flat
same onion40 "$work/onion40.obj" --shading flat --alpha 0.3
same sheets300 "$work/sheets300.obj" --shading flat --alpha 0.01 --orbit 180,0 --size 48x48

back=(--model "$work/sheets1200.obj" --size 32x32 --shading flat --alpha 0.01 --orbit 180,0)
"$oit" render "${back[@]}" --algorithm reference --out "$work/back-reference.png" >/dev/null || fail "reference"
for variant in default bma merge; do
    args=()
    [ $variant = default ] || args=(--sort $variant)
    "$oit" render "${back[@]}" --algorithm ll "${args[@]}" --out "$work/back-$variant.png" >/dev/null ||
        fail "1200 sheets from behind: ll ($variant) failed"
    "$oit" compare "$work/back-reference.png" "$work/back-$variant.png" --tolerance 2 --max-mismatch 0.1 ||
        fail "1200 sheets from behind: ll ($variant) must match the reference (2/255 on 99.9% of pixels)"
done
expect_exit 3 "ll: the sort found [0-9]+ of the frame's [0-9]+ fragments" -- \
    "$oit" render "${back[@]}" --algorithm ll --sort insertion --out "$work/back-insertion.png"
echo "ll --sort bma and merge: all behaved"
