#!/usr/bin/env bash
# run_comparison.sh: the whole benchmark on a freshly set-up checkout, in one command.
#   1. builds oit (Release) into BUILD if it is not there
#   2. installs the models and writes the scene lists (bat/setup.py, config/bench-scenes.json)
#   3. oit bench: every scene x blend, dp, ddp, ll, ll-array, ib, wboit at 600x600
#      -> BUILD/bench/results/bench.csv (+ .json); then every scene at 128x128, one frame,
#      against the CPU reference -> accuracy.csv
#   3b. the cost/quality map: every algorithm and parameter (kbuffer/hybrid/mlab k = 4/8/16, mboit
#      power4/power6/trig3, wavelet rank 1/2/3, stochastic N = 4/8/16, adaptive k = 4/8/16) against the
#      reference -> quality.json and quality-bundle/; the flicker of a slow orbit -> stability.json;
#      nested spheres of growing depth -> depth_sweep.json
#   3d. ll's four sorts (insertion, array, bma, merge) on the deepest views -> sorts.json
#   3c. scale (bat/scale.py): the deepest scenes at 1920x1080 and 3840x2160, and a level-5 Menger
#      sponge (13M triangles) at 600x600 and 1920x1080 -> scale.json
#   4. the source's six measurements (bat/measure_*.sh) -> BUILD/bench/results/*.txt
#   5. a perf profile of ll and ib on one scene (bat/profile.sh; skipped without perf)
#   6. bat/report.py -> docs/benchmarks.md and docs/images/bench-*.png (with the machine of step 3,
#      recorded in BUILD/bench/results/machine.json by bat/pages.py machine)
# Options:
#   --build DIR   build directory (default build)
#   --quick       4 models, 256x256, fewer frames, measurements at 300x300, resolution sweep
#                 400..500; the report goes
#                 to BUILD/bench/quick-docs/ instead of docs/ (a smoke test, minutes not hours)
#   --skip-measure  only oit bench and the report
#   --quality-only  only step 3b, then `report.py --section quality` rewrites that section of the
#                 existing docs/benchmarks.md (saying which command and commit made it); with
#                 --quick, of BUILD/bench/quick-docs/benchmarks.md. About 20 minutes.
# The full run takes about 1.5 hours on a quiet 2-core machine with llvmpipe (estimated from
# single-frame runs of every scene; menger4 alone, with dp and ddp at 80-90 s a frame, is a quarter);
# --quick about 10 minutes.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$ROOT/build
QUICK=0
MEASURE=1
QUALITY_ONLY=0
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$2; shift 2 ;;
    --quick) QUICK=1; shift ;;
    --skip-measure) MEASURE=0; shift ;;
    --quality-only) QUALITY_ONLY=1; MEASURE=0; shift ;;
    -h | --help) sed -n '2,/^$/p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "run_comparison.sh: unknown option '$1' (--build DIR, --quick, --skip-measure, --quality-only)" >&2; exit 2 ;;
    esac
done
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
OIT=$BUILD/src/cli/oit
started=$(date +%s)
step() { echo "== $(date -u +%H:%M:%S) $*" >&2; }

if [ ! -x "$OIT" ]; then
    step "building oit into $BUILD"
    cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
ninja -C "$BUILD" oit >/dev/null

quick=()
suffix=
if [ "$QUICK" = 1 ]; then
    quick=(--quick)
    suffix=-quick
fi
step "models and scene lists"
python3 "$ROOT/bat/setup.py" --build "$BUILD" "${quick[@]}"
RESULTS=$BUILD/bench/results$suffix
mkdir -p "$RESULTS"
SCENES=$BUILD/bench/scenes$suffix.txt

if [ "$QUICK" = 1 ]; then
    bench_flags=(--sizes 256 --frames 3 --warmup 1)
    accuracy_size=96
    measure_flags=(--quick --frames 2 --viewport 300)
    resolution_sizes="400 450 500"
    docs=$BUILD/bench/quick-docs
else
    # 5 frames: llvmpipe's frame times vary by a few % (min/max are reported);
    # heavy scenes (menger4: dp takes ~30 s a frame) stop after 3 frames past 10 s
    bench_flags=(--sizes 600 --frames 5 --warmup 1 --time-budget 10)
    accuracy_size=128
    measure_flags=(--frames 2)
    resolution_sizes=
    docs=$ROOT/docs
fi

step "the machine (CPU, cores, GL renderer) -> $RESULTS/machine.json"
python3 "$ROOT/bat/pages.py" machine --oit "$OIT" >"$RESULTS/machine.json"
# the accuracy run counts a pixel as off as the tests do (report.py reads the same bound)
tolerance=$(sed -n 's/^set(EXACT_TOLERANCE \([0-9]*\))$/\1/p' "$ROOT/tests/CMakeLists.txt")
[ -n "$tolerance" ] || { echo "run_comparison.sh: no set(EXACT_TOLERANCE N) in tests/CMakeLists.txt" >&2; exit 2; }

bench_status=0
accuracy_status=0
set +e
if [ "$QUALITY_ONLY" = 0 ]; then
step "oit bench (progress on stderr)"
"$OIT" bench --scene-list "$SCENES" --algorithms blend,dp,ddp,ll,ll-array,ib,wboit "${bench_flags[@]}" \
    --reference-max-pixels 0 --csv "$RESULTS/bench.csv" --json "$RESULTS/bench.json"
bench_status=$?
step "accuracy against the reference at ${accuracy_size}x${accuracy_size}"
"$OIT" bench --scene-list "$SCENES" --algorithms blend,dp,ddp,ll,ib,wboit --sizes $accuracy_size \
    --frames 1 --warmup 0 --reference-max-pixels $((accuracy_size * accuracy_size)) --tolerance "$tolerance" --quiet \
    --csv "$RESULTS/accuracy.csv"
accuracy_status=$?
fi
set -e

# The cost/quality map of the approximations (issue 12; bat/quality_map.py draws it): every
# algorithm and parameter on every scene against the reference, with a bundle of the images;
# the flicker of a slow orbit on a few scenes; and a depth sweep over nested spheres.
quality_algorithms=blend,wboit,kbuffer:4,kbuffer:8,kbuffer:16,hybrid:4,hybrid:8,hybrid:16,mlab:4,mlab:8,mlab:16,mboit:power4,mboit:power6,mboit:trig3,wavelet:1,wavelet:2,wavelet:3,stochastic:4,stochastic:8,stochastic:16,adaptive:4,adaptive:8,adaptive:16,ll,dp
quality_size=$accuracy_size
stability_frames=24
sweep_complexities="1 2 4 8 16 32"
if [ "$QUICK" = 1 ]; then
    stability_frames=6
    sweep_complexities="1 4 16"
fi
set +e
step "cost and quality: every algorithm and parameter at ${quality_size}x${quality_size} -> quality.json"
"$OIT" bench --scene-list "$SCENES" --algorithms "$quality_algorithms" --sizes "$quality_size" --frames 3 --warmup 1 \
    --reference-max-pixels $((quality_size * quality_size)) --quiet --json "$RESULTS/quality.json" \
    --bundle "$RESULTS/quality-bundle"
step "temporal stability: $stability_frames frames of a slow orbit -> stability.json"
"$OIT" bench --scene-list "$SCENES" --scenes 'gearbox*,engine*,spheres-*,onion*' --algorithms "$quality_algorithms" \
    --sizes 128 --frames 1 --warmup 0 --orbit-sequence "$stability_frames" --quiet --json "$RESULTS/stability.json"
step "depth sweep: nested spheres, complexity $sweep_complexities -> depth_sweep.json"
sweep_dir=$BUILD/bench/depth_sweep
mkdir -p "$sweep_dir"
: >"$sweep_dir/scenes.txt"
for complexity in $sweep_complexities; do
    "$OIT" gen onion --complexity "$complexity" --out "$sweep_dir/onion$complexity.obj"
    echo "onion$complexity $sweep_dir/onion$complexity.obj" >>"$sweep_dir/scenes.txt"
done
"$OIT" bench --scene-list "$sweep_dir/scenes.txt" --algorithms ll,dp,kbuffer:8,hybrid:8,mlab:8,adaptive:8,mboit:power4,wavelet:2,stochastic:8,wboit \
    --sizes "$quality_size" --frames 3 --warmup 1 --reference-max-pixels $((quality_size * quality_size)) --quiet \
    --json "$RESULTS/depth_sweep.json"
if [ "$QUALITY_ONLY" = 0 ]; then
    # Knowles' sorts against the plain ones (issue 30): the sort stage is what differs; the deepest
    # views, where the lists are longest, are where a sort shows
    step "ll's sorts on the deepest views -> sorts.json"
    "$OIT" bench --scene-list "$SCENES" --scenes 'engine-longest,menger4-longest,spheres11-longest' \
        --algorithms ll-insertion,ll-array,ll-bma,ll-merge "${bench_flags[@]}" --reference-max-pixels 0 --quiet \
        --json "$RESULTS/sorts.json"
    step "scale: the deepest scenes at 1920x1080 and 3840x2160, a 13M-triangle sponge -> scale.json"
    python3 "$ROOT/bat/scale.py" --oit "$OIT" --results "$RESULTS" --scene-list "$SCENES" \
        --models "$BUILD/bench/models" "${quick[@]}"
fi
set -e

[ $bench_status -eq 0 ] || echo "run_comparison.sh: some bench runs failed (rows with an error in bench.csv)" >&2
[ $accuracy_status -eq 0 ] || echo "run_comparison.sh: some accuracy runs failed (accuracy.csv)" >&2

if [ "$MEASURE" = 1 ]; then
    for script in linked_lists construction diffusion diffusion_gauss view_distance; do
        step "bat/measure_$script.sh"
        bash "$ROOT/bat/measure_$script.sh" --build "$BUILD" "${measure_flags[@]}"
    done
    step "bat/measure_resolutions.sh"
    if [ -n "$resolution_sizes" ]; then
        OIT_RESOLUTION_SIZES=$resolution_sizes bash "$ROOT/bat/measure_resolutions.sh" --build "$BUILD" "${measure_flags[@]}"
    else
        bash "$ROOT/bat/measure_resolutions.sh" --build "$BUILD" "${measure_flags[@]}"
    fi
fi

if [ "$QUALITY_ONLY" = 1 ]; then
    step "report: the cost/quality map section of $docs/benchmarks.md"
    elapsed=$(( $(date +%s) - started ))
    python3 "$ROOT/bat/report.py" --section quality --results "$RESULTS" --docs "$docs" \
        --command "$(echo bat/run_comparison.sh "${quick[@]}" --quality-only)"
    step "done in $((elapsed / 60)) min: the cost/quality map of $docs/benchmarks.md"
    exit 0
fi

step "bat/profile.sh (perf; skipped without it)"
if [ "$QUICK" = 1 ]; then
    bash "$ROOT/bat/profile.sh" --build "$BUILD" --quick --size 256 || true
else
    bash "$ROOT/bat/profile.sh" --build "$BUILD" || true
fi

step "report"
elapsed=$(( $(date +%s) - started ))
python3 "$ROOT/bat/report.py" --results "$RESULTS" --docs "$docs" --elapsed "$elapsed" \
    --command "$(echo bat/run_comparison.sh "${quick[@]}")"
step "done in $((elapsed / 60)) min: $docs/benchmarks.md"
