#!/usr/bin/env bash
# malformed_models.sh OIT DATA WORK: model files that crash, abort or hang the
# importer (Assimp) are contained: one line, exit 2, for `oit info` and
# `oit render`, the parser's failure named (crashed with its signal, timed out).
# DATA holds the regression inputs (tests/data/malformed; where each came from
# is in its README). The CPU limit is lowered so the spinning ones end in seconds.
source "$(dirname "$0")/lib.sh"
oit=$1 data=$2 work=$3
rm -rf "$work"; mkdir -p "$work"
export OIT_IMPORT_CPU_SECONDS=2
# knot multiplicities no 120 kB file could hold (made here from a KiCad model, tests/data/kicad)
sed -z "s/#34 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#35,#36),.UNSPECIFIED.,.F.,.F.,(2,\n2)/#34 = B_SPLINE_CURVE_WITH_KNOTS('',1,(#35,#36),.UNSPECIFIED.,.F.,.F.,(2000000000,\n2000000000)/" \
    "$data/../kicad/SOT-23.step" >"$work/huge_knots.step"
cmp -s "$data/../kicad/SOT-23.step" "$work/huge_knots.step" && fail "huge_knots.step: the edit did not apply"
for command in info render; do
    extra=()
    [ "$command" = render ] && extra=(--size 16x16 --out "$work/never.png")
    expect_exit 2 "ply_triangulate_abort.ply: the importer crashed \(signal 6, Aborted\)" -- \
        "$oit" "$command" --model "$data/ply_triangulate_abort.ply" "${extra[@]}"
    expect_exit 2 "ply_parser_spins.ply: the importer timed out" -- \
        "$oit" "$command" --model "$data/ply_parser_spins.ply" "${extra[@]}"
    expect_exit 2 "ply_truncated_header.ply: the importer timed out" -- \
        "$oit" "$command" --model "$data/ply_truncated_header.ply" "${extra[@]}"
    expect_exit 2 "ply_huge_count.ply: PLY header declares 4000000000 elements" -- \
        "$oit" "$command" --model "$data/ply_huge_count.ply" "${extra[@]}"
    # STEP and IGES (OpenCASCADE): cut short, corrupt, an entity numbered near 2^31,
    # B-spline knot multiplicities of 2e9 in a 120 kB file, parts in files that are missing
    expect_exit 2 "step_truncated.step: cannot import: not a readable STEP file" -- \
        "$oit" "$command" --model "$data/step_truncated.step" "${extra[@]}"
    expect_exit 2 "iges_garbage.igs: cannot import: OpenCASCADE read the IGES file but could not transfer" -- \
        "$oit" "$command" --model "$data/iges_garbage.igs" "${extra[@]}"
    expect_exit 2 "step_huge_entity_number.step: cannot import: OpenCASCADE read the STEP file but could not transfer" -- \
        "$oit" "$command" --model "$data/step_huge_entity_number.step" "${extra[@]}"
    # (OpenCASCADE gives up on the curve in 0.4 s; under AddressSanitizer the 2 s limit may come first)
    expect_exit 2 "huge_knots.step: (no triangles \(the STEP file holds no shapes|the importer timed out)" -- \
        "$oit" "$command" --model "$work/huge_knots.step" "${extra[@]}"
    expect_exit 2 "step_missing_part_files.step: cannot import: it refers to the file '[a-z]+\.stp', which cannot be read" -- \
        "$oit" "$command" --model "$data/step_missing_part_files.step" "${extra[@]}"
    # the worker's limits cover OpenCASCADE too: a tessellation far too fine for the CPU limit
    OIT_IMPORT_CPU_SECONDS=1 expect_exit 2 "SOT-23.step: the importer timed out \(more than 1 s of CPU time" -- \
        "$oit" "$command" --model "$data/../kicad/SOT-23.step" --tessellation 0.0000001 "${extra[@]}"
done
[ ! -e "$work/never.png" ] || fail "an image was written for a model that did not load"
# the same files in the calling process: the importer really does crash and
# hang there (else these inputs prove nothing); bounded by timeout
OIT_IMPORT=in-process timeout 10 "$oit" info --model "$data/ply_triangulate_abort.ply" >/dev/null 2>"$work/abort.err"
status=$?
# (the program's crash handler turns the abort into one line and exit 3)
[ "$status" -ge 128 ] || { [ "$status" -eq 3 ] && grep -q "crashed (signal 6, Aborted)" "$work/abort.err"; } \
    || fail "in-process import of ply_triangulate_abort.ply exited $status, not by a signal"
OIT_IMPORT=in-process timeout 5 "$oit" info --model "$data/ply_parser_spins.ply" >/dev/null 2>&1
status=$?
[ "$status" -eq 124 ] || fail "in-process import of ply_parser_spins.ply ended ($status) instead of spinning"

# files a model refers to must be regular files too: a glTF whose .bin and an OBJ whose MTL
# is a FIFO are refused at once, naming the file (the worker waited out the 20 s wall limit)
mkdir -p "$work/refers"
printf '{"asset": {"version": "2.0"}, "buffers": [{"uri": "data.bin", "byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}\n' \
    >"$work/refers/triangle.gltf"
mkfifo "$work/refers/data.bin" "$work/refers/parts.mtl"
printf 'mtllib parts.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$work/refers/triangle.obj"
expect_exit 2 "triangle.gltf: cannot import: the file it refers to, data.bin: not a regular file \(a FIFO\)" -- \
    timeout 10 "$oit" info --model "$work/refers/triangle.gltf"
expect_exit 2 "triangle.obj: cannot import: material library parts.mtl: not a regular file \(a FIFO\)" -- \
    timeout 10 "$oit" info --model "$work/refers/triangle.obj"

# the worker dies with its parent: killed (SIGKILL, no handler runs) while the worker spins
# on a file, the worker is gone within 3 s, not at its CPU limit (30 s here)
OIT_IMPORT_CPU_SECONDS=30 "$oit" info --model "$data/ply_parser_spins.ply" >/dev/null 2>&1 &
parent=$!
worker=
for _ in $(seq 200); do
    worker=$(ps -o pid= --ppid "$parent" | tr -d ' ')
    [ -n "$worker" ] && break
    sleep 0.05
done
[ -n "$worker" ] || fail "no import worker appeared"
kill -KILL "$parent"
wait "$parent" 2>/dev/null
for _ in $(seq 60); do
    kill -0 "$worker" 2>/dev/null || break
    sleep 0.05
done
if kill -0 "$worker" 2>/dev/null; then
    kill -KILL "$worker"
    fail "the import worker $worker outlived its killed parent"
fi
echo "ok: the import worker ended with its parent"
echo "malformed models: ok"
