#!/usr/bin/env bash
# startup.sh WORKBENCH WM_PING SHADERS WORK: the workbench's start on a broken
# installation or a broken saved state, run inside one xvfb-run (tests/app.cmake).
#  - no usable shader folder (missing, empty, one holding a FIFO): --screenshot
#    exits 3 with one line naming the problem; without it a dialog says it
#    (found by its title and answering the window manager's ping: shown, not
#    crashed, not hung);
#  - a settings file that is a FIFO: neither --screenshot nor a normal start
#    waits for it, and it stays a FIFO;
#  - --screenshot into a FIFO: refused at once (exit 2), the FIFO stays;
#  - OIT_BACKEND=bogus: exit 3, one line naming the values.
# The saved state lives in XDG_CONFIG_HOME, which this script points into WORK.
set -uo pipefail # not -e: expect_exit looks at failing commands' status
workbench=$1 probe=$2 shaders=$3 work=$4
source "$(dirname "$0")/../lib.sh"
[ -n "${DISPLAY:-}" ] || fail "no DISPLAY: run this under xvfb-run"
rm -rf "$work" && mkdir -p "$work" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR" || fail "cannot make $work"
export XDG_CONFIG_HOME=$work/config HOME=$work/home
mkdir -p "$XDG_CONFIG_HOME" "$HOME" || fail "cannot make the configuration folder"

workbench_pid=
stop_workbench() {
  [ -n "$workbench_pid" ] || return 0
  kill "$workbench_pid" 2>/dev/null || true
  for _ in $(seq 50); do kill -0 "$workbench_pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$workbench_pid" 2>/dev/null || true
  wait "$workbench_pid" 2>/dev/null || true
  workbench_pid=
}
trap stop_workbench EXIT
trap 'exit 143' INT TERM HUP

# window TITLE LOG: the workbench started in the background shows a window
# whose title holds TITLE and that answers pings (its event loop runs), and is
# still running; then it is stopped
window() {
  local title=$1 log=$2 status=0
  "$probe" --title "$title" --duration 1 --wait-window 60 > "$work/ping.json" 2> "$work/ping.err" || status=$?
  [ "$status" -eq 0 ] || { cat "$log" "$work/ping.err" >&2; fail "no window titled '*$title*' answering pings (wm_ping exit $status)"; }
  kill -0 "$workbench_pid" 2>/dev/null || { cat "$log" >&2; fail "the workbench exited"; }
  stop_workbench
  echo "ok: a window titled '*$title*' answers"
}

# --- no usable shader folder
mkdir -p "$work/empty" && cp -r "$shaders" "$work/fifo-shaders" && rm "$work/fifo-shaders/common/shade.glsl" &&
  mkfifo "$work/fifo-shaders/common/shade.glsl" || fail "cannot make the shader folders"
for entry in "$work/missing:OIT_SHADER_DIR=$work/missing holds no shaders" \
             "$work/empty:OIT_SHADER_DIR=$work/empty holds no shaders" \
             "$work/fifo-shaders:shader file $work/fifo-shaders/common/shade.glsl: not a regular file \(a FIFO\)"; do
  dir=${entry%%:*} message=${entry#*:}
  OIT_SHADER_DIR=$dir expect_exit 3 "^oit-workbench: error: $message" -- \
    "$workbench" --size 64x64 --screenshot "$work/never.png"
  [ ! -e "$work/never.png" ] || fail "a screenshot was written without shaders ($dir)"
done
OIT_SHADER_DIR=$work/missing "$workbench" > "$work/dialog.log" 2>&1 &
workbench_pid=$!
window "oit-workbench cannot start" "$work/dialog.log"
[ ! -e "$XDG_CONFIG_HOME/oit-workbench" ] || fail "the refused start wrote the saved state"

# --- a back end that does not exist: refused, naming the values (it meant EGL silently)
OIT_BACKEND=bogus expect_exit 3 "^oit-workbench: error: OIT_BACKEND=bogus: must be egl or osmesa" -- \
  "$workbench" --size 64x64 --screenshot "$work/never.png"
[ ! -e "$work/never.png" ] || fail "a screenshot was written with OIT_BACKEND=bogus"

# --- the settings file is a FIFO
settings=$XDG_CONFIG_HOME/oit-workbench/settings.json
mkdir -p "$XDG_CONFIG_HOME/oit-workbench" && mkfifo "$settings" || fail "cannot make the settings FIFO"
expect_exit 0 "" -- "$workbench" --size 64x64 --screenshot "$work/fifo-settings.png"
[ -s "$work/fifo-settings.png" ] || fail "no screenshot with a FIFO for settings"
"$workbench" --size 64x64 > "$work/fifo-settings.log" 2>&1 &
workbench_pid=$!
window "oit-workbench" "$work/fifo-settings.log"
[ -p "$settings" ] || fail "the settings FIFO was replaced"
[ "$(ls "$XDG_CONFIG_HOME/oit-workbench")" = settings.json ] || fail "files beside the settings FIFO: $(ls "$XDG_CONFIG_HOME/oit-workbench")"

# --- a screenshot into a FIFO: refused before anything waits for a reader
mkfifo "$work/shot.png" || fail "cannot make the screenshot FIFO"
expect_exit 2 "^oit-workbench: error: --screenshot $work/shot.png: not a regular file \(a FIFO\)" -- \
  "$workbench" --size 64x64 --screenshot "$work/shot.png"
[ -p "$work/shot.png" ] || fail "the screenshot FIFO was replaced"
echo "startup: ok"
