#!/usr/bin/env bash
# screenshots.sh [BUILD_DIR]: the workbench screenshots in docs/images/workbench/,
# each one `oit-workbench --screenshot` (one frame of the whole window) on a real
# model with an algorithm, a preset and a settings tab. Runs under xvfb-run when
# there is no display. From the repository root, after a build:
#
#     bash bat/screenshots.sh build
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
workbench=$build/src/app/oit-workbench
out=$root/docs/images/workbench
presets=$(mktemp -d)
trap 'rm -rf "$presets"' EXIT
mkdir -p "$out"
[ -x "$workbench" ] || { echo "screenshots.sh: $workbench is not built" >&2; exit 2; }

gearbox=$root/resources/models/gearbox.obj
spider=/usr/share/assimp/models/OBJ/spider.obj
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb

# settings presets: the keys are `oit render`'s flag names
cat > "$presets/spider-parts.json" <<'JSON'
{"alpha": 0.6, "component-alpha": {"HLeib01": 0.15, "OK": 0.15, "Brust": 0.2},
 "hide": ["Bein1Li", "Bein1Re"]}
JSON
cat > "$presets/engine-heatmap.json" <<'JSON'
{"view": "heatmap"}
JSON
cat > "$presets/engine-focus.json" <<'JSON'
{"alpha": 0.7, "focus-point": [0, -44, -6], "focus-region": 160}
JSON
cat > "$presets/gearbox-blend.json" <<'JSON'
{"alpha": 0.6}
JSON
cat > "$presets/gearbox-ib.json" <<'JSON'
{"alpha": 0.8, "modulation": "curvature", "curvature-effect": 6}
JSON
# issue 28: the gearbox cut open by a plane (front 0.35 removed; caps on its closed
# parts) and exploded by 0.5, beside the plain gearbox (gearbox-window.png)
cat > "$presets/gearbox-sectioned.json" <<'JSON'
{"alpha": 0.6, "section": [{"plane": [0, 0, 1, -0.1], "enabled": true}], "explode": 0.5}
JSON
# the split view (the workbench's own keys): ll left of the wipe line, blend right
cat > "$presets/gearbox-split.json" <<'JSON'
{"alpha": 0.6, "split": "wipe", "split-algorithm": "blend", "wipe": 0.5}
JSON
# the error view (`oit render --error-vs-reference`): blend's error map against the reference
cat > "$presets/gearbox-error.json" <<'JSON'
{"alpha": 0.6, "error-vs-reference": true}
JSON

# a deep model (343 spheres, 28 layers) whose dp frame takes seconds on llvmpipe
"$build/src/cli/oit" gen spheres --complexity 7 --out "$presets/spheres.obj" > /dev/null

run() {
  local name=$1; shift
  local command=("$workbench" --screenshot "$out/$name.png" "$@")
  if [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; then
    command=(xvfb-run -a -s "-screen 0 1400x1000x24" "${command[@]}")
  fi
  echo "== $name: ${*}"
  "${command[@]}" > /dev/null
}

# the window as it opens on the 1400x1000 screen (1200x760): the view dominates, the settings
# panel narrow beside it
run gearbox-window "$gearbox" --algorithm ll --tab opacity
# ghosting: the two pistons selected (highlighted), every other part faded to 10%
run engine-ghosted "$engine" --algorithm ll --tab parts \
  --select "Piston_123-844_0_Parts_1-0,Piston_123-844_0_Parts_1-0#2" --fade-others 10
run gearbox-ll-stats "$gearbox" --algorithm ll --tab stats
run gearbox-blend-opacity "$gearbox" --algorithm blend --preset "$presets/gearbox-blend.json" --tab opacity
run gearbox-ib-curvature "$gearbox" --algorithm ib --preset "$presets/gearbox-ib.json" --tab opacity
run spider-dp-parts "$spider" --algorithm dp --preset "$presets/spider-parts.json" --tab parts
run gearbox-split-wipe "$gearbox" --algorithm ll --preset "$presets/gearbox-split.json" --tab compare
run gearbox-blend-error "$gearbox" --algorithm blend --preset "$presets/gearbox-error.json" --tab compare
run engine-ll-heatmap "$engine" --algorithm ll --preset "$presets/engine-heatmap.json" --tab views
run engine-wboit-focus "$engine" --algorithm wboit --preset "$presets/engine-focus.json" --tab opacity
run gearbox-sectioned "$gearbox" --algorithm ll --preset "$presets/gearbox-sectioned.json" --tab sections
# a long frame in progress: the stand-in's preview, the status naming both, the peel count, Cancel
run spheres-dp-progress "$presets/spheres.obj" --algorithm dp --screenshot-after 4000
echo "wrote $(ls "$out"/*.png | wc -l) screenshots to $out"
