#!/usr/bin/env bash
# measure_construction.sh: Illustration Buffer construction (fill, sort, neighbours) at 600x600, every scene view
# (the source's counterpart: thesis appendix E.3). Appends to BUILD/bench/results/ib_construction.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh).
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/ib_construction.txt"
measure_views 2 "$RESULTS/ib_construction.txt"
echo "$RESULTS/ib_construction.txt"
