#!/usr/bin/env bash
# measure_diffusion.sh: one diffusion pass of the transparency fields at 600x600, every scene view
# (the source's counterpart: thesis appendix E.3). Appends to BUILD/bench/results/diffusion.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh).
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/diffusion.txt"
measure_views 3 "$RESULTS/diffusion.txt"
echo "$RESULTS/diffusion.txt"
