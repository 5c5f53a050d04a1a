#!/usr/bin/env bash
# closest_layers_exact.sh OIT REFERENCE_PNG OUT_PNG TOLERANCE MAX_MISMATCH_PERCENT -- render arguments...
# kbuffer or hybrid with --layers K where K is at least the longest list of the
# frame: every fragment is in the core, so the image must match the reference
# within the exact tolerance (compare_case.sh). The render's own max_list must be
# <= K, else the case would not test exactness.
source "$(dirname "$0")/lib.sh"
oit=$1 reference=$2 out=$3 tolerance=$4 mismatch=$5
shift 6
args=("$@")
k=
for ((i = 0; i < ${#args[@]}; ++i)); do
    [ "${args[i]}" = "--layers" ] && k=${args[i + 1]}
done
[ -n "$k" ] || fail "no --layers in the render arguments"
mkdir -p "$(dirname "$out")"
json=$("$oit" render "$@" --out "$out" --json) || fail "render exited $?"
echo "$json"
max_list=$(sed -n 's/.*"max_list": \([0-9]*\).*/\1/p' <<<"$json")
[ -n "$max_list" ] && [ "$max_list" -ge 1 ] && [ "$max_list" -le "$k" ] \
    || fail "the frame's longest list ($max_list) is not within k = $k"
"$oit" compare "$out" "$reference" --tolerance "$tolerance" --max-mismatch "$mismatch" \
    --diff "${out%.png}.diff.png" || fail "not within the exact tolerance of the reference"
