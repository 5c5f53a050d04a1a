#!/usr/bin/env bash
# measure_view_distance.sh: distance along the view ray and curvature (8 neighbours) at 600x600, every scene view
# (the source's counterpart: thesis appendix E.3). Appends to BUILD/bench/results/view_distance.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh).
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/view_distance.txt"
measure_views 5 "$RESULTS/view_distance.txt"
echo "$RESULTS/view_distance.txt"
