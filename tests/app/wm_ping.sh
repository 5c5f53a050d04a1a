#!/usr/bin/env bash
# wm_ping.sh WORKBENCH OIT WM_PING WORK: the workbench answers the window
# manager's _NET_WM_PING within 250 ms while it loads and renders a deep model
# with dp (depth peeling: one frame is many seconds on llvmpipe). Desktops mark
# a window that misses the ping "not responding"; the answer comes from the GUI
# thread's event loop, so it is late exactly when that thread is busy.
# Run inside one xvfb-run (tests/app/wm_ping.cmake).
set -euo pipefail
workbench=$1 oit=$2 probe=$3 work=$4
source "$(dirname "$0")/../lib.sh"
limit_ms=250 size=900x800
[ -n "${DISPLAY:-}" ] || fail "no DISPLAY: run this under xvfb-run"
rm -rf "$work" && mkdir -p "$work" "$XDG_RUNTIME_DIR" && chmod 700 "$XDG_RUNTIME_DIR"

# 7 x 7 x 7 overlapping spheres: 329,280 triangles, 28 layers to peel
model=$work/spheres7.obj
"$oit" gen spheres --complexity 7 --out "$model" > /dev/null

# How long loading and one dp frame of it take on this machine (9 s, 8 of
# them the frame, on 2 idle llvmpipe cores; several times that on a busy
# machine): the workbench's first full frame ends about as long after its
# window appears, so the probe watches that long with a quarter to spare, and
# at least 20 s (the load and two frames on an idle machine).
start_ns=$(date +%s%N)
"$oit" render --model "$model" --algorithm dp --size "$size" --json --out "$work/cli.png" > "$work/cli.json" \
  || fail "oit render of the deep model failed"
wall_ms=$((($(date +%s%N) - start_ns) / 1000000))
frame_ms=$(sed -n 's/.*"cpu_ms": \([0-9]*\).*/\1/p' "$work/cli.json")
[ -n "$frame_ms" ] || fail "no cpu_ms in oit render --json: $(head -c 200 "$work/cli.json")"
duration=$((wall_ms * 5 / 4000 + 3))
[ "$duration" -ge 20 ] || duration=20
[ "$duration" -le 40 ] || duration=40 # a minute or so even on a busy machine
echo "one dp frame at $size: $frame_ms ms ($wall_ms ms with loading); pinging for $duration s"

workbench_pid=
stop_workbench() {
  [ -n "$workbench_pid" ] || return 0
  kill "$workbench_pid" 2>/dev/null || true
  # SIGTERM ends it even mid-frame (Qt leaves the signal alone); SIGKILL should it linger
  for _ in $(seq 50); do kill -0 "$workbench_pid" 2>/dev/null || break; sleep 0.1; done
  kill -KILL "$workbench_pid" 2>/dev/null || true
  wait "$workbench_pid" 2>/dev/null || true
  workbench_pid=
}
trap stop_workbench EXIT
trap 'exit 143' INT TERM HUP

"$workbench" --fresh --size "$size" --algorithm dp "$model" > "$work/workbench.log" 2>&1 &
workbench_pid=$!
# The title is "oit-workbench" from the start and names the model once it is
# in: match the former so that the probe starts with the window, before the load.
status=0
"$probe" --title oit-workbench --duration "$duration" --limit-ms "$limit_ms" --wait-window 60 \
  --json "$work/wm_ping.json" 2> "$work/wm_ping.err" || status=$?
kill -0 "$workbench_pid" 2>/dev/null || { tail -5 "$work/workbench.log" >&2; fail "the workbench exited during the test"; }
stop_workbench

case $status in
  0) echo "wm ping: ok (every ping answered within $limit_ms ms)" ;;
  1)
    worst=$(sed -n 's/.*"max_ms": \([0-9.]*\).*/\1/p' "$work/wm_ping.json")
    at=$(sed -n 's/.*"worst_at_s": \([0-9.]*\).*/\1/p' "$work/wm_ping.json")
    over=$(sed -n 's/.*"over_limit": \([0-9]*\).*/\1/p' "$work/wm_ping.json")
    # no latency over the limit: the window went away before the end
    [ -n "$over" ] && [ "$over" -gt 0 ] || fail "$(cat "$work/wm_ping.err")"
    fail "the workbench did not answer the window manager's ping for $worst ms (limit $limit_ms; sent ${at} s after its window appeared, $over pings late) loading and rendering $(basename "$model") with dp at $size"
    ;;
  *) tail -5 "$work/workbench.log" >&2; fail "wm_ping exited $status: $(cat "$work/wm_ping.err")" ;;
esac
