#!/usr/bin/env bash
# assembly_tree.sh OIT WORKDIR: a glTF's node hierarchy becomes the model's
# assembly tree (tests/assembly_gltf.py: nested nodes, an instanced mesh,
# duplicate sibling names): `oit info --json` gives each part's path; the
# import worker carries the tree (contained and in-process import agree);
# --hide and --component-alpha take a subassembly's path for every part under
# it (the same image as naming each part, tolerance 0) and a part's path for
# the part; an unknown path is one line and exit 2; formats without a tree
# keep none; a 5,000-deep node chain keeps at most 32 levels.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2
rm -rf "$work"; mkdir -p "$work"
here=$(cd "$(dirname "$0")" && pwd)
model=$work/gearbox.gltf
python3 "$here/assembly_gltf.py" "$model" >"$work/expected.json" || fail "assembly_gltf.py"

# --- names and paths, and the same through the import worker and in process ---
"$oit" info --model "$model" --json >"$work/contained.json" || fail "info (contained import)"
OIT_IMPORT=in-process "$oit" info --model "$model" --json >"$work/in_process.json" || fail "info (in process)"
cmp -s "$work/contained.json" "$work/in_process.json" || fail "info --json differs between contained and in-process import"
python3 - "$work/contained.json" "$work/expected.json" <<'PY' || fail "paths"
import json, sys
got = [(p["name"], p["path"]) for p in json.load(open(sys.argv[1]))["parts"]]
want = [tuple(e) for e in json.load(open(sys.argv[2]))]
assert got == want, "\n".join("%-16s %-50s want %s" % (g + (w,)) for g, w in zip(got, want)) + "\n%d vs %d" % (len(got), len(want))
print("ok: %d parts with their paths (contained and in-process import agree)" % len(got))
PY

# --- a subassembly's path selects every part under it; a part's path the part ---
render() { # OUT flags...
    local out=$1; shift
    "$oit" render --model "$model" --algorithm reference --size 96x96 --shading flat --out "$work/$out.png" "$@" \
        >/dev/null || fail "render $out: $*"
}
same() { "$oit" compare "$work/$1.png" "$work/$2.png" --tolerance 0 --max-mismatch 0 >/dev/null || fail "$1 and $2 differ"; }
differ() { "$oit" compare "$work/$1.png" "$work/$2.png" --tolerance 0 --max-mismatch 0 >/dev/null && fail "$1 and $2 are the same"; true; }
render all
render hide_input_path --hide gearbox/input_shaft
render hide_input_names --hide shaft --hide bearing_1 --hide bearing_2
render hide_input_indices --hide 1 --hide 2 --hide 3
same hide_input_path hide_input_names
same hide_input_path hide_input_indices
differ hide_input_path all
render hide_stage_path --hide gearbox/output_shaft/stage#2
render hide_stage_name --hide 'pinion_mesh#2'
same hide_stage_path hide_stage_name
differ hide_stage_path all
render fade_output_path --component-alpha gearbox/output_shaft=0.2 --component-alpha gearbox/output_shaft/cover=0.9
render fade_output_names --component-alpha 'shaft#2=0.2' --component-alpha pinion_mesh=0.2 \
    --component-alpha 'pinion_mesh#2=0.2' --component-alpha bolt=0.2 --component-alpha cover=0.9
same fade_output_path fade_output_names
differ fade_output_path all
render hide_part_path --hide gearbox/input_shaft/bearing_1
render hide_part_name --hide bearing_1
same hide_part_path hide_part_name
render hide_all --hide gearbox
render hide_each --hide 0 --hide 1 --hide 2 --hide 3 --hide 4 --hide 5 --hide 6 --hide 7 --hide 8
same hide_all hide_each
echo "ok: subassembly, part and top paths select what naming each part selects"

# --- unknown paths: one line, exit 2; a path must follow the tree whole ---
r=("$oit" render --model "$model" --size 32x32 --out "$work/x.png")
expect_exit 2 "no component 'gearbox/nosuch'.*'housing'.*assembly path such as 'gearbox/housing'" -- "${r[@]}" --hide gearbox/nosuch
expect_exit 2 "no component 'input_shaft'" -- "${r[@]}" --hide input_shaft
expect_exit 2 "no component 'gearbox/input'" -- "${r[@]}" --component-alpha gearbox/input=0.5
expect_exit 2 "no component 'gearbox/input_shaft/'" -- "${r[@]}" --hide gearbox/input_shaft/
expect_exit 2 "no component 'gearbox/output_shaft/stage/pinion/pinion_mesh#2'" -- "${r[@]}" --hide gearbox/output_shaft/stage/pinion/pinion_mesh#2

# --- formats without a tree keep none; a deep chain keeps at most 32 levels ---
printf 'solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n' >"$work/flat.stl"
python3 "$here/deep_gltf.py" 5000 "$work/deep.gltf"
"$oit" info --model "$work/flat.stl" --json >"$work/flat.json" || fail "info flat.stl"
"$oit" info --model "$work/deep.gltf" --json >"$work/deep.json" || fail "info deep.gltf"
python3 - "$work/flat.json" "$work/deep.json" <<'PY' || fail "flat and deep trees"
import json, sys
flat, deep = (json.load(open(a)) for a in sys.argv[1:])
assert all(p["path"] == p["name"] for p in flat["parts"]), flat["parts"]
paths = [p["path"] for p in deep["parts"]]
levels = ["level%d" % k for k in range(32)]
# the root "near" holds a mesh: the scene, not a node; the chain below it is
assert paths == ["near", "/".join(levels) + "/far"], paths
print("ok: STL without a tree; a 5000-deep chain cut to 32 levels:", len(paths[1].split("/")) - 1, "nodes")
PY
