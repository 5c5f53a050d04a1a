#!/usr/bin/env bash
# sections_checks.sh OIT GEARBOX_OBJ WORK: what the section planes must do that an
# image comparison with the reference cannot show (tests/sections.cmake):
# - a plane removes pixels (the cut reference differs from the uncut one);
# - --section-parts cuts only the named parts: cutting gear_3 alone differs from
#   cutting every part and from no cut, and with gear_3 hidden it is
#   byte-identical to no cut (the only part it may cut is absent);
# - the pick never lands on a removed fragment: at the centre pixel the uncut
#   pick is the housing's front wall (z = 0.5); with the plane z <= 0.4 the
#   first and second parts' points keep z <= 0.4;
# - bad input exits non-zero with one line naming the problem.
set -u
oit=$1 model=$2 work=$3
mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
render() { local out=$1; shift; "$oit" render --model "$model" --algorithm reference --size 128x128 --out "$work/$out" "$@" >/dev/null || fail "render $out exited $?"; }
same() { "$oit" compare "$work/$1" "$work/$2" --tolerance 0 --max-mismatch 0 >/dev/null; }
plane=(--section 1,0.2,0,0.13)

render uncut.png
render cut.png "${plane[@]}"
render parts.png "${plane[@]}" --section-parts gear_3
render hidden_cut.png "${plane[@]}" --section-parts gear_3 --hide gear_3
render hidden.png --hide gear_3
same cut.png uncut.png && fail "the plane removed nothing"
same parts.png cut.png && fail "--section-parts gear_3 cut as much as every part"
same parts.png uncut.png && fail "--section-parts gear_3 cut nothing"
same hidden_cut.png hidden.png || fail "--section-parts gear_3 cut another part than gear_3"
echo "planes remove pixels; --section-parts cuts gear_3 alone"

pick() { "$oit" pick --model "$model" --size 128x128 --pixel 64,64 --json "$@" || fail "pick $* exited $?"; }
z_of() { python3 -c 'import json,sys; d=json.loads(sys.argv[1]); print(d["part"], d["point"][2] if d["part"] else "none")' "$1"; }
read -r part z <<<"$(z_of "$(pick)")"
[ "$part" = housing ] && python3 -c "import sys; sys.exit(not abs($z - 0.5) < 1e-3)" ||
    fail "uncut pick is $part at z $z, expected the housing at z 0.5"
for rank in 1 2; do
    read -r part z <<<"$(z_of "$(pick --section 0,0,1,0.4 --rank $rank)")"
    [ "$part" != None ] || fail "cut pick rank $rank found no part"
    python3 -c "import sys; sys.exit(not $z <= 0.4 + 1e-5)" || fail "cut pick rank $rank: $part at z $z, removed by z <= 0.4"
    echo "cut pick rank $rank: $part at z $z"
done

# bad input: exit non-zero, one line on stderr, naming the problem
bad() {
    local expect=$1; shift
    local err
    err=$("$oit" "$@" 2>&1 >/dev/null) && fail "$* succeeded"
    [ "$(printf '%s\n' "$err" | wc -l)" -eq 1 ] || fail "$*: more than one line: $err"
    grep -qF -- "$expect" <<<"$err" || fail "$*: '$err' does not say '$expect'"
    echo "refused: $err"
}
r=(render --model "$model" --algorithm reference --size 128x128 --out "$work/bad.png")
bad "normal (NX,NY,NZ) must not be zero" "${r[@]}" --section 0,0,0,1
bad "--section must be NX,NY,NZ,D" "${r[@]}" --section 1,2
bad "--section must be NX,NY,NZ,D" "${r[@]}" --section 1,0,0,nan
bad "--section must be NX,NY,NZ,D" "${r[@]}" --section 1,0,0,1e999
bad "at most 6 section planes" "${r[@]}" --section 1,0,0,1 --section 1,0,0,1 --section 1,0,0,1 \
    --section 1,0,0,1 --section 1,0,0,1 --section 1,0,0,1 --section 1,0,0,1
bad "no component 'nosuchpart'" "${r[@]}" --section 1,0,0,0 --section-parts gear_3,nosuchpart
bad "--caps must be on or off" "${r[@]}" --caps maybe
bad "no component 'nosuchpart'" pick --model "$model" --size 128x128 --pixel 1,1 --section 1,0,0,0 \
    --section-parts nosuchpart
echo "sections checks: all passed"
