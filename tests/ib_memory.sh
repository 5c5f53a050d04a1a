#!/usr/bin/env bash
# ib_memory.sh OIT WORK SCENES: the memory contract and bad modulation flags.
# A small first pool must grow (the frame is rendered again) and give the same
# image, and the memory must show it: the figures are checked against the GL
# objects' bytes counted independently (gl_allocated_bytes), the bytes per
# fragment against the difference between two pool capacities, and the growth
# against what the small pool held. A budget below the frame holds one band
# of rows at a time (the same image); one too small for a row fails with a
# message, nothing is dropped silently; bad flag values are usage errors
# (exit 2, one line).
source "$(dirname "$0")/lib.sh"
source "$(dirname "$0")/ib_lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/onion.obj
ib_render "$work/default.png" --model "$model" --modulation fields
ib_render "$work/grown.png" --model "$model" --modulation fields --fragment-pool 100
"$oit" compare "$work/grown.png" "$work/default.png" || fail "a grown pool must give the same image"
fragments=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["fragments"])' "$work/default.json") \
    || fail "no fragment count"
# two pools that hold the frame, 4000 fragments apart
ib_render "$work/pool_a.png" --model "$model" --modulation fields --fragment-pool $((fragments + 500))
ib_render "$work/pool_b.png" --model "$model" --modulation fields --fragment-pool $((fragments + 4500))
ib_py '
import json, sys
work = sys.argv[1]
default, grown, a, b = (json.load(open(f"{work}/{n}.json")) for n in ("default", "grown", "pool_a", "pool_b"))
print({k: grown[k] for k in ("fragments", "overflow_retries", "memory_bytes", "gl_allocated_bytes",
                             "bytes_per_fragment", "bytes_per_pixel")})
assert default["overflow_retries"] == 0 and grown["overflow_retries"] == 1, (default, grown)
assert a["overflow_retries"] == 0 and b["overflow_retries"] == 0, (a, b)
fragments = default["fragments"]
assert grown["fragments"] == fragments == a["fragments"] == b["fragments"]
# memory_bytes is what GL holds for ib (counted without its own accounting)
for d in (default, grown, a, b):
    assert d["memory_bytes"] == d["gl_allocated_bytes"], d
# the bytes one more pool fragment costs, from two capacities
per_fragment = (b["gl_allocated_bytes"] - a["gl_allocated_bytes"]) / 4000
print("GL bytes per pool fragment:", per_fragment)
assert all(d["bytes_per_fragment"] == per_fragment for d in (default, grown, a, b)), per_fragment
assert per_fragment <= 64  # the layout: 40 bytes (the source needed 208)
# the pool of 100 grew to hold every fragment, and the memory shows it
rest = a["gl_allocated_bytes"] - (fragments + 500) * per_fragment
small_pool = rest + 100 * per_fragment
assert grown["memory_bytes"] - small_pool >= (fragments - 100) * per_fragment, (grown, small_pool)
' "$work"
# a budget below the frame bounds the pool: the frame is drawn in bands of rows, the same
# image, and the pool is what the budget holds (the rest as in the whole frame, plus the
# long runs' histogram of a banded frame)
ib_render "$work/whole.png" --model "$model"
ib_render "$work/budget.png" --model "$model" --max-memory 1
cmp "$work/whole.png" "$work/budget.png" || fail "a frame drawn in bands within the budget differs"
ib_py '
import json, sys
whole, budget = (json.load(open(f"{sys.argv[1]}/{n}.json")) for n in ("whole", "budget"))
assert whole["bands"] == 1 and whole["overflow_retries"] == 0 and budget["bands"] > 1, (whole, budget)
assert budget["memory_bytes"] == budget["gl_allocated_bytes"], budget
pool_whole = 40 * 4 * 128 * 128  # four fragments a pixel at first
pool_budget = budget["memory_bytes"] - (whole["memory_bytes"] - pool_whole) - 4 * 65536
assert pool_budget == 40 * (2**20 // 40), pool_budget
' "$work"
# a budget too small for a row and the rows either side that the fields read
expect_exit 3 "^oit: error: ib: row [0-9]+ of the image, with the 103 rows either side that its neighbour passes read, needs [0-9]+ fragments, more than the --max-memory budget of 1.0 MB holds \(26214\)$" -- \
    "$oit" render --model "$model" --algorithm ib --size 128x128 --max-memory 1 --modulation fields \
    --diffusion-iterations 100 --out "$work/x.png"
for bad in "--modulation sideways" "--neighbours nearest" "--curvature-neighbours 6" \
    "--focus-region -1" "--distance skip:0" "--fields alpha,delta" "--halo-colour 1,2,3" \
    "--lambda-beta 0" "--diffusion-iterations -2" "--view fields:x" "--epsilon-max nan"; do
    expect_exit 2 "${bad%% *}" -- "$oit" render --model "$model" --algorithm ib --size 16x16 $bad \
        --out "$work/x.png"
done
echo ok
