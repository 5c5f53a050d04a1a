#!/usr/bin/env bash
# cli_session.sh OIT WORK SOURCE: `oit render --session` without the workbench
# (docs/sessions.md). The committed version-1 example renders at its export size;
# moved together with its model (relative path) it renders the same bytes; a flag
# after it overrides it, another --size keeps the vertical field of view; malformed
# JSON, another format, a newer version, a missing model, a bad value and a bad
# --session are one line and exit 2; unknown fields are warned about, then ignored.
# The byte-for-byte match with the workbench's Export PNG is app_sessions'.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 src=$3
example=$src/tests/data/sessions/gearbox-v1.oitsession
rm -rf "$work" && mkdir -p "$work/pack" || fail "cannot make $work"

"$oit" render --session "$example" --out "$work/example.png" >/dev/null || fail "the version-1 example does not render"
size=$(python3 -c "import struct,sys; d=open(sys.argv[1],'rb').read(24); print('%dx%d' % struct.unpack('>II', d[16:24]))" "$work/example.png")
[ "$size" = 160x120 ] || fail "the example rendered at $size, not its export size 160x120"

# (d) the session and its model moved together: the relative path follows
cp "$src/resources/models/gearbox.obj" "$src/resources/models/gearbox.mtl" "$work/pack/"
sed 's|"../../../resources/models/gearbox.obj"|"gearbox.obj"|' "$example" >"$work/pack/s.oitsession"
mv "$work/pack" "$work/moved"
(cd / && "$oit" render --session "$work/moved/s.oitsession" --out "$work/moved.png" >/dev/null) || fail "moved session"
cmp -s "$work/example.png" "$work/moved.png" || fail "the moved session renders other bytes"
# a relative --session path too
(cd "$work" && "$oit" render --session moved/s.oitsession --out relative.png >/dev/null) || fail "relative --session"
cmp -s "$work/example.png" "$work/relative.png" || fail "a relative --session path renders other bytes"

# flags after the session override it
"$oit" render --session "$example" --algorithm ll --alpha 0.9 --out "$work/override.png" >/dev/null || fail "override"
cmp -s "$work/example.png" "$work/override.png" && fail "--alpha 0.9 after --session changed nothing"
"$oit" render --session "$example" --size 240x120 --out "$work/wide.png" >/dev/null || fail "--size over the session"

s=$work/moved/s.oitsession
bad() { # NAME SED-EXPRESSION: a copy of the moved session, edited
    sed "$2" "$s" >"$work/moved/$1.oitsession"
    echo "$work/moved/$1.oitsession"
}
head -c 300 "$s" >"$work/moved/cut.oitsession"
expect_exit 2 "cut.oitsession: line [0-9]+: not valid JSON" -- "$oit" render --session "$work/moved/cut.oitsession"
expect_exit 2 "not an oit session: \"format\" must be \"oit-session\", got \"oit-preset\"" -- \
    "$oit" render --session "$(bad format 's/"oit-session"/"oit-preset"/')"
expect_exit 2 "version 2 is newer than this oit reads \(1\)" -- "$oit" render --session "$(bad newer 's/"version": 1/"version": 2/')"
expect_exit 2 "model 'nothere.obj' not found \(looked for .*/moved/nothere.obj\)" -- \
    "$oit" render --session "$(bad nomodel 's/"gearbox.obj"/"nothere.obj"/')"
expect_exit 2 "\"render.algorithm\": unknown algorithm 'nope'" -- \
    "$oit" render --session "$(bad badvalue 's/"algorithm": "dp"/"algorithm": "nope"/')"
expect_exit 2 "\"render.alpha\": --alpha must be a number in \[0, 1\], got '7'" -- \
    "$oit" render --session "$(bad badalpha 's/"alpha": [0-9.]*/"alpha": 7/')"
expect_exit 2 "--session: not a regular file|--session .*: No such file|session.*(does not exist|not found)" -- \
    "$oit" render --session "$work/none.oitsession"
expect_exit 2 "--session needs a value" -- "$oit" render --session

# unknown fields: one warning each, the same image
extra=$(bad extra 's/"format":/"colour-scheme": "dark", "format":/; s/"alpha":/"sparkle": 3, "alpha":/')
"$oit" render --session "$extra" --out "$work/extra.png" >/dev/null 2>"$work/extra.err" || { cat "$work/extra.err"; fail "unknown fields refused"; }
grep -q 'unknown field "colour-scheme" ignored' "$work/extra.err" || { cat "$work/extra.err"; fail "no warning for colour-scheme"; }
grep -q '"render.sparkle": unknown field ignored' "$work/extra.err" || { cat "$work/extra.err"; fail "no warning for sparkle"; }
cmp -s "$work/example.png" "$work/extra.png" || fail "unknown fields changed the image"
echo "cli_session: ok"
