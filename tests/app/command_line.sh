#!/usr/bin/env bash
# command_line.sh WORKBENCH WORK: the workbench's command line, run inside one
# xvfb-run (tests/app.cmake) so every start finds $DISPLAY.
set -euo pipefail
workbench=$1 work=$2
rm -rf "$work" && mkdir -p "$work" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"
run() { "$workbench" "$@"; }
fail() { echo "FAIL: $*" >&2; exit 1; }
[ -n "${DISPLAY:-}" ] || fail "no DISPLAY: run this under xvfb-run"

env -u DISPLAY -u WAYLAND_DISPLAY "$workbench" --help | grep -q -- "--screenshot" \
  || fail "--help (without a display) does not list --screenshot"

# one frame of the whole window, on the default model, view at the size asked for
run --algorithm ll --size 200x150 --screenshot "$work/window.png" > "$work/out.txt"
grep -q "window.png" "$work/out.txt" || fail "no screenshot path printed"
head -c 8 "$work/window.png" | od -An -c | grep -q "P   N   G" || fail "window.png is not a PNG"
width=$(od -An -tu1 -j16 -N4 "$work/window.png" | awk '{print $1*16777216+$2*65536+$3*256+$4}')
height=$(od -An -tu1 -j20 -N4 "$work/window.png" | awk '{print $1*16777216+$2*65536+$3*256+$4}')
[ "$width" -gt 200 ] && [ "$height" -gt 150 ] || fail "window.png is ${width}x${height}, smaller than its view"

# a preset on the command line
cat > "$work/preset.json" <<'JSON'
{"algorithm": "dp", "alpha": 0.8, "shading": "flat"}
JSON
run --preset "$work/preset.json" --size 120x90 --screenshot "$work/preset.png" > /dev/null \
  || fail "a good preset was refused"

# the default model with gear_1 selected and the others ghosted: a different window
# from the same command without (the highlight and the faded parts), same size
run --algorithm ll --size 120x90 --tab parts --screenshot "$work/plain.png" > /dev/null
run --algorithm ll --size 120x90 --tab parts --select gear_1 --fade-others 10 --screenshot "$work/ghosted.png" > /dev/null \
  || fail "--select gear_1 --fade-others 10 failed"
cmp -s "$work/plain.png" "$work/ghosted.png" && fail "--select and --fade-others changed nothing in the window"

# bad input: exit 2 (3 for a frame that fails) and a one-line reason
expect_error() {
  local expected=2
  if [ "$1" = "--status" ]; then expected=$2; shift 2; fi
  local pattern=$1; shift
  set +e
  run "$@" > "$work/stdout.txt" 2> "$work/stderr.txt"
  local status=$?
  set -e
  [ "$status" -eq "$expected" ] || fail "$* exited $status, expected $expected"
  grep -q "oit-workbench: error: .*$pattern" "$work/stderr.txt" || { cat "$work/stderr.txt" >&2; fail "$*: no message naming '$pattern'"; }
}
printf 'not a model\n' > "$work/bad.obj"
expect_error "bad.obj" "$work/bad.obj" --screenshot "$work/never.png"
expect_error "unknown algorithm" --algorithm nonesuch --screenshot "$work/never.png"
expect_error "--size" --size 12 --screenshot "$work/never.png"
printf '{\n  "alpha": 2\n}\n' > "$work/bad-preset.json"
expect_error "bad-preset.json:2:" --preset "$work/bad-preset.json" --screenshot "$work/never.png"
# --select and --fade-others (issue 27): names as `oit render --highlight` takes them
expect_error "no part or assembly named 'nonesuch'" --select gear_1,nonesuch --screenshot "$work/never.png"
expect_error "--fade-others '10' needs --select" --fade-others 10 --screenshot "$work/never.png"
expect_error "--fade-others '150' needs --select and 0..100" --select gear_1 --fade-others 150 --screenshot "$work/never.png"
# a session (docs/sessions.md) instead of a model; a newer one is refused in one line
session=$(cd "$(dirname "$0")/../data/sessions" && pwd)/gearbox-v1.oitsession
run "$session" --size 120x90 --screenshot "$work/session.png" > /dev/null || fail "the version-1 session did not open"
sed 's/"version": 1/"version": 2/' "$session" > "$work/newer.oitsession"
expect_error "newer.oitsession: version 2 is newer than this build reads" "$work/newer.oitsession" --screenshot "$work/never.png"
[ ! -e "$work/never.png" ] || fail "a screenshot was written after an error"
# an option the algorithm cannot express (dp has no heatmap) is left out, never a
# grey view: the frame renders and one warning line names what was left out
printf '{"view": "heatmap"}\n' > "$work/heatmap.json"
run --algorithm dp --preset "$work/heatmap.json" --size 64x64 --screenshot "$work/left-out.png" \
  > "$work/stdout.txt" 2> "$work/stderr.txt" || fail "dp with a heatmap preset failed instead of leaving it out"
grep -q "^oit-workbench: warning: dp left out: dp: buffer views are ll's and ib's (view 'heatmap')" "$work/stderr.txt" \
  || { cat "$work/stderr.txt" >&2; fail "no warning naming the heatmap dp left out"; }
# no OpenGL context (a driver that does not exist): the frame fails with exit 3. Mesa's
# failed EGL initialisation leaks and unloads its driver, so LeakSanitizer could only
# name "<unknown module>" (no suppression can match it): leak checks are off for this run
ASAN_OPTIONS="${ASAN_OPTIONS:-}:detect_leaks=0" GALLIUM_DRIVER=nonesuch expect_error --status 3 "frame failed: no OpenGL context" \
  --size 64x64 --screenshot "$work/no-context.png"
echo "command line: ok"
