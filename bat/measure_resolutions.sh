#!/usr/bin/env bash
# measure_resolutions.sh: Illustration Buffer construction at 400x400 to 700x700 in steps
# of 50, every scene view (thesis appendix B, tables B.1-B.2). Appends to
# BUILD/bench/results/ib_resolutions.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh);
# OIT_RESOLUTION_SIZES="400 450" narrows the sweep.
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/ib_resolutions.txt"
for size in ${OIT_RESOLUTION_SIZES:-400 450 500 550 600 650 700}; do
    measure_views 2 "$RESULTS/ib_resolutions.txt" "$size"
done
echo "$RESULTS/ib_resolutions.txt"
