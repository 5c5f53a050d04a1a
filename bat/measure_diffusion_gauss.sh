#!/usr/bin/env bash
# measure_diffusion_gauss.sh: one diffusion pass and one Gaussian pass at 600x600, every scene view
# (the source's counterpart: thesis appendix E.3). Appends to BUILD/bench/results/diffusion_gauss.txt.
# Options: --build DIR, --quick, --frames N, --scenes REGEX (bat/measure_lib.sh).
source "$(dirname "$0")/measure_lib.sh"
rm -f "$RESULTS/diffusion_gauss.txt"
measure_views 4 "$RESULTS/diffusion_gauss.txt"
echo "$RESULTS/diffusion_gauss.txt"
