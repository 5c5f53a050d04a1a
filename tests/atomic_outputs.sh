#!/usr/bin/env bash
# atomic_outputs.sh OIT WORKDIR SCENES: every file oit writes is replaced
# atomically. A full disk is simulated with a file-size limit (ulimit -f 1:
# writes past 1 KB fail with EFBIG, SIGXFSZ ignored): each command must exit
# non-zero with one line naming the file, leave the previous file byte for
# byte, and leave no temporary file behind. Successful writes keep a file's
# permissions and a symbolic link.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
mv="1 0 0 0  0 1 0 0  0 0 1 -3  0 0 0 1"
p="1.8 0 0 0  0 1.8 0 0  0 0 -1.2 -2.2  0 0 -1 0"

# limited CODE PATTERN -- command...: runs the command under a 1 KB file-size limit
limited() {
    local want=$1 pattern=$2
    shift 3
    expect_exit "$want" "$pattern" -- bash -c 'trap "" XFSZ; ulimit -f 1; exec "$@"' _ "$@"
}
# unchanged DIR FILE...: each FILE is byte for byte its copy FILE.before, and DIR holds no temporary file
unchanged() {
    local dir=$1 file
    shift
    for file in "$@"; do
        cmp -s "$file" "$file.before" || fail "$file changed after a failed write"
    done
    local left
    left=$(find "$dir" -name '*.tmp.*')
    [ -z "$left" ] || fail "temporary files left behind: $left"
}
keep() { for f in "$@"; do cp -p "$f" "$f.before"; done; }

# --- oit render --out ---
d=$work/render; mkdir -p "$d"
"$oit" render --model "$model" --algorithm reference --size 32x32 --out "$d/out.png" >/dev/null || fail "render"
keep "$d/out.png"
limited 3 "$d/out.png: cannot write: File too large" -- \
    "$oit" render --model "$model" --algorithm blend --size 128x128 --out "$d/out.png"
unchanged "$d" "$d/out.png"

# --- oit compare --diff ---
d=$work/compare; mkdir -p "$d"
"$oit" render --model "$model" --algorithm reference --size 128x128 --out "$d/a.png" >/dev/null || fail "render a"
"$oit" render --model "$model" --algorithm reference --size 128x128 --background 0,0,0 --out "$d/b.png" >/dev/null \
    || fail "render b"
"$oit" compare "$d/a.png" "$d/a.png" --diff "$d/diff.png" >/dev/null || fail "compare --diff"
keep "$d/diff.png"
limited 3 "$d/diff.png: cannot write: File too large" -- "$oit" compare "$d/a.png" "$d/b.png" --diff "$d/diff.png"
unchanged "$d" "$d/diff.png"

# --- oit bench --csv / --json ---
d=$work/bench; mkdir -p "$d"
bench=("$oit" bench --model "$model" --algorithms blend --sizes 8,9,10,11,12 --frames 1 --warmup 0 --quiet)
"${bench[@]}" --csv "$d/out.csv" --json "$d/out.json" || fail "bench"
keep "$d/out.csv" "$d/out.json"
limited 3 "--csv: cannot write $d/out.csv: File too large" -- "${bench[@]}" --csv "$d/out.csv"
unchanged "$d" "$d/out.csv" "$d/out.json"
limited 3 "--json: cannot write $d/out.json: File too large" -- "${bench[@]}" --json "$d/out.json"
unchanged "$d" "$d/out.csv" "$d/out.json"
# the other output of a failed run is not replaced either
limited 3 "cannot write $d/out.(csv|json): File too large" -- "${bench[@]}" --csv "$d/out.csv" --json "$d/out.json"
unchanged "$d" "$d/out.csv" "$d/out.json"
# a device is written in place (there is nothing to rename over), and its failure is named
expect_exit 3 "--csv: cannot write /dev/full: No space left" -- "${bench[@]}" --csv /dev/full
"${bench[@]}" --csv /dev/null --json /dev/null || fail "bench into /dev/null"

# --- oit gen: the OBJ and its MTL ---
d=$work/gen; mkdir -p "$d"
"$oit" gen cyclic --out "$d/scene.obj" || fail "gen cyclic"
keep "$d/scene.obj" "$d/scene.mtl"
limited 3 "$d/scene.(obj|mtl): cannot write: File too large" -- "$oit" gen onion --out "$d/scene.obj"
unchanged "$d" "$d/scene.obj" "$d/scene.mtl"

# --- oit measure --results (appends: the previous lines and the new one) ---
d=$work/measure; mkdir -p "$d"
# shellcheck disable=SC2086
"$oit" measure --results "$d/results.txt" --frames 1 --warmup 0 1 1 Onion "$model" $mv $p 16 >/dev/null \
    || fail "measure"
for i in $(seq 40); do echo "# an earlier run's note $i" >>"$d/results.txt"; done # past the 1 KB limit
keep "$d/results.txt"
# shellcheck disable=SC2086
limited 3 "measure: cannot append to $d/results.txt: File too large" -- \
    "$oit" measure --results "$d/results.txt" --frames 1 --warmup 0 1 1 Onion "$model" $mv $p 16
unchanged "$d" "$d/results.txt"
# without the limit the line is appended to the previous contents
# shellcheck disable=SC2086
"$oit" measure --results "$d/results.txt" --frames 1 --warmup 0 1 2 Onion "$model" $mv $p 16 >/dev/null \
    || fail "measure append"
cmp -s -n "$(stat -c %s "$d/results.txt.before")" "$d/results.txt" "$d/results.txt.before" \
    || fail "measure must keep the previous lines"
[ "$(tail -n 1 "$d/results.txt" | cut -f 1-3)" = "$(printf '1\tOnion\t2')" ] || fail "measure must append its line"

# --- a successful replacement keeps the file's permissions and a symbolic link ---
d=$work/replace; mkdir -p "$d/real"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out "$d/real/out.png" >/dev/null || fail "render"
chmod 640 "$d/real/out.png"
ln -s real/out.png "$d/link.png"
"$oit" render --model "$model" --algorithm reference --size 24x24 --out "$d/link.png" >/dev/null || fail "render via link"
[ -L "$d/link.png" ] || fail "a symbolic link given as --out must stay a link"
[ "$(stat -c %a "$d/real/out.png")" = 640 ] || fail "the replaced file must keep its permissions"
"$oit" compare "$d/real/out.png" "$d/real/out.png" >/dev/null || fail "the replaced file must be a whole PNG"
[ -z "$(find "$d" -name '*.tmp.*')" ] || fail "temporary files left after a successful write"
echo "all outputs are atomic"
