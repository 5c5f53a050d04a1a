#!/usr/bin/env bash
# measure_linked_lists.sh: per-pixel linked lists alone (fill, sort, compose) at 600x600, every scene view
# (the source's counterpart: thesis appendix E.3). Appends to BUILD/bench/results/linked_lists.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh).
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/linked_lists.txt"
measure_views 1 "$RESULTS/linked_lists.txt"
echo "$RESULTS/linked_lists.txt"
