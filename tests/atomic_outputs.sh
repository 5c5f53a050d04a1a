#!/usr/bin/env bash
# atomic_outputs.sh OIT WORKDIR SCENES: every file oit writes is replaced
# atomically. A full disk is simulated with a file-size limit (ulimit -f 1:
# writes past 1 KB fail with EFBIG, SIGXFSZ ignored): each command must exit
# non-zero with one line naming the file, leave the previous file byte for
# byte, and leave no temporary file behind. Successful writes keep a file's
# permissions and a symbolic link (also a dangling one). Outputs that are not
# regular files or new names (a FIFO, a socket, a directory) and names too
# long are refused before any work, exit 2; /dev/null and stdout are written
# in place. About 10 s.
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
# /dev/null and stdout have nothing to rename over: written in place, a failure named
"${bench[@]}" --csv /dev/null --json /dev/null || fail "bench into /dev/null"
limited 3 "--csv: cannot write /dev/stdout: File too large" -- bash -c 'exec "$@" >"$0"' "$d/stdout.csv" \
    "${bench[@]}" --csv /dev/stdout

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
# a dangling link stays a link: the file it names is created
ln -s real/new.png "$d/dangling.png"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out "$d/dangling.png" >/dev/null \
    || fail "render via a dangling link"
[ -L "$d/dangling.png" ] && [ -f "$d/real/new.png" ] || fail "a dangling link given as --out must stay a link"
# a link to a missing directory, or a loop of links, is refused before the work
ln -s nowhere/x.png "$d/lost.png"
ln -s loop-b.png "$d/loop-a.png"; ln -s loop-a.png "$d/loop-b.png"
expect_exit 2 "--out $d/lost.png: the directory $d/nowhere does not exist" -- \
    "$oit" render --model "$model" --size 16x16 --out "$d/lost.png"
expect_exit 2 "--out $d/loop-a.png: Too many levels of symbolic links" -- \
    "$oit" render --model "$model" --size 16x16 --out "$d/loop-a.png"
[ -z "$(find "$d" -name '*.tmp.*')" ] || fail "temporary files left after a successful write"

# --- outputs that are not regular files or new names: refused at once, exit 2, untouched ---
d=$work/special; mkdir -p "$d"
mkfifo "$d/fifo"
python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$d/socket" || fail "no socket"
ln -s fifo "$d/link-to-fifo"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out "$d/a.png" >/dev/null || fail "render a"
# refused PATTERN -- command...: exit 2 within 20 s (a FIFO opened for writing would block for ever)
refused() { expect_exit 2 "$1" -- timeout 20 "${@:3}"; }
for entry in fifo:"a FIFO" socket:"a socket" link-to-fifo:"a FIFO"; do
    out=$d/${entry%%:*} kind=${entry#*:}
    why="$out: not a regular file or a new name \($kind\)"
    refused "--out $why" -- "$oit" render --model "$model" --size 16x16 --out "$out"
    refused "--error-map $why" -- "$oit" render --model "$model" --size 16x16 --error-map "$out"
    refused "--diff $why" -- "$oit" compare "$d/a.png" "$d/a.png" --diff "$out"
    refused "--csv $why" -- "${bench[@]}" --csv "$out"
    refused "--json $why" -- "${bench[@]}" --json "$out"
    refused "--bundle $out: not a directory or a new name \($kind\)" -- "${bench[@]}" --bundle "$out"
    # shellcheck disable=SC2086
    refused "measure: results file $why" -- "$oit" measure --results "$out" --frames 1 --warmup 0 1 1 Onion \
        "$model" $mv $p 16
    refused "$why" -- "$oit" gen onion --out "$out"
done
[ -p "$d/fifo" ] && [ -S "$d/socket" ] && [ -L "$d/link-to-fifo" ] || fail "a refused output was replaced"
refused "--out $d: is a directory" -- "$oit" render --model "$model" --size 16x16 --out "$d"
refused "--csv $d: is a directory" -- "${bench[@]}" --csv "$d"
# /dev/null: accepted, nothing kept; stdout: the PNG goes there and the summary line to stderr
"$oit" render --model "$model" --size 16x16 --out /dev/null >/dev/null || fail "render --out /dev/null"
# shellcheck disable=SC2086
"$oit" measure --results /dev/null --frames 1 --warmup 0 1 1 Onion "$model" $mv $p 16 >/dev/null \
    || fail "measure --results /dev/null"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out /dev/stdout 2>"$d/summary.txt" \
    | cat >"$d/piped.png" || fail "render --out /dev/stdout"
cmp -s "$d/piped.png" "$d/a.png" || fail "the PNG written to stdout differs from the file's"
grep -q "wrote /dev/stdout" "$d/summary.txt" || fail "the summary line must go to stderr when the PNG is on stdout"
[ -z "$(find "$d" -name '*.tmp.*')" ] || fail "temporary files left beside refused outputs"

# --- names too long: refused before any work (exit 2), not after it (exit 3) ---
d=$work/long; mkdir -p "$d"
long=$(printf 'n%.0s' $(seq 300))
deep=$(printf '/%s' $(for i in $(seq 17); do printf 'd%.0s' $(seq 250); echo; done))
why="File name too long: a name has at most 255 bytes, this one 30[0-9]"
expect_exit 2 "--out $d/$long.png: $why" -- "$oit" render --model "$model" --size 16x16 --out "$d/$long.png"
expect_exit 2 "--error-map $d/$long.png: $why" -- "$oit" render --model "$model" --size 16x16 --error-map "$d/$long.png"
expect_exit 2 "--csv $d/$long.csv: $why" -- "${bench[@]}" --csv "$d/$long.csv"
expect_exit 2 "--bundle $d/$long: $why" -- "${bench[@]}" --bundle "$d/$long"
# shellcheck disable=SC2086
expect_exit 2 "measure: results file $d/$long.txt: $why" -- "$oit" measure --results "$d/$long.txt" --frames 1 \
    --warmup 0 1 1 Onion "$model" $mv $p 16
expect_exit 2 "--out .*: File name too long: a path has at most 4095 bytes" -- \
    "$oit" render --model "$model" --size 16x16 --out "$d$deep/x.png"
# a scene name that would make a bundle file's name too long
expect_exit 2 "--bundle $d/b: File name too long: the file name '.*' would have 2[6-9][0-9] bytes" -- \
    "${bench[@]}" --name "$long" --bundle "$d/b"
# the longest name that fits (255 bytes) is written, through its short temporary
fits=$(printf 'f%.0s' $(seq 251)).png
"$oit" render --model "$model" --size 16x16 --out "$d/$fits" >/dev/null || fail "a 255-byte name must be written"
[ "$(ls "$d")" = "$fits" ] || fail "the 255-byte name: $(ls "$d")"
echo "all outputs are atomic"
