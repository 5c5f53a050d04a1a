#!/usr/bin/env bash
# bench_variants.sh OIT WORKDIR SCENES: `oit bench --algorithms NAME:PARAMETER` and the
# error columns. Variants of the algorithms that read layers, moments or their own samples (found in
# `oit algorithms --json`, whatever the registry holds) run with the parameter and give
# the same error figures as `oit render --layers K / --moments M --error-vs-reference`;
# a parameter an algorithm does not read, or a bad one, is one line and exit 2; every
# row's error_* columns equal `oit render --error-vs-reference` on the same scene,
# camera and size.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"

# refusals: parameters of algorithms that take none, bad parameters
expect_exit 2 "--algorithms: 'll:4': ll takes no layers" -- "$oit" bench --model "$scenes/onion.obj" --algorithms ll:4
expect_exit 2 "'ll:power6': ll takes no moments" -- "$oit" bench --model "$scenes/onion.obj" --algorithms blend,ll:power6
expect_exit 2 "'ll-array:8': ll-array takes no layers" -- "$oit" bench --model "$scenes/onion.obj" --algorithms ll-array:8
expect_exit 2 "'dp:x': dp takes no parameter" -- "$oit" bench --model "$scenes/onion.obj" --algorithms dp:x
expect_exit 2 "'wavelet:4': the wavelet rank must be a whole number from 1 to 3" -- "$oit" bench --model "$scenes/onion.obj" --algorithms wavelet:4
expect_exit 2 "'wavelet:power6': wavelet takes a rank R, got 'power6'" -- "$oit" bench --model "$scenes/onion.obj" --algorithms wavelet:power6
expect_exit 2 "'dp:': no parameter after the colon" -- "$oit" bench --model "$scenes/onion.obj" --algorithms dp:
expect_exit 2 "unknown algorithm 'nope'" -- "$oit" bench --model "$scenes/onion.obj" --algorithms nope:4

# the algorithms that read layers / moments, from the registry
"$oit" algorithms --json >"$work/algorithms.json" || fail "oit algorithms --json"
read -r layered moment_user < <(python3 - "$work/algorithms.json" <<'PY'
import json, sys
listed = json.load(open(sys.argv[1]))
assert all("uses_layers" in a and "uses_moments" in a for a in listed), listed
layers = [a["name"] for a in listed if a["uses_layers"]]
moments = [a["name"] for a in listed if a["uses_moments"]]
assert "ll" not in layers + moments and "reference" not in layers + moments, (layers, moments)
print(layers[0] if layers else "-", moments[0] if moments else "-")
PY
)
# an algorithm that reads --samples as its own (stochastic): NAME:N is its samples
sampler=$(python3 -c 'import json, sys; print(next((a["name"] for a in json.load(open(sys.argv[1])) if "--samples" in a["options"]), "-"))' "$work/algorithms.json")
variants=ll,blend,wboit
if [ "$layered" != - ]; then
    variants+=",$layered:1,$layered:3"
    expect_exit 2 "'$layered:0': layers must be a whole number from 1 to 64" -- \
        "$oit" bench --model "$scenes/onion.obj" --algorithms "$layered:0"
    expect_exit 2 "'$layered:65': layers must be" -- "$oit" bench --model "$scenes/onion.obj" --algorithms "$layered:65"
    if [ "$moment_user" != "$layered" ]; then
        expect_exit 2 "'$layered:power6': $layered takes layers K, got 'power6'" -- \
            "$oit" bench --model "$scenes/onion.obj" --algorithms "$layered:power6"
    fi
else
    echo "no algorithm reads layers yet: NAME:K is checked by its refusals only"
fi
if [ "$moment_user" != - ]; then
    variants+=",$moment_user:power6,$moment_user:trig3"
    if [ "$moment_user" != "$layered" ]; then
        expect_exit 2 "'$moment_user:4': $moment_user takes moments power4, power6 or trig3, got '4'" -- \
            "$oit" bench --model "$scenes/onion.obj" --algorithms "$moment_user:4"
    fi
    expect_exit 2 "'$moment_user:power5'" -- "$oit" bench --model "$scenes/onion.obj" --algorithms "$moment_user:power5"
else
    echo "no algorithm reads moments yet: NAME:MOMENTS is checked by its refusals only"
fi

if [ "$sampler" != - ]; then
    variants+=",$sampler:4,$sampler:16"
    expect_exit 2 "'$sampler:5': samples must be 1, 4, 8 or 16" -- "$oit" bench --model "$scenes/onion.obj" --algorithms "$sampler:5"
    expect_exit 2 "'$sampler:power6': $sampler takes samples 1, 4, 8 or 16, got 'power6'" -- \
        "$oit" bench --model "$scenes/onion.obj" --algorithms "$sampler:power6"
fi

# error columns: every row against oit render --error-vs-reference (same view, same size)
printf 'gear %s/gearbox.obj --orbit 30,20 --alpha 0.4\n' "$scenes" >"$work/scenes.txt"
"$oit" bench --scene-list "$work/scenes.txt" --algorithms "$variants" --sizes 64,48x40 --frames 2 --warmup 0 \
    --reference-max-pixels 4096 --quiet --csv "$work/bench.csv" --json "$work/bench.json" \
    || fail "bench with variants $variants"
for size in 64x64 48x40; do
    IFS=, read -ra names <<<"$variants"
    for label in "${names[@]}"; do
        name=${label%%:*} parameter=${label#*:} flags=()
        if [ "$label" != "$name" ]; then
            case $parameter in
            [0-9]*) if [ "$name" = "$sampler" ]; then flags=(--samples "$parameter"); else flags=(--layers "$parameter"); fi ;;
            *) flags=(--moments "$parameter") ;;
            esac
        fi
        "$oit" render --model "$scenes/gearbox.obj" --orbit 30,20 --alpha 0.4 --algorithm "$name" "${flags[@]}" \
            --size "$size" --frames 2 --error-vs-reference --json >"$work/render_${label}_$size.json" \
            || fail "oit render $label $size"
    done
done
python3 - "$work" "$variants" <<'PY' || fail "bench error columns differ from oit render --error-vs-reference"
import csv, json, os, sys
work, variants = sys.argv[1], sys.argv[2].split(",")
rows = list(csv.DictReader(open(os.path.join(work, "bench.csv"))))
data = json.load(open(os.path.join(work, "bench.json")))
header = list(rows[0])
expected_tail = ["ref_max_diff", "ref_mean_diff", "ref_over_tolerance_percent", "error_rmse", "error_psnr",
                 "error_ssim", "error_max", "error_share_over_2", "error_flip", "flicker", "flicker_max",
                 "orbit_rmse_mean", "stages", "list_histogram", "scene_histogram", "error"]
assert header[-len(expected_tail):] == expected_tail, header
assert len(rows) == 2 * len(variants) == len(data["results"]), (len(rows), len(data["results"]))
keys = {"rmse": "error_rmse", "psnr": "error_psnr", "ssim": "error_ssim", "max": "error_max",
        "share_over_2": "error_share_over_2", "flip": "error_flip"}
for row, result in zip(rows, data["results"]):
    label, size = row["algorithm"], f"{row['width']}x{row['height']}"
    assert result["algorithm"] == label and row["error"] == "", (row, result)
    render = json.load(open(os.path.join(work, f"render_{label}_{size}.json")))["error"]
    for short, key in keys.items():
        want = render[short]
        assert result[key] == want, (label, size, key, result[key], want)          # JSON: the same number
        text = row[key]
        assert (text == "" if want is None else float(text) == float(want)), (label, size, key, text, want)
    assert row["flicker"] == "" and "flicker" not in result, row
    assert row["ref_max_diff"] == str(result["reference"]["max_channel_diff"]) == str(render["max"]), row
    print(f"{label:14} {size}: rmse {render['rmse']:.4f} psnr {render['psnr']} ssim {render['ssim']:.5f} "
          f"max {render['max']} over 2 {render['share_over_2']:.3f}% flip {render['flip']:.5f}  = oit render")
# the parameter reaches the algorithm: its two settings give two images (a k-buffer of 1 layer
# and of 3 on a gearbox of 3+ layers at alpha 0.4; power and trigonometric moments)
pairs = [(a, b) for a, b in zip(variants, variants[1:]) if a.split(":")[0] == b.split(":")[0] and ":" in a]
for a, b in pairs:
    first = [r for r in data["results"] if r["algorithm"] == a]
    second = [r for r in data["results"] if r["algorithm"] == b]
    assert any(x["error_rmse"] != y["error_rmse"] for x, y in zip(first, second)), \
        f"{a} and {b} give the same error: the parameter does not reach the algorithm"
exact = {r["algorithm"]: r for r in data["results"] if r["width"] == 64}
assert exact["ll"]["error_max"] <= 2 and exact["blend"]["error_rmse"] > exact["ll"]["error_rmse"], exact
PY
# without a reference (--reference-max-pixels 0) the columns are empty and the keys absent
"$oit" bench --model "$scenes/onion.obj" --algorithms ll --sizes 32 --frames 1 --warmup 0 --reference-max-pixels 0 \
    --quiet --csv "$work/none.csv" --json "$work/none.json" || fail "bench without reference"
python3 - "$work/none.csv" "$work/none.json" <<'PY' || fail "error columns without a reference"
import csv, json, sys
row = list(csv.DictReader(open(sys.argv[1])))[0]
assert all(row[k] == "" for k in ("error_rmse", "error_psnr", "error_ssim", "error_max", "error_share_over_2",
                                  "error_flip")), row
assert not any(k.startswith("error_") for k in json.load(open(sys.argv[2]))["results"][0]), "error_* keys"
print("no reference: empty error columns")
PY
echo "bench variants ok"
