#!/usr/bin/env bash
# model_import.sh OIT SCENES: import through Assimp keeps parts, names, material
# colours and counts, across formats; welding merges seam duplicates.
source "$(dirname "$0")/lib.sh"
oit=$1 scenes=$2
models=/usr/share/assimp/models
info() { "$oit" info --model "$1" --json || fail "info $1"; }
python3 - "$(info $models/OBJ/spider.obj)" "$(info $models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb)" \
          "$(info $models/STL/Spider_ascii.stl)" "$(info $models/STL/Spider_binary.stl)" \
          "$(info $models/PLY/Wuson.ply)" "$(info "$scenes/onion.obj")" "$(info "$scenes/gearbox.obj")" <<'PY' || fail "model checks"
import json, sys
spider, engine, stl_ascii, stl_binary, ply, onion, gearbox = (json.loads(a) for a in sys.argv[1:])
# OBJ + MTL: one component per group, colours from Kd (spider.mtl: Skin Kd 0.827451 0.792157 0.772549)
assert spider["components"] == 19 and spider["triangles"] == 1368, spider
names = [p["name"] for p in spider["parts"]]
assert len(set(names)) == len(names), names
skin = [p for p in spider["parts"] if abs(p["colour"][0] - 0.8275) < 1e-3 and abs(p["colour"][2] - 0.7725) < 1e-3]
assert skin, spider["parts"]
assert sum(p["triangles"] for p in spider["parts"]) == spider["triangles"]
# glTF 2.0 binary: every mesh a named component with its base colour
assert engine["components"] >= 100 and engine["triangles"] > 100000, {k: engine[k] for k in ("components", "triangles")}
assert any(p["colour"] != [0.8, 0.8, 0.8] for p in engine["parts"])
# STL, ASCII and binary: the same triangles, and welding finds the shared corners
assert stl_ascii["triangles"] == stl_binary["triangles"] == 1368
assert stl_ascii["welded_vertices"] == stl_binary["welded_vertices"] < stl_ascii["vertices"]
# PLY
assert ply["triangles"] > 0 and ply["components"] == 1
# generated: onion's UV seams are duplicated vertices that welding merges; radii k/4
assert onion["components"] == 4 and onion["welded_vertices"] < onion["vertices"], onion
assert abs(onion["radius"] - 1.0) < 1e-3, onion
assert gearbox["components"] == 14, gearbox
print("import checks ok:", spider["components"], engine["components"], stl_ascii["welded_vertices"], onion["welded_vertices"])
PY
# Longest edges (the Illustration Buffer's id-search window relies on them being
# upper bounds): a 3-4-5 triangle in one group, a unit right triangle in another.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cat >"$work/edges.obj" <<'OBJ'
v 0 0 0
v 3 0 0
v 0 4 0
v 10 0 0
v 11 0 0
v 10 1 0
g big
f 1 2 3
g small
f 4 5 6
OBJ
python3 - "$(info "$work/edges.obj")" <<'PY' || fail "longest edges"
import json, sys
m = json.loads(sys.argv[1])
edges = {p["name"]: p["longest_edge"] for p in m["parts"]}
# rounded up (never below the true length), by at most a float step
assert 5.0 <= edges["big"] <= 5.0 * (1 + 1e-6), edges
assert 2 ** 0.5 <= edges["small"] <= 2 ** 0.5 * (1 + 1e-6), edges
assert m["longest_edge"] == edges["big"], m
print("longest edges ok:", edges)
PY
# glTF files that are wrong in known ways are refused with a one-line message.
expect_exit 2 "non-finite" -- "$oit" info --model $models/glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb
# (Assimp itself drops the faces of IndexOutOfRange.gltf that point outside; with all of them out, nothing is left)
expect_exit 2 "AllIndicesOutOfRange.*no triangles" -- "$oit" info --model $models/glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf
echo "model import ok"
