# lib.sh: helpers shared by the test scripts (sourced, not run).
set -u

fail() { echo "FAIL: $*" >&2; exit 1; }

# replace_once FILE OLD NEW: replaces OLD, which must occur exactly once in FILE,
# by NEW (for the tests that run a patched copy of the shader tree)
replace_once() {
    local file=$1 old=$2 new=$3
    [ "$(grep -cF -- "$old" "$file")" -eq 1 ] || fail "'$old' is not once in $file"
    OLD=$old NEW=$new perl -0pi -e 's/\Q$ENV{OLD}\E/$ENV{NEW}/' "$file"
    grep -qF -- "$new" "$file" || fail "$file unchanged"
}

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
