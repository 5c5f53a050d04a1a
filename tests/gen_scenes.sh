#!/usr/bin/env bash
# gen_scenes.sh OIT DIR WORK: writes every generated test scene into DIR and
# makes the output folders under WORK (a test fixture).
set -eu
oit=$1 dir=$2 work=$3
mkdir -p "$dir" "$work/reference" "$work/egl" "$work/osmesa"
"$oit" gen cyclic --out "$dir/cyclic.obj"
"$oit" gen onion --out "$dir/onion.obj"
"$oit" gen spheres --out "$dir/spheres.obj"
"$oit" gen gearbox --out "$dir/gearbox.obj"
"$oit" gen coplanar --out "$dir/coplanar.obj"
"$oit" gen menger --complexity 3 --out "$dir/menger.obj"
for scene in cyclic onion spheres gearbox coplanar menger; do
    "$oit" info --model "$dir/$scene.obj" --json
done
