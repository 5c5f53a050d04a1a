#!/usr/bin/env bash
# coverage_rule.sh OIT WORKDIR: one coverage rule (issue "Exact anywhere and at
# any scale", part 3). 1024 sub-pixel triangles and slivers at many sub-pixel
# positions, with vertices on the snap's rounding ties and edges through pixel
# centres (tests/coverage_scene.py), positions exact in float: the reference
# and the GL must cover the same fragments. ll's and ib's "fragments" must
# equal the reference's, and ll, ib and dp must draw the reference's image
# exactly (alpha 1, one fragment per pixel), on both back ends.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2
rm -rf "$work"; mkdir -p "$work"
python3 "$(dirname "$0")/coverage_scene.py" "$work/subpixel.obj" || fail "coverage_scene.py"
# x / 65536 - 1: 1/1024-pixel integers to NDC of a 128x128 image, exactly
scale=1.52587890625e-05
view=(--model "$work/subpixel.obj" --size 128x128 --shading flat --alpha 1
      --modelview "$scale,0,0,-1,0,$scale,0,-1,0,0,1,0,0,0,0,1" --projection 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1)
fragments() { # JSON FILE: its "fragments"
    python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["fragments"])' "$1"
}
"$oit" render "${view[@]}" --algorithm reference --json --out "$work/reference.png" >"$work/reference.json" \
    || fail "reference"
want=$(fragments "$work/reference.json")
[ "$want" -gt 0 ] || fail "the reference covers no pixel"
for backend in egl osmesa; do
    for algorithm in ll ib dp; do
        "$oit" render "${view[@]}" --algorithm $algorithm --backend $backend --debug --json \
            --out "$work/${algorithm}_$backend.png" >"$work/${algorithm}_$backend.json" || fail "$algorithm $backend"
        if [ $algorithm != dp ]; then # dp counts no fragments
            got=$(fragments "$work/${algorithm}_$backend.json")
            [ "$got" -eq "$want" ] \
                || fail "$algorithm ($backend) covers $got fragments, the reference $want: different coverage rules"
        fi
        "$oit" compare "$work/reference.png" "$work/${algorithm}_$backend.png" --tolerance 0 \
            || fail "$algorithm ($backend) covers other pixels than the reference"
    done
done
echo "coverage: the reference and ll, ib, dp on both back ends cover the same $want fragments"
