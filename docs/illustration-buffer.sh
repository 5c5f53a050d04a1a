#!/usr/bin/env bash
# illustration-buffer.sh OIT [OUT_DIR]: regenerates the measurements and the
# images of docs/illustration-buffer.md (llvmpipe, 256x256, median of frames 2-3).
#   OIT      the oit executable (e.g. build/src/cli/oit)
#   OUT_DIR  where images go (default: docs/images/ib next to this script)
# Prints the neighbour-search table as Markdown on stdout.
set -eu
oit=$1
here=$(cd "$(dirname "$0")" && pwd)
out=${2:-$here/images/ib}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"
for scene in onion spheres gearbox menger; do
    "$oit" gen $scene --out "$work/$scene.obj" >/dev/null
done
cp /usr/share/assimp/models/OBJ/spider.obj /usr/share/assimp/models/OBJ/spider.mtl "$work/" 2>/dev/null || true
engine=/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb
models="onion spheres gearbox menger spider engine"
model_path() { if [ "$1" = engine ]; then echo "$engine"; else echo "$work/$1.obj"; fi; }

echo "| scene | fragments | search | four neighbours | symmetric | same component | neighbours ms | frame ms |"
echo "|---|---:|---|---:|---:|---:|---:|---:|"
for scene in $models; do
    for search in index welded epsilon; do
        "$oit" render --model "$(model_path $scene)" --algorithm ib --size 256x256 --frames 3 \
            --neighbours $search --json >"$work/m.json"
        python3 - "$work/m.json" "$scene" "$search" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
stage = {s["name"]: s["gpu_ms"] for s in d["stages"]}
stage["neighbours"] += stage.get("neighbours_epsilon", 0.0)  # the whole search
print(f"| {sys.argv[2]} | {d['fragments']} | {sys.argv[3]} | {d['neighbours_four_share']:.3f} | "
      f"{d['neighbours_symmetric_share']:.3f} | {d['neighbours_same_component_share']:.3f} | "
      f"{stage['neighbours']:.0f} | {d['gpu_ms']:.0f} |")
PY
    done
done

render() { # NAME MODEL ARGS...
    local name=$1 model=$2; shift 2
    "$oit" render --model "$(model_path $model)" --algorithm ib --size 256x256 --out "$out/$name.png" "$@" >/dev/null
}
render onion_none onion
render onion_heatmap onion --view heatmap
render onion_neighbours_index onion --view neighbours --alpha 1 --neighbours index
render onion_neighbours_welded onion --view neighbours --alpha 1 --neighbours welded
render onion_curvature onion --modulation curvature --curvature-effect 20
render onion_distance onion --modulation distance
render onion_fields onion --modulation fields
render onion_fields_view onion --view fields:1
render gearbox_none gearbox
render gearbox_dist_curv gearbox --modulation dist-curv --curvature-effect 20
render gearbox_fields gearbox --modulation fields --halo-colour 1,0.6,0
render gearbox_edges gearbox --modulation edges --alpha 0.2
render spider_edges spider --modulation edges --alpha 0.2
render engine_none engine
render engine_fields engine --modulation fields --fields alpha,beta --last-layer-opaque
render engine_dist_curv engine --modulation dist-curv --curvature-effect 20
echo "images in $out" >&2
