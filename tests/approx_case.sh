#!/usr/bin/env bash
# approx_case.sh OIT EXPECT REFERENCE_PNG OUT_PNG "MAX SHARE MEAN" -- render arguments...
# An approximation (blend, wboit) against the reference, within its recorded error
# bound (tests/approx_bounds.cmake, docs/testing.md). MAX SHARE MEAN are the figures
# measured when the bound was recorded: the largest channel difference, the share of
# pixels (percent) more than 2/255 off, and the mean difference. Each figure must stay
# within its band, the measured value plus or minus the headroom
#   max:   max(3, 10% rounded up)     share: max(0.25 points, 10%)     mean: max(0.05, 10%)
# both ways: a larger error is a regression, a smaller one is a change to the image
# too (re-measure and record it). EXPECT is "within" or "outside" (the broken-shader
# tests: OIT_SHADER_DIR points at a deliberately broken copy, and the same bound must
# notice). The figures are printed either way.
set -u
oit=$1 expect=$2 reference=$3 out=$4 measured=$5
shift 6
mkdir -p "$(dirname "$out")"
"$oit" render "$@" --out "$out" || { echo "FAIL: render exited $?" >&2; exit 1; }
json=$("$oit" compare "$out" "$reference" --tolerance 2 --json --diff "${out%.png}.diff.png")
case $? in 0|1) ;; *) echo "FAIL: compare failed: $json" >&2; exit 1 ;; esac
field() { sed -n "s/.*\"$1\": \([-0-9.e+]*\).*/\1/p" <<<"$json"; }
verdict=$(awk -v max="$(field max_channel_diff)" -v share="$(field over_tolerance_percent)" \
              -v mean="$(field mean_diff)" -v recorded="$measured" '
    # prints "NAME VALUE (bound LOW..HIGH)"; notes NAME when VALUE is outside
    function band(name, value, low, high, format) {
        printf "%s " format " (bound " format ".." format ")", name, value, low, high
        if (value < low || value > high)
            outside = outside (outside == "" ? "" : ", ") name
    }
    function headroom(x, floor) { return x * 0.1 > floor ? x * 0.1 : floor }
    function at_least_0(x) { return x < 0 ? 0 : x }
    BEGIN {
        if (split(recorded, r, " ") != 3) { print "bad recorded figures: " recorded; exit 2 }
        hm = int(r[1] * 0.1); if (hm < r[1] * 0.1) hm++; if (hm < 3) hm = 3
        hs = headroom(r[2], 0.25); hmean = headroom(r[3], 0.05)
        band("max channel diff", max, at_least_0(r[1] - hm), r[1] + hm, "%d"); printf ", "
        band("share over 2/255", share, at_least_0(r[2] - hs), r[2] + hs, "%.3f%%"); printf ", "
        band("mean diff", mean, at_least_0(r[3] - hmean), r[3] + hmean, "%.4f")
        print (outside == "" ? ": within the recorded bound" : ": OUTSIDE the recorded bound (" outside ")")
        exit (outside == "" ? 0 : 1)
    }')
status=$?
echo "$verdict"
case "$expect:$status" in
    within:0|outside:1) exit 0 ;;
    *) echo "FAIL: expected '$expect' the recorded bound ($measured)" >&2; exit 1 ;;
esac
