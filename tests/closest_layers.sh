#!/usr/bin/env bash
# closest_layers.sh OIT WORK SCENES CONFIG_TEST: kbuffer and hybrid beyond their
# images (tests/alg_kbuffer.cmake): the statistics against ll's, k = 1, the memory
# budget, refused modulations and views, bad --layers, and the core's own check of
# config.layers (CONFIG_TEST, tests/closest_layers_config.c).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 config_test=$4
rm -rf "$work"; mkdir -p "$work"
model=$scenes/menger.obj # longest list 20 at 128x128: a tail at k = 8, none at k = 64

"$oit" render --model "$model" --algorithm ll --size 128x128 --json >"$work/ll.json" || fail "ll render"
for algorithm in kbuffer hybrid; do
    for k in 1 8 64; do
        "$oit" render --model "$model" --algorithm $algorithm --layers $k --size 128x128 --json --debug \
            --out "$work/${algorithm}_$k.png" >"$work/${algorithm}_$k.json" \
            || fail "$algorithm --layers $k render"
    done
    python3 - "$work" "$algorithm" "$(cd "$(dirname "$0")/.." && pwd)/shaders/common/oit_shared.h" <<'PY' || fail "$algorithm statistics"
import json, re, sys
work, algorithm = sys.argv[1:3]
# the frame's parameter block every GPU algorithm holds beside its targets
FRAME_BLOCK = int(re.search(r"#define OIT_FRAME_BLOCK_BYTES (\d+)", open(sys.argv[3]).read()).group(1))
ll = json.load(open(f"{work}/ll.json"))
for k in (1, 8, 64):
    d = json.load(open(f"{work}/{algorithm}_{k}.json"))
    # every fragment with alpha > 0 is counted once, in the core or in the tail, and
    # the list lengths (core + tail per pixel) are ll's
    for key in ("fragments", "max_list", "mean_list"):
        assert d[key] == ll[key], (k, key, d[key], ll[key])
    assert d["list_histogram"] == ll["list_histogram"], (k, "histogram")
    assert [s["name"] for s in d["stages"]] == ["clear", "select", "store", "compose"], d["stages"]
    # slots of 16 bytes per layer, a tail count, the tail targets and the output per pixel
    tail = 16 if algorithm == "kbuffer" else 20
    assert d["bytes_per_pixel"] == 16 * k + 4 + tail + 4, (k, d["bytes_per_pixel"])
    assert d["memory_bytes"] == 128 * 128 * d["bytes_per_pixel"] + 69 * 4 + FRAME_BLOCK, (k, d["memory_bytes"])
    print(f"{algorithm} k={k}: fragments {d['fragments']}, max_list {d['max_list']}, "
          f"{d['bytes_per_pixel']} bytes per pixel, memory {d['memory_bytes']}: ok")
PY
    # k = 1 keeps the nearest layer and puts everything else in the tail: an image, and
    # not the k = 64 one (menger has up to 20 layers)
    "$oit" compare "$work/${algorithm}_1.png" "$work/${algorithm}_64.png" --tolerance 2 >/dev/null
    [ $? -eq 1 ] || fail "$algorithm: k = 1 gives the same image as k = 64"
    # ... and the k = 64 image matches ll's (both exact here)
    "$oit" render --model "$model" --algorithm ll --size 128x128 --out "$work/ll.png" >/dev/null || fail "ll"
    "$oit" compare "$work/${algorithm}_64.png" "$work/ll.png" --tolerance 2 --max-mismatch 0 \
        || fail "$algorithm --layers 64 differs from ll"

    # the budget is checked before allocating: W x H x (16 k + ...) bytes, named
    expect_exit 3 "$algorithm: 512x512 with k = 64 layers needs [0-9]+ bytes .*over the --max-memory" -- \
        "$oit" render --model "$model" --algorithm $algorithm --layers 64 --size 512x512 --max-memory 16 \
        --out "$work/x.png"
    # what it cannot do is refused before any work
    expect_exit 2 "$algorithm: opacity modulation 'curvature' needs surface neighbours" -- \
        "$oit" render --model "$model" --algorithm $algorithm --modulation curvature --out "$work/x.png"
    expect_exit 2 "$algorithm: the distance modulation" -- \
        "$oit" render --model "$model" --algorithm $algorithm --modulation distance --out "$work/x.png"
    expect_exit 2 "$algorithm: buffer views .*heatmap" -- \
        "$oit" render --model "$model" --algorithm $algorithm --view heatmap --out "$work/x.png"
    for bad in 0 65 -1 x; do
        expect_exit 2 "--layers must be a whole number from 1 to 64" -- \
            "$oit" render --model "$model" --algorithm $algorithm --layers "$bad" --out "$work/x.png"
    done
done
# hybrid and kbuffer differ only in the tail: the same at k = 64, not at k = 1
"$oit" compare "$work/kbuffer_64.png" "$work/hybrid_64.png" --max-mismatch 0 \
    || fail "k = 64: the tails are empty, the images must be the same"
"$oit" compare "$work/kbuffer_1.png" "$work/hybrid_1.png" --tolerance 2 >/dev/null
[ $? -eq 1 ] || fail "k = 1: kbuffer's and hybrid's tails give the same image"

# the core refuses config.layers outside 1..64 by itself (the command line never passes them)
"$config_test" "$model" || fail "config.layers checks in the core"
echo "closest layers ok"
