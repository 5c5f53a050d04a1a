#!/usr/bin/env bash
# antialiasing.sh OIT WORKDIR MODEL PART: --samples N (docs/algorithms.md, "Anti-aliasing").
# PART exact:
# - every exact algorithm (dp, ddp, ll, ib; kbuffer and hybrid at --layers 64, where
#   they keep every layer of this scene) at --samples 4 matches the reference at
#   --samples 4 within 2/255 on 99.9% of pixels (EGL; dp on OSMesa too): the
#   reference samples at the same positions;
# PART samples:
# - ll at 8 and 16 samples against the reference at 8 and 16;
# - 4 samples are closer (RMSE) than 1 to the reference rendered at 4x the width
#   and height and box-averaged (tests/aa_closer.py); the reference at 4 samples too;
# - the frame at 4 samples differs from the one at 1 (it did sample elsewhere);
# - --samples 3, 0, 32, abc: one-line message naming --samples, exit 2.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2/$4 model=$3 part=$4
rm -rf "$work"; mkdir -p "$work"
common=(--model "$model" --size 96x96 --shading flat --orbit 30,25)
if [ "$part" = exact ]; then
"$oit" render "${common[@]}" --algorithm reference --samples 4 --out "$work/reference_4.png" >/dev/null \
    || fail "reference --samples 4"
for variant in dp:egl ddp:egl ll:egl ib:egl kbuffer:egl:--layers:64 hybrid:egl:--layers:64 dp:osmesa; do
    IFS=: read -r algorithm backend extra <<<"$variant"
    args=(--algorithm "$algorithm" --backend "$backend")
    [ -n "$extra" ] && args+=(${extra//:/ })
    label=${algorithm}_${backend}
    "$oit" render "${common[@]}" "${args[@]}" --samples 4 --debug --out "$work/${label}_4.png" >/dev/null \
        || fail "$variant --samples 4"
    "$oit" compare "$work/reference_4.png" "$work/${label}_4.png" --tolerance 2 --max-mismatch 0.1 \
        >"$work/$label.txt" || { cat "$work/$label.txt"; fail "$variant at 4 samples differs from the reference at 4"; }
    echo "$variant --samples 4 vs reference: $(cat "$work/$label.txt")"
done
echo "antialiasing exact: ok"
exit 0
fi
[ "$part" = samples ] || fail "PART must be exact or samples, got '$part'"
for n in 8 16; do
    "$oit" render "${common[@]}" --algorithm reference --samples $n --out "$work/reference_$n.png" >/dev/null \
        || fail "reference --samples $n"
    "$oit" render "${common[@]}" --algorithm ll --samples $n --out "$work/ll_$n.png" >/dev/null || fail "ll --samples $n"
    "$oit" compare "$work/reference_$n.png" "$work/ll_$n.png" --tolerance 2 --max-mismatch 0.1 \
        || fail "ll at $n samples differs from the reference at $n"
done
# anti-aliasing changes the image (at 1 sample the edges are hard)
"$oit" render "${common[@]}" --algorithm ll --out "$work/ll_1.png" >/dev/null || fail "ll --samples 1"
"$oit" render "${common[@]}" --algorithm ll --samples 4 --out "$work/ll_4.png" >/dev/null || fail "ll --samples 4"
"$oit" render "${common[@]}" --algorithm reference --samples 4 --out "$work/reference_4.png" >/dev/null \
    || fail "reference --samples 4"
"$oit" compare "$work/ll_1.png" "$work/ll_4.png" --tolerance 2 --max-mismatch 1 >/dev/null
[ $? -eq 1 ] || fail "ll at 4 samples is (nearly) the image at 1 sample"
# closer to the box-filtered frame than 1 sample
"$oit" render --model "$model" --size 384x384 --shading flat --orbit 30,25 --algorithm reference \
    --out "$work/reference_big.png" >/dev/null || fail "reference at 384x384"
"$oit" render "${common[@]}" --algorithm reference --out "$work/reference_1.png" >/dev/null || fail "reference"
python3 "$(dirname "$0")/aa_closer.py" "$work/reference_big.png" 4 "$work/ll_1.png" "$work/ll_4.png" || exit 1
python3 "$(dirname "$0")/aa_closer.py" "$work/reference_big.png" 4 "$work/reference_1.png" "$work/reference_4.png" || exit 1
# the figures describe the whole frame: memory counts the accumulation target
# (memory_bytes equals the GL objects counted independently), stages have
# samples_accumulate, --json names the samples and their positions
json=$("$oit" render "${common[@]}" --algorithm ll --samples 4 --json) || fail "ll --samples 4 --json"
python3 -c '
import json, sys
d = json.loads(sys.argv[1])
assert d["samples"] == 4 and d["sample_positions"] == "d3d11-standard-4", d
assert d["memory_bytes"] == d["gl_allocated_bytes"], (d["memory_bytes"], d["gl_allocated_bytes"])
assert any(s["name"] == "samples_accumulate" for s in d["stages"]), d["stages"]
print("ll --samples 4 --json: memory_bytes", d["memory_bytes"], "= gl_allocated_bytes; samples_accumulate staged")
' "$json" || fail "ll --samples 4 --json figures"
for bad in 3 0 32 abc; do
    expect_exit 2 "^oit: error: --samples must be 1, 4, 8 or 16, got '$bad'$" -- "$oit" render "${common[@]}" --samples $bad
done
echo "antialiasing samples: ok"
