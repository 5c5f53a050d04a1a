#!/usr/bin/env bash
# special_inputs.sh OIT WORKDIR SCENES SHADERS: inputs must be regular files.
# A FIFO (which would block the open or the read forever), /dev/zero (which
# never ends), a directory and a socket, given as a model, a compare input, a
# scene list or placed as a shader file, are refused within seconds with one
# line naming the path: exit 2, or 3 for a shader file (as a missing shader).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 shaders=$4
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
mv="1 0 0 0  0 1 0 0  0 0 1 -3  0 0 0 1"
p="1.8 0 0 0  0 1.8 0 0  0 0 -1.2 -2.2  0 0 -1 0"

mkfifo "$work/fifo.obj"
mkdir "$work/directory.obj"
python3 -c 'import socket, sys; socket.socket(socket.AF_UNIX).bind(sys.argv[1])' "$work/socket.obj" \
    || fail "cannot make a socket"
"$oit" render --model "$model" --algorithm reference --size 16x16 --out "$work/a.png" >/dev/null || fail "render"

# refused CODE PATTERN -- command...: as expect_exit, but a hang fails after 20 s (timeout's 124)
refused() {
    local want=$1 pattern=$2
    shift 3
    expect_exit "$want" "$pattern" -- timeout 20 "$@"
}

for entry in "$work/fifo.obj:a FIFO" "/dev/zero:a character device" "$work/directory.obj:a directory" \
             "$work/socket.obj:a socket"; do
    path=${entry%%:*} kind=${entry#*:}
    refused 2 "model $path: not a regular file \($kind\)" -- "$oit" render --model "$path" --out "$work/x.png"
    refused 2 "model $path: not a regular file \($kind\)" -- "$oit" info --model "$path"
    refused 2 "^oit: error: $path: not a regular file \($kind\)" -- "$oit" compare "$work/a.png" "$path"
    refused 2 "^oit: error: $path: not a regular file \($kind\)" -- "$oit" compare "$path" "$work/a.png"
    refused 2 "--scene-list $path: not a regular file \($kind\)" -- \
        "$oit" bench --scene-list "$path" --algorithms blend --sizes 16x16
done
# shellcheck disable=SC2086
refused 2 "model $work/fifo.obj: not a regular file \(a FIFO\)" -- \
    "$oit" measure --results "$work/results.txt" 1 1 Fifo "$work/fifo.obj" $mv $p 16
[ ! -e "$work/results.txt" ] || fail "a refused measure must not write its results file"
refused 2 "model /dev/zero: not a regular file" -- "$oit" demo --model /dev/zero --out "$work/demo" --size 16x16
# oit bench: a model that cannot be read fails its row (exit 3), the row names it
refused 3 "1 run\(s\) failed" -- "$oit" bench --model "$work/fifo.obj" --algorithms blend --sizes 16 --quiet \
    --csv "$work/fifo.csv"
grep -q "model $work/fifo.obj: not a regular file (a FIFO)" "$work/fifo.csv" || fail "the bench row must name the FIFO"

# shader files: a copy of the shader tree with one file replaced
for entry in "blend/draw.frag:fifo:a FIFO" "common/shade.glsl:zero:a character device"; do
    file=${entry%%:*} rest=${entry#*:}
    how=${rest%%:*} kind=${rest#*:}
    tree=$work/shaders-$how
    rm -rf "$tree"; cp -r "$shaders" "$tree"
    rm "$tree/$file"
    if [ "$how" = fifo ]; then mkfifo "$tree/$file"; else ln -s /dev/zero "$tree/$file"; fi
    OIT_SHADER_DIR=$tree refused 3 "shader file $tree/$file: not a regular file \($kind\)" -- \
        "$oit" render --model "$model" --algorithm blend --size 16x16 --out "$work/x.png"
done
echo "special files refused"
