#!/usr/bin/env bash
# highlight.sh OIT WORKDIR SCENES TOLERANCE MISMATCH: the selection highlight
# (--highlight, docs/modulation.md). The exact algorithms' highlighted images
# match the reference's highlighted image within the exact tolerance; in every
# algorithm the highlight changes only the highlighted parts' pixels (and enough
# of them to be seen); --highlight-colour changes it; parts past 1024 are reached;
# bad values exit 2 with one line.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 tolerance=$4 mismatch=$5
here=$(dirname "$0")
rm -rf "$work"; mkdir -p "$work"
model=$scenes/gearbox.obj
frame=(--model "$model" --size 96x96 --component-alpha housing=0.3)
render() { local out=$1; shift; "$oit" render "${frame[@]}" "$@" --out "$work/$out" >/dev/null || fail "render $out: exit $?"; }
others=()
for part in housing gear_2 gear_3 gear_4 shaft_1 shaft_2 shaft_3 bearing_1_back bearing_1_front \
    bearing_2_back bearing_2_front bearing_3_back bearing_3_front; do
    others+=(--hide "$part")
done

render reference.png --algorithm reference --highlight gear_1
render alone.png --algorithm reference "${others[@]}"
for algorithm in ll dp ddp ib kbuffer wboit mboit blend; do
    render "$algorithm.png" --algorithm "$algorithm"
    render "${algorithm}_highlight.png" --algorithm "$algorithm" --highlight gear_1
    echo -n "$algorithm: "
    python3 "$here/highlight_pixels.py" "$work/$algorithm.png" "$work/${algorithm}_highlight.png" \
        "$work/alone.png" || fail "$algorithm: the highlight is not only on gear_1"
    case $algorithm in
    wboit | mboit | blend) ;; # approximations: only the check above
    *) "$oit" compare "$work/${algorithm}_highlight.png" "$work/reference.png" --tolerance "$tolerance" \
        --max-mismatch "$mismatch" || fail "$algorithm's highlighted image differs from the reference's" ;;
    esac
done

# the other back end (OSMesa) too
render osmesa_ll.png --algorithm ll --highlight gear_1 --backend osmesa
"$oit" compare "$work/osmesa_ll.png" "$work/reference.png" --tolerance "$tolerance" --max-mismatch "$mismatch" ||
    fail "ll on OSMesa: the highlighted image differs from the reference's"

# a colour of one's own changes the image; several parts, by name and index
render green.png --algorithm ll --highlight gear_1 --highlight-colour 0,1,0
cmp -s "$work/green.png" "$work/ll_highlight.png" && fail "--highlight-colour changed nothing"
render two.png --algorithm ll --highlight gear_1,2
render two_reference.png --algorithm reference --highlight gear_1 --highlight gear_2
"$oit" compare "$work/two.png" "$work/two_reference.png" --tolerance "$tolerance" --max-mismatch "$mismatch" ||
    fail "two highlighted parts: ll differs from the reference"

# parts past the first 256 (the chunk the GPU buffer is written in) and 1024:
# a 1331-part model (tests/many_parts.py), parts 1200 and 1300 highlighted
python3 "$here/many_parts.py" "$work/many.obj" 1331 >/dev/null || fail "many_parts.py"
many=(--model "$work/many.obj" --size 96x96 --highlight 1200,1300)
"$oit" render "${many[@]}" --algorithm reference --out "$work/many_reference.png" >/dev/null || fail "render many reference"
"$oit" render "${many[@]}" --algorithm ll --out "$work/many_ll.png" >/dev/null || fail "render many ll"
"$oit" render --model "$work/many.obj" --size 96x96 --algorithm ll --out "$work/many_plain.png" >/dev/null ||
    fail "render many plain"
cmp -s "$work/many_ll.png" "$work/many_plain.png" && fail "highlighting parts 1200 and 1300 changed nothing"
"$oit" compare "$work/many_ll.png" "$work/many_reference.png" --tolerance "$tolerance" --max-mismatch "$mismatch" ||
    fail "parts 1200 and 1300 highlighted: ll differs from the reference"

r=("$oit" render "${frame[@]}" --out "$work/x.png")
expect_exit 2 "highlight: no component 'nosuchpart'.*housing" -- "${r[@]}" --highlight nosuchpart
expect_exit 2 "highlight: no component '14'" -- "${r[@]}" --highlight gear_1,14
expect_exit 2 "highlight needs NAME" -- "${r[@]}" --highlight gear_1,
expect_exit 2 "highlight-colour must be R,G,B" -- "${r[@]}" --highlight-colour 1,0
expect_exit 2 "highlight-colour must be R,G,B" -- "${r[@]}" --highlight-colour 1,0,2
"$oit" render --help | grep -q -- "--highlight NAME" || fail "render --help lacks --highlight"
echo "highlight: ok"
