#!/usr/bin/env bash
# precision.sh OIT WORKDIR: depth precision over long ranges (issue "Exact means
# exact", part 2). Plane pairs 1e-3 apart about 800 units away
# (tests/precision_scene.py), seen with the near plane at 0.01 and the far
# plane at 1000 (near/far 1e-5), where window depths of a pair are the same
# float. The image must not depend on the near plane: the reference with
# near 0.01 equals the reference with near 100 (where window depth would
# still separate the pairs), and every exact algorithm matches it (2/255 on
# 99.9% of the pixels), on both back ends.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2
rm -rf "$work"; mkdir -p "$work"
python3 "$(dirname "$0")/precision_scene.py" "$work/pairs.obj"
projection() { # NEAR FAR: a 40-degree perspective, row by row
    python3 -c 'import sys; n, f = map(float, sys.argv[1:]); t = 2.7474774194546216
print(",".join(repr(v) for v in (t,0,0,0, 0,t,0,0, 0,0,(f+n)/(n-f),2*f*n/(n-f), 0,0,-1,0)))' "$1" "$2"
}
view=(--model "$work/pairs.obj" --size 96x96 --shading flat --modelview 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1)
deep=$(projection 0.01 1000)
"$oit" render "${view[@]}" --projection "$(projection 100 1000)" --algorithm reference --out "$work/reference_near100.png" \
    >/dev/null || fail "reference, near 100"
"$oit" render "${view[@]}" --projection "$deep" --algorithm reference --out "$work/reference.png" >/dev/null \
    || fail "reference, near 0.01"
"$oit" compare "$work/reference_near100.png" "$work/reference.png" --tolerance 2 --max-mismatch 0.1 \
    || fail "the reference must not depend on the near plane (pairs 1e-3 apart at 800 units)"
for backend in egl osmesa; do
    for variant in dp ddp ll ll:--sort:array ib; do
        IFS=: read -r -a args <<<"$variant"
        label=$(IFS=_; echo "${args[*]}" | tr -d '-')
        "$oit" render "${view[@]}" --projection "$deep" --algorithm "${args[@]}" --backend $backend --debug \
            --out "$work/${label}_$backend.png" >/dev/null || fail "$variant $backend"
        "$oit" compare "$work/reference.png" "$work/${label}_$backend.png" --tolerance 2 --max-mismatch 0.1 \
            || fail "$variant ($backend): plane pairs 1e-3 apart at 800 units with near 0.01"
    done
done
echo "depth precision: all exact algorithms separate the pairs"

# A face exactly on the far plane: its canonical depth is the largest the
# clamp allows; dp's depth test against the cleared 1.0 must still let it
# through (it lost the face while the clamp went up to 1.0 itself).
cat >"$work/far.obj" <<'OBJ'
v -1 -1 -2
v 1 -1 -2
v 1 1 -2
v -1 1 -2
v -0.5 -0.5 -1.5
v 0.5 -0.5 -1.5
v 0 0.5 -1.5
f 1 2 3
f 1 3 4
f 5 6 7
OBJ
far=(--model "$work/far.obj" --size 32x32 --modelview 1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1
     --projection 3,0,0,0,0,3,0,0,0,0,-3,-4,0,0,-1,0) # near 1, far 2
"$oit" render "${far[@]}" --algorithm reference --out "$work/far_reference.png" >/dev/null || fail "far: reference"
for variant in dp ddp ll ib; do
    "$oit" render "${far[@]}" --algorithm $variant --out "$work/far_$variant.png" >/dev/null || fail "far: $variant"
    "$oit" compare "$work/far_reference.png" "$work/far_$variant.png" --tolerance 2 \
        || fail "$variant: a face on the far plane is lost"
done
echo "depth precision: a face on the far plane is drawn by every exact algorithm"
