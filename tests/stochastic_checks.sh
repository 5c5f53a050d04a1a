#!/usr/bin/env bash
# stochastic_checks.sh OIT WORKDIR SCENES REFERENCE_DIR: stochastic beyond its image bounds.
#  - the noise falls as the samples grow: on gearbox (128x128, flat, alpha 0.5) the RMSE
#    against the reference falls from N = 4 to 8 to 16, for both mask modes;
#  - a fixed seed gives the same image, byte for byte; another seed a different one;
#  - at alpha 1 every fragment covers all samples: the front one hides the rest, exact;
#  - --samples not given is 8 samples; it leaves other algorithms' images as --samples 1;
#  - --json reports samples, seed and masks; bad values are refused in one line, exit 2.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 reference=$4
rm -rf "$work"; mkdir -p "$work"
g=(--model "$scenes/gearbox.obj" --size 128x128 --shading flat)
s=("$oit" render "${g[@]}" --algorithm stochastic)

rmse() { # the RMSE (0..255) of an image against gearbox's reference, from compare's PSNR
    "$oit" compare "$1" "$reference/gearbox_flat.png" --tolerance 255 | sed -n 's/.*PSNR \([0-9.]*\) dB.*/\1/p' |
        awk '{printf "%.4f", 255 * 10 ^ (-$1 / 20)}'
}
for masks in stratified independent; do
    last=1000
    for n in 4 8 16; do
        "${s[@]}" --samples $n --stochastic-masks $masks --out "$work/${masks}_$n.png" >/dev/null || fail "render $masks $n"
        e=$(rmse "$work/${masks}_$n.png")
        echo "$masks N=$n: rmse $e"
        awk -v a="$e" -v b="$last" 'BEGIN { exit !(a < b) }' || fail "$masks: rmse at N=$n ($e) is not below the last ($last)"
        last=$e
    done
done

"${s[@]}" --seed 5 --out "$work/seed5a.png" >/dev/null && "${s[@]}" --seed 5 --out "$work/seed5b.png" >/dev/null \
    || fail "render seed 5"
cmp -s "$work/seed5a.png" "$work/seed5b.png" || fail "seed 5 twice gives different images"
"${s[@]}" --seed 6 --out "$work/seed6.png" >/dev/null || fail "render seed 6"
cmp -s "$work/seed5a.png" "$work/seed6.png" && fail "seeds 5 and 6 give the same image"

"${s[@]}" --alpha 1 --error-vs-reference --out "$work/opaque.png" | grep -q "max [01], 0.000% of pixels over 2" \
    || fail "alpha 1 is not exact"

"${s[@]}" --out "$work/default.png" >/dev/null || fail "render default"
cmp -s "$work/default.png" "$work/stratified_8.png" || fail "--samples not given is not 8 stratified samples"
"$oit" render "${g[@]}" --algorithm wboit --out "$work/wboit_default.png" >/dev/null &&
    "$oit" render "${g[@]}" --algorithm wboit --samples 1 --out "$work/wboit_1.png" >/dev/null || fail "render wboit"
cmp -s "$work/wboit_default.png" "$work/wboit_1.png" || fail "wboit without --samples differs from --samples 1"

json=$("${s[@]}" --samples 16 --seed 9 --stochastic-masks independent --json --out "$work/j.png") || fail "json"
for want in '"samples": 16' '"seed": 9' '"stochastic_masks": "independent"' '"sample_positions": "centre"'; do
    grep -qF "$want" <<<"$json" || fail "--json lacks $want"
done

r=("${s[@]}" --out "$work/x.png")
expect_exit 2 "--seed must be a whole number from 0 to 4294967295" -- "${r[@]}" --seed -1
expect_exit 2 "--seed must be a whole number from 0 to 4294967295" -- "${r[@]}" --seed 4294967296
expect_exit 2 "--stochastic-masks must be stratified or independent" -- "${r[@]}" --stochastic-masks sobol
expect_exit 2 "--samples must be 1, 4, 8 or 16" -- "${r[@]}" --samples 2
expect_exit 2 "stochastic: the distance modulation needs the next fragment" -- "${r[@]}" --modulation distance
expect_exit 2 "stochastic: buffer views are ll's and ib's" -- "${r[@]}" --view heatmap
echo "stochastic_checks: ok"
