# ib_lib.sh: helpers for the Illustration Buffer tests (sourced after lib.sh).
# ib_render OUT.png|- [render args...]: renders 128x128 with ib, JSON to OUT.json
ib_render() {
    local out=$1; shift
    if [ "$out" = - ]; then
        "$oit" render --algorithm ib --size 128x128 --json "$@" || fail "render failed: $*"
    else
        "$oit" render --algorithm ib --size 128x128 --json --out "$out" "$@" >"${out%.png}.json" \
            || fail "render failed: $*"
    fi
}
# ib_py SCRIPT ARGS...: runs python with ib_png importable; fails the test on error
ib_py() {
    local script=$1; shift
    PYTHONPATH="$tests_dir${PYTHONPATH:+:$PYTHONPATH}" python3 -c "$script" "$@" || fail "check failed"
}
tests_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
