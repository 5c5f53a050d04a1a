#!/usr/bin/env bash
# workbench.sh [BUILD_DIR] [workbench arguments...]: the README's first command.
# Starts oit-workbench on the bundled gearbox where a display exists; where none
# does ($DISPLAY and $WAYLAND_DISPLAY unset) it says so and runs the headless
# `oit demo` instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
workbench=$build/src/app/oit-workbench
oit=$build/src/cli/oit
if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
  echo "oit-workbench: no display (\$DISPLAY and \$WAYLAND_DISPLAY are unset), running the headless 'oit demo' instead" >&2
  echo "  (with a display, or under xvfb-run, this starts the workbench on resources/models/gearbox.obj)" >&2
  exec "$oit" demo
fi
if [ ! -x "$workbench" ]; then
  echo "oit-workbench: $workbench was not built (Qt 5 missing? see config/debian-packages.txt), running 'oit demo' instead" >&2
  exec "$oit" demo
fi
if [ $# -eq 0 ]; then
  set -- "$root/resources/models/gearbox.obj"
fi
exec "$workbench" "$@"
