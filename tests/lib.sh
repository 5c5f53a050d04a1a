# lib.sh: helpers shared by the test scripts (sourced, not run).
set -u

fail() { echo "FAIL: $*" >&2; exit 1; }

# expect_exit CODE PATTERN -- command...
# Runs the command, checks its exit status, that stderr is exactly one line on
# a usage or runtime error (2, 3), and that it matches PATTERN (extended regexp, case-insensitive).
expect_exit() {
    local want=$1 pattern=$2
    shift 3
    local err out status
    err=$(mktemp) out=$(mktemp)
    timeout 120 "$@" >"$out" 2>"$err"
    status=$?
    if [ "$status" -ne "$want" ]; then
        echo "command: $*" >&2; cat "$err" >&2
        rm -f "$err" "$out"
        fail "expected exit $want, got $status"
    fi
    if [ "$want" -ge 2 ]; then
        local lines
        lines=$(wc -l <"$err")
        [ "$lines" -eq 1 ] || { cat "$err" >&2; rm -f "$err" "$out"; fail "expected one line on stderr, got $lines: $*"; }
        grep -Eqi -- "$pattern" "$err" || { cat "$err" >&2; rm -f "$err" "$out"; fail "stderr does not match /$pattern/: $*"; }
        echo "ok ($status): $(cat "$err")"
    fi
    rm -f "$err" "$out"
}
