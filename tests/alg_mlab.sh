#!/usr/bin/env bash
# alg_mlab.sh OIT WORKDIR SCENES: multi-layer alpha blending's contract beyond
# its images (docs/algorithms.md, "mlab").
# - Determinism on llvmpipe: every pixel's fragments arrive in triangle order
#   there (one rasterizer thread per 64x64 tile, the tile's triangles in
#   submission order), so the merges, which depend on arrival order, are the
#   same on every run and with any LP_NUM_THREADS. Checked where the order
#   matters: menger at k = 4, whose merges err (tests/alg_mlab.cmake).
# - The lock's give-up path: with --locks-held (config.locks_held, tests only)
#   every pixel's lock starts taken, so every fragment spins to the cap and
#   gives up; the frame must fail naming them all, and write no image.
# - Statistics: fragments and max_list equal ll's (every fragment counted, the
#   per-pixel count is fragments received, not layers kept), bytes_per_pixel is
#   16 k + 12, the stages are clear, insert, resolve.
# - Refusals: the distance and ib-only modulations and buffer views (exit 2), a
#   memory budget too small (exit 3, naming the bytes needed).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
json_int() { sed -n "s/.*\"$1\": \([0-9-]*\).*/\1/p"; }
json_num() { sed -n "s/.*\"$1\": \([0-9.e+-]*\).*/\1/p"; }

# --- determinism ---
m=("$oit" render --model "$scenes/menger.obj" --algorithm mlab --layers 4 --size 128x128 --shading flat)
"${m[@]}" --out "$work/menger_a.png" >/dev/null || fail "menger k=4"
"${m[@]}" --out "$work/menger_b.png" >/dev/null || fail "menger k=4, again"
LP_NUM_THREADS=1 "${m[@]}" --out "$work/menger_t1.png" >/dev/null || fail "menger k=4, one thread"
LP_NUM_THREADS=7 "${m[@]}" --out "$work/menger_t7.png" >/dev/null || fail "menger k=4, seven threads"
"${m[@]}" --backend osmesa --out "$work/menger_osmesa.png" >/dev/null || fail "menger k=4, osmesa"
for other in b t1 t7 osmesa; do
    "$oit" compare "$work/menger_a.png" "$work/menger_$other.png" --tolerance 0 >/dev/null ||
        fail "mlab k=4 on menger: image $other differs from the first render"
done
# the order matters there: k = 4 is not the exact composite (else the above proves little)
"$oit" render --model "$scenes/menger.obj" --algorithm mlab --layers 64 --size 128x128 --shading flat \
    --out "$work/menger_64.png" >/dev/null || fail "menger k=64"
"$oit" compare "$work/menger_a.png" "$work/menger_64.png" --tolerance 2 >/dev/null &&
    fail "mlab k=4 on menger equals k=64: the determinism check sees no merge error"
echo "ok: mlab k=4 on menger is the same image twice, with 1 and 7 rasterizer threads and on osmesa"

# --- the lock gives up: counted, and the frame fails ---
c=("$oit" render --model "$scenes/cyclic.obj" --algorithm mlab --size 32x32)
f=$("${c[@]}" --out "$work/cyclic.png" --json | json_int fragments)
[ -n "$f" ] && [ "$f" -gt 100 ] || fail "mlab: no fragment count on cyclic ($f)"
expect_exit 3 "^oit: error: mlab: $f of the frame's $f fragments gave up waiting for their pixel's lock after 4096 tries each \(config.locks_held: every lock started taken\); the image would miss them$" -- \
    "${c[@]}" --locks-held --out "$work/held.png"
[ ! -e "$work/held.png" ] || fail "mlab: a frame whose fragments gave up wrote an image"
# and the algorithm is not left broken: the same options without the test switch render
"${c[@]}" --out "$work/cyclic_again.png" >/dev/null || fail "mlab: cyclic after the give-up test"

# --- statistics ---
g=("$oit" render --model "$scenes/gearbox.obj" --size 128x128 --json)
ll=$("${g[@]}" --algorithm ll --out "$work/gearbox_ll.png")
for k in 4 8; do
    d=$("${g[@]}" --algorithm mlab --layers $k --out "$work/gearbox_$k.png")
    [ "$(json_int fragments <<<"$d")" -eq "$(json_int fragments <<<"$ll")" ] ||
        fail "mlab k=$k: fragments $(json_int fragments <<<"$d") != ll's $(json_int fragments <<<"$ll")"
    [ "$(json_int max_list <<<"$d")" -eq "$(json_int max_list <<<"$ll")" ] ||
        fail "mlab k=$k: max_list $(json_int max_list <<<"$d") != ll's $(json_int max_list <<<"$ll")"
    bpp=$(json_num bytes_per_pixel <<<"$d")
    [ "$bpp" = "$((16 * k + 12))" ] || fail "mlab k=$k: bytes_per_pixel $bpp, not 16 x $k + 12"
    stages='"stages": \[{"name": "clear", [^]]*{"name": "insert", [^]]*{"name": "resolve", [^]]*\]'
    grep -q "$stages" <<<"$d" ||
        fail "mlab k=$k: stages are not clear, insert, resolve: $d"
done
echo "ok: mlab counts ll's fragments and longest list, 16 k + 12 bytes per pixel"

# --- what mlab refuses ---
r=("$oit" render --model "$scenes/onion.obj" --algorithm mlab --size 32x32 --out "$work/x.png")
expect_exit 2 "^oit: error: mlab: the distance modulation needs the distance to the next fragment" -- \
    "${r[@]}" --modulation distance
expect_exit 2 "^oit: error: mlab: opacity modulation 'curvature' needs surface neighbours \(ib only\)" -- \
    "${r[@]}" --modulation curvature
expect_exit 2 "^oit: error: mlab: buffer views are ll's and ib's \(view 'heatmap'\)" -- \
    "${r[@]}" --view heatmap
expect_exit 2 "^oit: error: --layers must be a whole number from 1 to 64, got '65'" -- \
    "${r[@]}" --layers 65
# 128 x 128 x (8 x 16 + 12) + 6 counters x 4 = 2293784 bytes
expect_exit 3 "^oit: error: mlab: 8 layers per pixel at 128x128 need 2293784 bytes .*over the --max-memory budget of 1.0 MB$" -- \
    "$oit" render --model "$scenes/onion.obj" --algorithm mlab --size 128x128 --max-memory 1 \
    --out "$work/x.png"
echo "ok: mlab refuses what it cannot do"
