#!/usr/bin/env bash
# ib_epsilon_bounds.sh OIT WORK SHADERS MODEL...: the epsilon search's two bounds
# change no link. ib/neighbours.comp queues a fragment for the epsilon fallback
# only where the candidate nearest its predicted depth is within --epsilon-max
# of it (eps >= eps_z), and the mutual check stops at the fragment's own epsilon
# from its candidate; both are meant to skip only work whose answer is "none" or
# "not mutual". Here a copy of the shaders without them (every miss queued, the
# mutual check over the whole run, as before the bounds) must give the same
# images and neighbour figures, at tolerance 0, for welded (whose fallback the
# first bound prunes) and epsilon (the second), on models whose fallback links
# something.
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 shaders=$3
shift 3
rm -rf "$work"; mkdir -p "$work"
unbounded=$work/unbounded_shaders
cp -R "$shaders" "$unbounded"
replace_once "$unbounded/ib/neighbours.comp" \
    "nearest_gap / ib_radius_eye <= ib_epsilon_max + IB_EPSILON_MARGIN;" "other_length[d] > 0u; // unbounded"
replace_once "$unbounded/ib/neighbour_search.glsl" \
    "epsilon(partner, f_eps_z, f) + IB_EPSILON_MARGIN, back_eps);" "1e30, back_eps); // unbounded"

for model in "$@"; do
    name=$(basename "${model%.*}")
    for search in welded epsilon; do
        for side in bounded unbounded; do
            dir=$shaders
            [ $side = unbounded ] && dir=$unbounded
            # the neighbour view (each fragment's link count) and the curvature,
            # which reads the links' depths, at alpha 0.5 so every layer counts
            OIT_SHADER_DIR=$dir ib_render "$work/${name}_${search}_view_$side.png" --model "$model" \
                --orbit 30,20 --neighbours $search --view neighbours
            OIT_SHADER_DIR=$dir ib_render "$work/${name}_${search}_curv_$side.png" --model "$model" \
                --orbit 30,20 --neighbours $search --modulation curvature
        done
        for kind in view curv; do
            "$oit" compare "$work/${name}_${search}_${kind}_bounded.png" \
                "$work/${name}_${search}_${kind}_unbounded.png" --tolerance 0 \
                || fail "$name $search $kind: the bounded search changed the image"
        done
        ib_py '
import json, sys
work, name, search = sys.argv[1:4]
figures = ("fragments", "neighbours_four_share", "neighbours_symmetric_share",
           "neighbours_same_component_share")
a, b = (json.load(open(f"{work}/{name}_{search}_view_{side}.json")) for side in ("bounded", "unbounded"))
for f in figures:
    assert a[f] == b[f], f"{name} {search}: {f} is {a[f]} bounded, {b[f]} unbounded"
print(name, search, "same images and figures:", {f: a[f] for f in figures})
' "$work" "$name" "$search"
    done
done
echo "ok"
