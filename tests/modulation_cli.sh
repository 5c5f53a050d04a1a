#!/usr/bin/env bash
# modulation_cli.sh OIT WORKDIR SCENES: the local modulation flags refuse bad
# values with one clear line (exit 2), `oit render --help` documents each flag
# and its range, and fragments whose opacity is 0 are never stored (the
# fragment counts of ll, ib and the reference drop by the same amount).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
model=$scenes/gearbox.obj
render() { "$oit" render --model "$model" --size 64x64 --out "$work/x.png" "$@"; }
r=("$oit" render --model "$model" --size 64x64 --out "$work/x.png") # for expect_exit

# --- bad values (exit 2, one line naming the flag) ---
expect_exit 2 "no component 'nosuchpart'.*housing" -- "${r[@]}" --hide nosuchpart
expect_exit 2 "no component '14'.*0\.\.13" -- "${r[@]}" --component-alpha 14=0.5
expect_exit 2 "component-alpha.*\[0, 1\]" -- "${r[@]}" --component-alpha housing=1.5
expect_exit 2 "component-alpha.*\[0, 1\]" -- "${r[@]}" --component-alpha housing=-0.1
expect_exit 2 "component-alpha.*\[0, 1\]" -- "${r[@]}" --component-alpha housing=nan
expect_exit 2 "component-alpha must be NAME=A" -- "${r[@]}" --component-alpha housing
expect_exit 2 "component-alpha must be NAME=A" -- "${r[@]}" --component-alpha =0.5
expect_exit 2 "hide needs a value" -- "${r[@]}" --hide
expect_exit 2 "focus-point must be x,y,z" -- "${r[@]}" --focus-point 1,2
expect_exit 2 "focus-point must be x,y,z" -- "${r[@]}" --focus-point 1,2,3,4
expect_exit 2 "focus-point must be x,y,z" -- "${r[@]}" --focus-point 1,inf,3
expect_exit 2 "focus-point must be x,y,z" -- "${r[@]}" --focus-point 1,2e10,3
expect_exit 2 "focus-plane.*normal.*zero" -- "${r[@]}" --focus-plane 0,0,0,1
expect_exit 2 "focus-plane must be a,b,c,d" -- "${r[@]}" --focus-plane 1,0,0
expect_exit 2 "focus-box.*minimum" -- "${r[@]}" --focus-box 1,0,0,0,1,1
expect_exit 2 "focus-box must be" -- "${r[@]}" --focus-box 0,0,0,1,1
expect_exit 2 "only one focus shape.*focus-point" -- "${r[@]}" --focus-point 0,0,0 --focus-box 0,0,0,1,1,1
expect_exit 2 "contrast must be a number in \[0.1, 10\]" -- "${r[@]}" --contrast 0
expect_exit 2 "contrast must be a number in \[0.1, 10\]" -- "${r[@]}" --contrast 11
expect_exit 2 "contrast must be a number in \[0.1, 10\]" -- "${r[@]}" --contrast x

# --- the help names every flag and its range ---
help=$("$oit" render --help)
for pattern in "--component-alpha NAME=A .*\[0, 1\]" "--hide NAME" "--focus-point X,Y,Z" \
    "--focus-plane A,B,C,D" "--focus-box X0,Y0,Z0,X1,Y1,Z1" "--contrast C" "C in \[0.1, 10\]" \
    "1/4 of the bounding radius"; do
    grep -Eq -- "$pattern" <<<"$help" || fail "render --help lacks /$pattern/"
done
echo "ok: help documents every local modulation flag"

# --- opacity 0 is never stored: equal fragment counts in ll, ib and the reference ---
fragments() { render --json "$@" | sed -n 's/.*"fragments": \([0-9-]*\).*/\1/p'; }
for flags in "" "--hide gear_1 --hide housing" "--focus-box -0.5,-0.5,-1,0.5,0.5,1" \
    "--component-alpha gear_1=0 --focus-point 0,0,0.6"; do
    # shellcheck disable=SC2086
    ref=$(fragments --algorithm reference $flags)
    # shellcheck disable=SC2086
    ll=$(fragments --algorithm ll $flags)
    # shellcheck disable=SC2086
    ib=$(fragments --algorithm ib $flags)
    [ -n "$ref" ] && [ "$ref" -gt 0 ] || fail "no fragment count from the reference ($flags)"
    # rasterization may differ on a few edge pixels: 0.5% of the fragments
    for got in "$ll" "$ib"; do
        diff=$(( got > ref ? got - ref : ref - got ))
        [ $(( diff * 200 )) -le "$ref" ] || fail "fragments: reference $ref, ll $ll, ib $ib ($flags)"
    done
    echo "ok: fragments reference $ref, ll $ll, ib $ib ($flags)"
    if [ -z "$flags" ]; then all=$ref; else
        [ "$ref" -lt "$all" ] || fail "'$flags' stored $ref fragments, no fewer than all $all"
    fi
done

# --- what an algorithm cannot express, it refuses with its reason (exit 2) ---
expect_exit 2 "blend: the distance modulation needs the next fragment" -- "${r[@]}" --algorithm blend --modulation distance
expect_exit 2 "wboit: the distance modulation needs the next fragment" -- "${r[@]}" --algorithm wboit --modulation distance
expect_exit 2 "dp: only the adjacent distance" -- "${r[@]}" --algorithm dp --modulation distance --distance far
expect_exit 2 "dp: only the adjacent distance" -- "${r[@]}" --algorithm dp --modulation distance --distance skip:2
expect_exit 2 "ddp: only the adjacent distance" -- "${r[@]}" --algorithm ddp --modulation distance --distance far
for algorithm in blend wboit ddp ll; do
    expect_exit 2 "$algorithm: opacity modulation 'curvature' needs surface neighbours" -- "${r[@]}" --algorithm "$algorithm" --modulation curvature
done
# dp approximates curvature and edges (neighbours in the same peeled layer), not fields
expect_exit 2 "dp: opacity modulation 'fields' needs surface neighbours" -- "${r[@]}" --algorithm dp --modulation fields
expect_exit 2 "dp: only the adjacent distance" -- "${r[@]}" --algorithm dp --modulation dist-curv --distance far
