#!/usr/bin/env bash
# compare_case.sh OIT EXPECT REFERENCE_PNG OUT_PNG TOLERANCE MAX_MISMATCH_PERCENT -- render arguments...
# Renders OUT_PNG with the given arguments and compares it with REFERENCE_PNG.
# EXPECT is "match" (the comparison must be within bounds) or "differ" (it must
# not be: used where an algorithm is known to be wrong, e.g. blend on cyclic).
# The comparison's figures are printed either way, so errors are reported, not hidden.
set -u
oit=$1 expect=$2 reference=$3 out=$4 tolerance=$5 mismatch=$6
shift 7
mkdir -p "$(dirname "$out")"
"$oit" render "$@" --out "$out" --json || { echo "FAIL: render exited $?" >&2; exit 1; }
"$oit" compare "$out" "$reference" --tolerance "$tolerance" --max-mismatch "$mismatch" --diff "${out%.png}.diff.png"
status=$?
case "$expect:$status" in
    match:0|differ:1) exit 0 ;;
    *) echo "FAIL: expected '$expect', compare exited $status" >&2; exit 1 ;;
esac
