#!/usr/bin/env bash
# many_parts.sh OIT WORKDIR TOLERANCE MAX_MISMATCH [PARTS [CANDIDATES]]: per-part
# opacity reaches every part, however many (docs/modulation.md). A model of PARTS
# parts (default 1331; tests/many_parts.py) is rendered with part PARTS-31 (1300)
# hidden and part PARTS-131 (1200) faded:
# the exact GPU algorithms must match the reference with the same flags
# (TOLERANCE / MAX_MISMATCH: the suite's exact bounds) and must differ from the
# reference without them, so a GPU that dropped the opacity of parts past 1024
# (the old uniform-array limit) fails. Hidden fragments are never stored; an
# index past the model is refused naming the flag and the valid range.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 tolerance=$3 mismatch=$4 parts=${5:-1331}
candidates=${6:-"ll:egl ll:osmesa llarray:egl dp:egl ddp:egl ib:egl"}
hidden=$((parts - 31)) faded=$((parts - 131)) last=$((parts - 1))
rm -rf "$work"; mkdir -p "$work"
model=$work/many_parts.obj
python3 "$(dirname "$0")/many_parts.py" "$model" "$parts" || fail "many_parts.py"
"$oit" info --model "$model" | grep -Eq "^components +$parts\$" || fail "the model does not have $parts parts"

alphas=(--hide "$hidden" --component-alpha "$faded=0.4")
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
[ $? -eq 1 ] || fail "hiding part $hidden and fading part $faded does not change the reference image"
ref_fragments=$(fragments "$work/reference.json")
plain_fragments=$(fragments "$work/reference_plain.json")
[ "$ref_fragments" -lt "$plain_fragments" ] || fail "reference: hiding part $hidden stored no fewer fragments ($ref_fragments, $plain_fragments)"

for candidate in $candidates; do
    label=${candidate%%:*} backend=${candidate#*:}
    algorithm=$label extra=()
    [ "$label" = llarray ] && algorithm=ll extra=(--sort array)
    out=$work/${label}_$backend.png
    render "$out" "$algorithm" "${extra[@]}" --backend "$backend" --debug "${alphas[@]}"
    compare "$out" "$work/reference.png" || fail "$label ($backend): per-part opacity of parts $faded and $hidden differs from the reference"
    compare "$out" "$work/reference_plain.png"
    [ $? -eq 1 ] || fail "$label ($backend): the image is that of the model without the part opacities"
    case $label in ll|llarray|ib)
        got=$(fragments "${out%.png}.json")
        # the same fragments as the reference, within edge rasterization (0.5%)
        diff=$(( got > ref_fragments ? got - ref_fragments : ref_fragments - got ))
        [ $(( diff * 200 )) -le "$ref_fragments" ] || fail "$label: $got fragments, reference $ref_fragments (hidden part $hidden stored?)"
        ;;
    esac
    echo "ok: $label ($backend) applies the opacity of parts $faded and $hidden"
done

# the same parts as a glTF (a node, mesh and material each; Assimp's path):
# the same image within the tolerance (its coordinates are rounded once, the OBJ's
# by its reader)
if [ "$parts" -gt 1331 ]; then
    python3 "$(dirname "$0")/many_parts.py" "$work/many_parts.gltf" "$parts" || fail "many_parts.py (glTF)"
    "$oit" render --model "$work/many_parts.gltf" --algorithm ll --size 128x128 --out "$work/gltf.png" "${alphas[@]}" \
        >/dev/null || fail "render the glTF"
    compare "$work/gltf.png" "$work/reference.png" || fail "the glTF of $parts parts differs from the OBJ's reference"
    echo "ok: the glTF's $parts parts take their opacity too"
fi

# indices: any part of the model, and a clear refusal past it
expect_exit 0 "" -- "$oit" render --model "$model" --size 32x32 --out "$work/last.png" --component-alpha "$last=0.5"
expect_exit 2 "component-alpha: no component '$parts'.*index 0\.\.$last" -- \
    "$oit" render --model "$model" --size 32x32 --out "$work/past.png" --component-alpha "$parts=0.5"
expect_exit 2 "hide: no component '4000000000'.*index 0\.\.$last" -- \
    "$oit" render --model "$model" --size 32x32 --out "$work/past.png" --hide 4000000000
echo "ok: every part of a $parts-part model takes its opacity on the GPU"
