#!/usr/bin/env bash
# bench_report.sh OIT WORKDIR SCENES SOURCE: bat/report.py turns a tiny bench run
# into benchmarks.md with its sections and plots (shape only, no timings).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 source=$4
rm -rf "$work"; mkdir -p "$work/results" "$work/docs"
printf 'onion-a %s/onion.obj --orbit 0,0\nspheres-b %s/spheres.obj --orbit 30,20\n' "$scenes" "$scenes" >"$work/scenes.txt"
"$oit" bench --scene-list "$work/scenes.txt" --algorithms blend,dp,ddp,ll,ll-array,ib,wboit --sizes 32 --frames 1 \
    --warmup 0 --quiet --reference-max-pixels 0 --csv "$work/results/bench.csv" --json "$work/results/bench.json" \
    || fail "bench"
"$oit" bench --scene-list "$work/scenes.txt" --algorithms ll,ib --sizes 24 --frames 1 --warmup 0 --quiet \
    --reference-max-pixels 1000 --csv "$work/results/accuracy.csv" || fail "accuracy bench"
mv="1 0 0 0 0 1 0 0 0 0 1 -3 0 0 0 1"
p="1.8 0 0 0 0 1.8 0 0 0 0 -1.2 -2.2 0 0 -1 0"
for size in 24 32; do
    # shellcheck disable=SC2086
    "$oit" measure --results "$work/results/ib_resolutions.txt" --frames 1 --warmup 0 2 1 onion "$scenes/onion.obj" $mv $p $size >/dev/null || fail "measure"
done
python3 "$source/bat/report.py" --results "$work/results" --docs "$work/docs" --command "tests/bench_report.sh" \
    || fail "report.py"
page=$work/docs/benchmarks.md
for heading in "## Targets" "## Scenes" "## Frame time per algorithm and scene" "## Our ratios beside the thesis's" \
    "## Illustration Buffer: stage breakdown" "## Parallel coordinates" "## Memory per algorithm" "## Resolution sweep" \
    "## Difference from the reference"; do
    grep -qF "$heading" "$page" || fail "benchmarks.md lacks '$heading'"
done
grep -q "llvmpipe" "$page" || fail "benchmarks.md must name the driver"
for image in frame-times ratios ib-stages parallel memory resolutions; do
    [ -s "$work/docs/images/bench-$image.png" ] || fail "no plot bench-$image.png"
done
echo "report ok"
