#!/usr/bin/env bash
# many_parts.sh OIT WORKDIR TOLERANCE MAX_MISMATCH: per-part opacity reaches
# every part, however many (docs/modulation.md). A model of 1331 parts
# (tests/many_parts.py) is rendered with part 1300 hidden and part 1200 faded:
# the exact GPU algorithms must match the reference with the same flags
# (TOLERANCE / MAX_MISMATCH: the suite's exact bounds) and must differ from the
# reference without them, so a GPU that dropped the opacity of parts past 1024
# (the old uniform-array limit) fails. Hidden fragments are never stored; an
# index past the model is refused naming the flag and the valid range.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 tolerance=$3 mismatch=$4
rm -rf "$work"; mkdir -p "$work"
model=$work/many_parts.obj
python3 "$(dirname "$0")/many_parts.py" "$model" 1331 || fail "many_parts.py"
"$oit" info --model "$model" | grep -Eq '^components +1331$' || fail "the model does not have 1331 parts"

alphas=(--hide 1300 --component-alpha 1200=0.4)
render() { # OUT ALGORITHM [args...]
    local out=$1 algorithm=$2
    shift 2
    "$oit" render --model "$model" --algorithm "$algorithm" --size 128x128 --out "$out" --json "$@" \
        >"${out%.png}.json" || fail "render $algorithm $*"
}
fragments() { sed -n 's/.*"fragments": \([0-9-]*\).*/\1/p' "$1"; }
compare() { "$oit" compare "$1" "$2" --tolerance "$tolerance" --max-mismatch "$mismatch"; }

render "$work/reference.png" reference "${alphas[@]}"
render "$work/reference_plain.png" reference
# the alphas must change the reference image by far (else the checks below prove nothing)
compare "$work/reference.png" "$work/reference_plain.png"
[ $? -eq 1 ] || fail "hiding part 1300 and fading part 1200 does not change the reference image"
ref_fragments=$(fragments "$work/reference.json")
plain_fragments=$(fragments "$work/reference_plain.json")
[ "$ref_fragments" -lt "$plain_fragments" ] || fail "reference: hiding part 1300 stored no fewer fragments ($ref_fragments, $plain_fragments)"

for candidate in ll:egl ll:osmesa llarray:egl dp:egl ddp:egl ib:egl; do
    label=${candidate%%:*} backend=${candidate#*:}
    algorithm=$label extra=()
    [ "$label" = llarray ] && algorithm=ll extra=(--sort array)
    out=$work/${label}_$backend.png
    render "$out" "$algorithm" "${extra[@]}" --backend "$backend" --debug "${alphas[@]}"
    compare "$out" "$work/reference.png" || fail "$label ($backend): per-part opacity past part 1024 differs from the reference"
    compare "$out" "$work/reference_plain.png"
    [ $? -eq 1 ] || fail "$label ($backend): the image is that of the model without the part opacities"
    case $label in ll|llarray|ib)
        got=$(fragments "${out%.png}.json")
        # the same fragments as the reference, within edge rasterization (0.5%)
        diff=$(( got > ref_fragments ? got - ref_fragments : ref_fragments - got ))
        [ $(( diff * 200 )) -le "$ref_fragments" ] || fail "$label: $got fragments, reference $ref_fragments (hidden part 1300 stored?)"
        ;;
    esac
    echo "ok: $label ($backend) applies the opacity of parts 1200 and 1300"
done

# indices: any part of the model, and a clear refusal past it
expect_exit 0 "" -- "$oit" render --model "$model" --size 32x32 --out "$work/last.png" --component-alpha 1330=0.5
expect_exit 2 "component-alpha: no component '1331'.*index 0\.\.1330" -- \
    "$oit" render --model "$model" --size 32x32 --out "$work/past.png" --component-alpha 1331=0.5
expect_exit 2 "hide: no component '4000000000'.*index 0\.\.1330" -- \
    "$oit" render --model "$model" --size 32x32 --out "$work/past.png" --hide 4000000000
echo "ok: every part of a 1331-part model takes its opacity on the GPU"
