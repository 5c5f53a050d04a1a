#!/usr/bin/env bash
# profile.sh: where the time of ll and ib goes on llvmpipe, from perf (Debian linux-perf).
# Records one scene (default engine-longest from the bench's scene list) with `oit render
# --frames 4` for ll and ib and writes BUILD/bench/results/profile.txt: the share of samples
# in llvmpipe's JIT-compiled shader code, in the driver, in the kernel and elsewhere, which
# bat/report.py quotes where a target is missed. Skipped (exit 0) when perf is missing.
# Options: --build DIR (default build), --quick, --scene NAME, --size N (default 600)
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BUILD=$ROOT/build
SCENE=engine-longest
SIZE=600
SUFFIX=
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$2; shift 2 ;;
    --quick) SUFFIX=-quick; shift ;;
    --scene) SCENE=$2; shift 2 ;;
    --size) SIZE=$2; shift 2 ;;
    -h | --help) sed -n '2,/^$/p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "profile.sh: unknown option '$1'" >&2; exit 2 ;;
    esac
done
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
OIT=$BUILD/src/cli/oit
RESULTS=$BUILD/bench/results$SUFFIX
mkdir -p "$RESULTS"
if ! command -v perf >/dev/null || ! perf record -o /dev/null -- true >/dev/null 2>&1; then
    echo "profile.sh: perf is missing or not permitted (Debian linux-perf; kernel.perf_event_paranoid <= 2); skipped" >&2
    rm -f "$RESULTS/profile.txt"
    exit 0
fi
read -r _ model options < <(grep -E "^$SCENE " "$BUILD/bench/scenes$SUFFIX.txt")
[ -n "${model:-}" ] || { echo "profile.sh: no scene $SCENE in $BUILD/bench/scenes$SUFFIX.txt (run bat/setup.py)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
summary=()
led=() trailed=()   # the algorithms whose largest share is the JIT-compiled shader code, and the others
for algorithm in ll ib; do
    # shellcheck disable=SC2086  # the scene's view options are separate words
    perf record -q -F 999 -o "$work/$algorithm.data" -- "$OIT" render --model "$model" $options \
        --algorithm $algorithm --size "${SIZE}x${SIZE}" --frames 4 >/dev/null 2>&1
    shares=$(perf report -i "$work/$algorithm.data" --sort dso --stdio 2>/dev/null | awk '
        /^ *[0-9.]+%/ { share = $1 + 0; $1 = ""; dso = $0
            if (dso ~ /\[JIT\]/) jit += share
            else if (dso ~ /swrast_dri|libgallium|libLLVM/) driver += share
            else if (dso ~ /kernel/) kernel += share
            else other += share }
        END { printf "%.0f %.0f %.0f %.0f", jit, driver, kernel, other }')
    read -r jit driver kernel other <<<"$shares"
    summary+=("\`$algorithm\` $jit % in JIT-compiled shader code, $driver % in the driver (swrast_dri, LLVM), $kernel % in the kernel, $other % elsewhere (model import, libc)")
    if [ "$jit" -ge "$driver" ] && [ "$jit" -ge "$kernel" ] && [ "$jit" -ge "$other" ]; then
        led+=("\`$algorithm\`")
    else
        trailed+=("\`$algorithm\`")
    fi
done
# the closing sentence follows the shares measured above
if [ ${#trailed[@]} -eq 0 ]; then
    verdict="For both, llvmpipe running the shaders themselves is the largest share, so the stage breakdown shows where the time goes."
else
    verdict="For ${trailed[*]} the shaders themselves are not the largest share, so the stage breakdown shows only part of where the time goes."
fi
printf 'A perf profile of %s at %sx%s (`bat/profile.sh`, 4 frames, all threads): %s; %s. %s\n' \
    "$SCENE" "$SIZE" "$SIZE" "${summary[0]}" "${summary[1]}" "$verdict" >"$RESULTS/profile.txt"
cat "$RESULTS/profile.txt"
