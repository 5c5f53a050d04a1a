#!/usr/bin/env bash
# import_overhead.sh [BUILD_DIR]: what importing in a contained worker process
# costs (src/core/model/model_contained.c), side by side with importing in the calling
# process (OIT_IMPORT=in-process), on models from 6k to 1.7M triangles: the
# median wall time of 5 `oit info` runs each, alternating the two ways.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
oit=$build/src/cli/oit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$oit" gen spheres --complexity 7 --out "$work/spheres7.obj" > /dev/null
"$oit" gen spheres --complexity 12 --out "$work/spheres12.obj" > /dev/null
models=("$root/resources/models/gearbox.obj" /usr/share/assimp/models/PLY/Wuson.ply
        "$work/spheres7.obj" "$work/spheres12.obj")
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
seconds() { local start end; start=$(date +%s.%N); "$@" > /dev/null; end=$(date +%s.%N); echo "$end - $start" | bc; }
echo "| model | triangles | MB | in-process s | contained s | contained / in-process |"
echo "| --- | --- | --- | --- | --- | --- |"
for model in "${models[@]}"; do
  [ -f "$model" ] || continue
  triangles=$("$oit" info --model "$model" --json | python3 -c 'import json,sys; print(json.load(sys.stdin)["triangles"])')
  inproc=() contained=()
  for _ in 1 2 3 4 5; do
    inproc+=("$(OIT_IMPORT=in-process seconds "$oit" info --model "$model")")
    contained+=("$(seconds "$oit" info --model "$model")")
  done
  a=$(printf '%s\n' "${inproc[@]}" | median) b=$(printf '%s\n' "${contained[@]}" | median)
  mb=$(echo "scale=1; $(stat -c %s "$model") / 1048576" | bc)
  printf '| %s | %s | %s | %.3f | %.3f | %.2f |\n' "$(basename "$model")" "$triangles" "$mb" "$a" "$b" \
    "$(echo "$b / $a" | bc -l)"
done
