# measure_lib.sh: sourced by the bat/measure_*.sh scripts, the counterparts of the
# source's .bat files (thesis appendix E.3). Builds oit if needed, installs the
# models and views (bat/setup.py), then measure_views TASK RESULTS [VIEWPORT]
# runs `oit measure` once per scene view.
#   options: --build DIR (default build)  --quick (the config's quick models)
#            --frames N (measured frames per view, default 3)  --scenes REGEX (model names)
#            --viewport N (default 600, the thesis's; the resolution sweep sets its own)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BUILD=$ROOT/build
QUICK=0
FRAMES=3
WARMUP=1
SCENES=
VIEWPORT=600
while [ $# -gt 0 ]; do
    case $1 in
    --build) BUILD=$(cd "$2" 2>/dev/null && pwd || echo "$2"); shift 2 ;;
    --quick) QUICK=1; shift ;;
    --frames) FRAMES=$2; shift 2 ;;
    --scenes) SCENES=$2; shift 2 ;;
    --viewport) VIEWPORT=$2; shift 2 ;;
    -h | --help) sed -n '2,/^$/p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "$(basename "$0"): unknown option '$1' (--build DIR, --quick, --frames N, --scenes REGEX, --viewport N)" >&2; exit 2 ;;
    esac
done
case $BUILD in /*) ;; *) BUILD=$ROOT/$BUILD ;; esac
OIT=$BUILD/src/cli/oit
SUFFIX=
[ "$QUICK" = 1 ] && SUFFIX=-quick
VIEWS=$BUILD/bench/views$SUFFIX.txt
RESULTS=$BUILD/bench/results$SUFFIX
if [ ! -x "$OIT" ]; then
    cmake -S "$ROOT" -B "$BUILD" -G Ninja >/dev/null
    ninja -C "$BUILD" oit
fi
if [ ! -s "$VIEWS" ]; then
    quick_flag=()
    [ "$QUICK" = 1 ] && quick_flag=(--quick)
    python3 "$ROOT/bat/setup.py" --build "$BUILD" "${quick_flag[@]}"
fi
mkdir -p "$RESULTS"

# measure_views TASK RESULTS_FILE [VIEWPORT]: one `oit measure` per view in $VIEWS.
measure_views() {
    local task=$1 results=$2 viewport=${3:-$VIEWPORT}
    local name counter path numbers
    while read -r name counter path numbers; do
        case $name in '#'* | '') continue ;; esac
        if [ -n "$SCENES" ] && ! [[ $name =~ $SCENES ]]; then continue; fi
        # shellcheck disable=SC2086  # the 32 matrix numbers are separate arguments
        "$OIT" measure --results "$results" --frames "$FRAMES" --warmup "$WARMUP" \
            "$task" "$counter" "$name" "$path" $numbers "$viewport" ||
            echo "$(basename "$0"): $name $counter at $viewport failed (see above); going on" >&2
    done <"$VIEWS"
}
