#!/usr/bin/env bash
# cli_errors.sh OIT WORKDIR SCENES: every kind of bad input gets its exit status
# and a one-line message naming the problem; nothing crashes or hangs.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
good_mv=1,0,0,0,0,1,0,0,0,0,1,-3,0,0,0,1
good_p=1.8,0,0,0,0,1.8,0,0,0,0,-1.2,-2.2,0,0,-1,0

# --- bad model files (exit 2) ---
expect_exit 2 "missing.obj" -- "$oit" render --model "$work/missing.obj" --out "$work/x.png"
: >"$work/empty.obj"
expect_exit 2 "empty" -- "$oit" render --model "$work/empty.obj" --out "$work/x.png"
head -c 4096 /dev/urandom >"$work/garbage.obj"
expect_exit 2 "garbage.obj" -- "$oit" render --model "$work/garbage.obj" --out "$work/x.png"
head -c 4096 /dev/urandom >"$work/garbage.bin"
expect_exit 2 "garbage.bin" -- "$oit" info --model "$work/garbage.bin"
# --tessellation (STEP, IGES): a level or millimetres > 0, on render and info
expect_exit 2 "--tessellation must be coarse, normal, fine or a linear deflection in millimetres greater than 0, got '0'" -- \
    "$oit" render --model "$work/garbage.bin" --tessellation 0 --out "$work/x.png"
expect_exit 2 "--tessellation must be .* got 'medium'" -- "$oit" info --model "$work/garbage.bin" --tessellation medium
expect_exit 2 "--tessellation must be .* got 'nan'" -- "$oit" info --model "$work/garbage.bin" --tessellation nan
mkdir -p "$work/adirectory.obj"
expect_exit 2 "director" -- "$oit" render --model "$work/adirectory.obj" --out "$work/x.png"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\np 3\n' >"$work/notriangles.obj"
expect_exit 2 "triangle" -- "$oit" render --model "$work/notriangles.obj" --out "$work/x.png"
printf 'v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$work/nan.obj"
expect_exit 2 "nan.obj" -- "$oit" render --model "$work/nan.obj" --out "$work/x.png"
printf 'v inf 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$work/inf.obj"
expect_exit 2 "inf.obj" -- "$oit" info --model "$work/inf.obj"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n' >"$work/badindex.obj"
expect_exit 2 "badindex.obj" -- "$oit" render --model "$work/badindex.obj" --out "$work/x.png"

# --- bad matrices (exit 2) ---
expect_exit 2 "16" -- "$oit" render --model "$model" --out "$work/x.png" --modelview 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0
expect_exit 2 "not a (finite )?number|finite" -- "$oit" render --model "$model" --out "$work/x.png" --modelview 1,0,0,0,0,nan,0,0,0,0,1,0,0,0,0,1
expect_exit 2 "list of numbers" -- "$oit" render --model "$model" --out "$work/x.png" --projection 1,0,0,0,0,1,0,0,0,0,1,0,0,0,x,1
expect_exit 2 "singular" -- "$oit" render --model "$model" --out "$work/x.png" --modelview "$good_mv" --projection 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0
expect_exit 2 "singular" -- "$oit" render --model "$model" --out "$work/x.png" --modelview 0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,1 --projection "$good_p"

# --- absurd sizes and values (exit 2) ---
expect_exit 2 "at least 1" -- "$oit" render --model "$model" --out "$work/x.png" --size 0x0
expect_exit 2 "too large" -- "$oit" render --model "$model" --out "$work/x.png" --size 100000x100000
expect_exit 2 "WxH" -- "$oit" render --model "$model" --out "$work/x.png" --size banana
expect_exit 2 "alpha" -- "$oit" render --model "$model" --out "$work/x.png" --alpha 1.5
expect_exit 2 "unknown algorithm" -- "$oit" render --model "$model" --out "$work/x.png" --algorithm nosuch
expect_exit 2 "backend" -- "$oit" render --model "$model" --out "$work/x.png" --backend vulkan
expect_exit 2 "unknown option" -- "$oit" render --model "$model" --out "$work/x.png" --frobnicate
expect_exit 2 "unknown command" -- "$oit" frobnicate
expect_exit 2 "unknown" -- "$oit" gen nosuchscene --out "$work/n.obj"

# --- an exhausted memory budget (exit 3), for the growing fragment pool ---
expect_exit 3 "budget" -- "$oit" render --model "$scenes/menger.obj" --algorithm ll --size 256x256 --max-memory 1 --out "$work/x.png"

# --- compare: bad input (2) and outside bounds (1) ---
"$oit" render --model "$model" --algorithm reference --size 32x32 --out "$work/a.png" >/dev/null || fail "render a"
"$oit" render --model "$model" --algorithm reference --size 32x32 --background 0,0,0 --out "$work/b.png" >/dev/null || fail "render b"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out "$work/small.png" >/dev/null || fail "render small"
expect_exit 0 "" -- "$oit" compare "$work/a.png" "$work/a.png"
expect_exit 1 "" -- "$oit" compare "$work/a.png" "$work/b.png" --tolerance 2
expect_exit 2 "size|32x32" -- "$oit" compare "$work/a.png" "$work/small.png"
expect_exit 2 "PNG" -- "$oit" compare "$work/a.png" "$work/garbage.bin"
expect_exit 2 "missing.png" -- "$oit" compare "$work/a.png" "$work/missing.png"
# --- special files and failing writes: no hang, nothing lost ---
mkfifo "$work/fifo.png" "$work/fifo.txt"
expect_exit 2 "fifo.png: not a regular file" -- "$oit" compare "$work/a.png" "$work/fifo.png"
expect_exit 2 "fifo.txt: not a regular file" -- "$oit" bench --scene-list "$work/fifo.txt" --algorithms blend --sizes 16x16
# a FIFO is no output (its open would block): refused before the run
expect_exit 2 "--csv $work/fifo.txt: not a regular file or a new name \(a FIFO\)" -- timeout 20 "$oit" bench \
    --model "$model" --algorithms blend --sizes 16x16 --frames 1 --warmup 0 --quiet --csv "$work/fifo.txt"
# a PNG that cannot be written whole (here: past a 1 KB file-size limit) leaves the previous file
echo previous >"$work/keep.png"
expect_exit 3 "keep.png: cannot write" -- bash -c 'trap "" XFSZ; ulimit -f 1; exec "$@"' _ \
    "$oit" render --model "$model" --algorithm blend --size 128x128 --out "$work/keep.png"
[ "$(cat "$work/keep.png")" = previous ] || fail "a failed PNG write must leave the previous file"
[ -z "$(ls "$work" | grep 'keep.png.tmp')" ] || fail "a failed PNG write must remove its temporary file"
echo "all error cases behaved"

# the approximate families' parameters and the error options (issue 12)
expect_exit 2 "--layers must be a whole number from 1 to 64, got '0'" -- "$oit" render --model "$model" --layers 0
expect_exit 2 "--layers must be a whole number from 1 to 64, got '65'" -- "$oit" render --model "$model" --layers 65
expect_exit 2 "--moments must be power4, power6 or trig3, got 'power5'" -- "$oit" render --model "$model" --moments power5
expect_exit 2 "--wavelet-rank must be a whole number from 1 to 3, got '4'" -- "$oit" render --model "$model" --wavelet-rank 4
expect_exit 2 "--error-map needs a value" -- "$oit" render --model "$model" --error-map
expect_exit 2 "--error-map" -- "$oit" render --model "$model" --error-map "$work/no/such/dir/map.png"
expect_exit 2 "algorithms: unknown option '--jsn'" -- "$oit" algorithms --jsn

# environment values: a CPU limit that is no number of seconds in (0, 1e6] is refused naming it
# (inf and 1e30 overflowed the limit and made every import "time out" at once)
for value in inf 1e30 -1 0 abc; do
    OIT_IMPORT_CPU_SECONDS=$value expect_exit 2 \
        "^oit: error: OIT_IMPORT_CPU_SECONDS=$value: must be a number of seconds greater than 0 and at most 1000000" \
        -- "$oit" info --model "$model"
done
OIT_IMPORT_CPU_SECONDS=0.5 "$oit" info --model "$model" >/dev/null || fail "OIT_IMPORT_CPU_SECONDS=0.5 must import"
OIT_IMPORT_CPU_SECONDS=1000000 "$oit" info --model "$model" >/dev/null || fail "OIT_IMPORT_CPU_SECONDS=1000000 must import"
echo "environment values refused"
