#!/usr/bin/env bash
# ib_memory.sh OIT WORK SCENES: the memory contract and bad modulation flags.
# A small first pool must grow (the frame is rendered again) and give the same
# image; a budget too small for the frame fails with a message, nothing is
# dropped silently; bad flag values are usage errors (exit 2, one line).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
ib_render "$work/default.png" --model "$model" --modulation fields
ib_render "$work/grown.png" --model "$model" --modulation fields --fragment-pool 100
"$oit" compare "$work/grown.png" "$work/default.png" || fail "a grown pool must give the same image"
ib_py '
import json, sys
work = sys.argv[1]
default, grown = (json.load(open(f"{work}/{n}.json")) for n in ("default", "grown"))
print({k: grown[k] for k in ("fragments", "overflow_retries", "memory_bytes", "bytes_per_fragment", "bytes_per_pixel")})
assert default["overflow_retries"] == 0 and grown["overflow_retries"] == 1, (default, grown)
assert grown["fragments"] == default["fragments"]
assert grown["bytes_per_fragment"] <= 64 and grown["bytes_per_pixel"] <= 12
# memory: every per-fragment buffer for the pool, every per-pixel one for the image
pool_min = grown["fragments"] * grown["bytes_per_fragment"] + 128 * 128 * grown["bytes_per_pixel"]
assert grown["memory_bytes"] >= pool_min, grown
' "$work"
expect_exit 3 "budget|max-memory" -- "$oit" render --model "$model" --algorithm ib --size 512x512 \
    --max-memory 1 --out "$work/x.png"
for bad in "--modulation sideways" "--neighbours nearest" "--curvature-neighbours 6" \
    "--focus-region -1" "--distance skip:0" "--fields alpha,delta" "--halo-colour 1,2,3" \
    "--lambda-beta 0" "--diffusion-iterations -2" "--view fields:x" "--epsilon-max nan"; do
    expect_exit 2 "${bad%% *}" -- "$oit" render --model "$model" --algorithm ib --size 16x16 $bad \
        --out "$work/x.png"
done
echo ok
