#!/usr/bin/env bash
# counter_limits.sh OIT WORKDIR SCENES: the 32-bit counters and 16-bit indices
# of ll and ib never wrap silently (docs/algorithms.md, "Limits").
# - The fill's fragment counter is 32-bit; the fill also counts its wraps, so
#   the frame's count is exact in 64 bits, and a frame past 4294967295
#   fragments (node indices are 32-bit, 0xFFFFFFFF ends a list) is an error
#   naming the count and the limit. 2^32 fragments would take hours on
#   llvmpipe, so --fragment-counter-start N (tests only) starts the counter at
#   N: the boundary and the exact count past the wrap are checked for real.
# - ib's neighbour links hold 16-bit layer indices: a pixel's list may hold
#   65535 fragments and not one more. One pixel with 65535 and 65536 stacked
#   triangles (tests/deep_pixel.py): the first renders as the reference, the
#   second is an error. (llvmpipe ends every shader loop after 65535
#   iterations, so there the sort notices the list it could not walk; another
#   GL reaches the link check. Either way it is an error, never an image.)
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/gearbox.obj
r=("$oit" render --model "$model" --size 64x64 --out "$work/x.png") # for expect_exit
json_int() { sed -n "s/.*\"$1\": \([0-9-]*\).*/\1/p"; }

# --- the option's range ---
expect_exit 2 "fragment-counter-start must be a whole number in \[0, 4294967295\]" -- "${r[@]}" --fragment-counter-start -1
expect_exit 2 "fragment-counter-start must be a whole number in \[0, 4294967295\]" -- "${r[@]}" --fragment-counter-start 4294967296
expect_exit 2 "fragment-counter-start must be a whole number in \[0, 4294967295\]" -- "${r[@]}" --fragment-counter-start x

for algorithm in ll ib; do
    f=$("${r[@]}" --algorithm "$algorithm" --out "$work/${algorithm}_plain.png" --json | json_int fragments)
    [ -n "$f" ] && [ "$f" -gt 1000 ] || fail "$algorithm: no fragment count ($f)"
    # a counter that starts elsewhere changes nothing but the count
    got=$("${r[@]}" --algorithm "$algorithm" --out "$work/${algorithm}_start.png" --json \
        --fragment-counter-start 1000 | json_int fragments)
    [ "$got" -eq $((f + 1000)) ] || fail "$algorithm: counter from 1000 counted $got, not $((f + 1000))"
    "$oit" compare "$work/${algorithm}_start.png" "$work/${algorithm}_plain.png" --tolerance 0 >/dev/null ||
        fail "$algorithm: a counter from 1000 changed the image"
    # exactly 4294967295 fragments: within the indices (ll: the pool budget refuses it; ib,
    # whose budget bounds one band's pool: its 64 rows would each need more than a pool)
    refusal="over the --max-memory budget"
    [ "$algorithm" = ll ] || refusal="more than bands of rows can hold"
    expect_exit 3 "^oit: error: $algorithm: the frame needs 4294967295 fragments.* $refusal" -- \
        "${r[@]}" --algorithm "$algorithm" --fragment-counter-start $((4294967295 - f))
    # one more: the counter wraps, and the frame is refused
    expect_exit 3 "^oit: error: $algorithm: the frame has 4294967296 fragments \(config.fragment_counter_start $((4294967296 - f)) included\), more than the 4294967295 its 32-bit fragment counter and node indices can number$" -- \
        "${r[@]}" --algorithm "$algorithm" --fragment-counter-start $((4294967296 - f))
    # far past the wrap the count is still exact (the wraps are counted)
    expect_exit 3 "^oit: error: $algorithm: the frame has $((4294967000 + f)) fragments .*more than the 4294967295" -- \
        "${r[@]}" --algorithm "$algorithm" --fragment-counter-start 4294967000
    echo "ok: $algorithm counts $f fragments past 2^32 exactly and refuses the frame"
done

# --- ib: 65535 fragments in one pixel, and one more ---
python3 "$(dirname "$0")/deep_pixel.py" "$work/deep.obj" 65536 || fail "deep_pixel.py"
deep=("$oit" render --model "$work/deep.obj" --size 1x1)
"${deep[@]}" --algorithm reference --hide last --out "$work/deep_ref.png" --json >"$work/deep_ref.json" || fail "reference"
"${deep[@]}" --algorithm ib --hide last --out "$work/deep_ib.png" --json >"$work/deep_ib.json" || fail "ib: a list of 65535 fragments"
[ "$(json_int max_list <"$work/deep_ib.json")" -eq 65535 ] || fail "ib: the list is not 65535 long: $(cat "$work/deep_ib.json")"
[ "$(json_int fragments <"$work/deep_ib.json")" -eq 65535 ] || fail "ib: not 65535 fragments"
"$oit" compare "$work/deep_ib.png" "$work/deep_ref.png" || fail "ib: the 65535-deep pixel differs from the reference"
echo "ok: ib renders a pixel of 65535 fragments"
expect_exit 3 "^oit: error: ib: (a pixel's list has 65536 fragments, more than the 65535 a neighbour link can address|the sort found 65535 of the frame's 65536 fragments: this GL cut a per-pixel shader loop short)" -- \
    "${deep[@]}" --algorithm ib --out "$work/deep_ib_over.png"

# --- ll: a long list sorted in place either is whole or is an error ---
python3 "$(dirname "$0")/deep_pixel.py" "$work/deep1000.obj" 1000 || fail "deep_pixel.py"
out=$("$oit" render --model "$work/deep1000.obj" --size 1x1 --algorithm ll --out "$work/deep1000.png" --json 2>"$work/ll.err")
status=$?
if [ $status -eq 0 ]; then
    [ "$(json_int max_list <<<"$out")" -eq 1000 ] || fail "ll: a list of 1000 came out $(json_int max_list <<<"$out") long"
    echo "ok: ll sorts a list of 1000 whole"
else
    [ $status -eq 3 ] && grep -Eq "ll: the sort found [0-9]+ of the frame's 1000 fragments" "$work/ll.err" ||
        { cat "$work/ll.err" >&2; fail "ll: exit $status on a list of 1000"; }
    echo "ok (3): $(cat "$work/ll.err")"
fi
