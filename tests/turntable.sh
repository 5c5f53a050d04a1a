#!/usr/bin/env bash
# turntable.sh OIT WORKDIR SCENES: oit render --turntable N (docs/cli.md, "Turntables").
# (a) the N frames are byte for byte N single renders at the modelviews --json
#     reports, and those are the orbit: frame 0 the camera given, each the one
#     before turned by 360/N about the up axis through the model's centre (the
#     centre's eye position and the axis's eye direction stay), within 1e-9;
# (b) the video decodes (ffprobe) to N frames of the size, H.264 yuv420p, and
#     its decoded frame 0 is close to frame_0000.png (lossy: mean |diff| under
#     4 of 255 and PSNR over 30 dB) and closer to it than to frame N/2;
# (c) bad input (N 0, -3, abc, 100001, an odd size with the video, flags a
#     turntable cannot take, unwritable or foreign folders) exits 2 with one
#     line and leaves no file; SIGTERM mid-run leaves nothing; a second run
#     replaces a previous turntable whole.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
here=$(dirname "$0")
rm -rf "$work"; mkdir -p "$work"
model=$scenes/gearbox.obj
n=8
common=(--model "$model" --size 64x64 --orbit 30,20 --explode 0.3 --component-alpha housing=0.3)

# (a) the frames and the matrices
"$oit" render "${common[@]}" --algorithm ll --turntable $n --out "$work/tt" --json >"$work/tt.json" ||
    fail "turntable: exit $?"
"$oit" render "${common[@]}" --algorithm ll --json >"$work/single.json" || fail "single: exit $?"
[ "$(ls "$work/tt" | wc -l)" -eq $((n + 1)) ] || fail "expected $n PNGs and the video: $(ls "$work/tt")"
python3 "$here/turntable_check.py" "$work/tt.json" "$work/single.json" $n >"$work/frames.txt" ||
    fail "the turntable's matrices are not the orbit"
i=0
while read -r modelview projection; do
    png=$(printf 'frame_%04d.png' $i)
    "$oit" render "${common[@]}" --algorithm ll --modelview "$modelview" --projection "$projection" \
        --out "$work/single_$png" >/dev/null || fail "single render $i: exit $?"
    cmp -s "$work/tt/$png" "$work/single_$png" || fail "$png differs from the single render at its matrices"
    i=$((i + 1))
done <"$work/frames.txt"
[ $i -eq $n ] || fail "$i frames listed, expected $n"
echo "ok: $n frames byte for byte the single renders at the reported matrices"
# the view's up axis: the same property about another axis, with another algorithm
"$oit" render "${common[@]}" --algorithm dp --turntable 4 --turntable-up view --no-video --out "$work/view" \
    --json >"$work/view.json" || fail "--turntable-up view: exit $?"
python3 "$here/turntable_check.py" "$work/view.json" "$work/single.json" 4 view >"$work/view.txt" ||
    fail "--turntable-up view: not the orbit"
read -r modelview projection < <(sed -n 3p "$work/view.txt")
"$oit" render "${common[@]}" --algorithm dp --modelview "$modelview" --projection "$projection" \
    --out "$work/view_2.png" >/dev/null || fail "single render (view): exit $?"
cmp -s "$work/view/frame_0002.png" "$work/view_2.png" || fail "--turntable-up view: frame 2 differs"
[ ! -e "$work/view/turntable.mp4" ] || fail "--no-video wrote a video"
echo "ok: --turntable-up view, dp, --no-video"

# (b) the video
probe=$(ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,pix_fmt,nb_read_frames -of csv=p=0 "$work/tt/turntable.mp4")
[ "$probe" = "h264,64,64,yuv420p,$n" ] || fail "ffprobe: '$probe', expected h264,64,64,yuv420p,$n"
ffmpeg -v error -y -i "$work/tt/turntable.mp4" -frames:v 1 -pix_fmt rgba "$work/decoded_0.png" ||
    fail "ffmpeg cannot decode frame 0"
near=$("$oit" compare "$work/decoded_0.png" "$work/tt/frame_0000.png" --json) || true
far=$("$oit" compare "$work/decoded_0.png" "$work/tt/frame_$(printf %04d $((n / 2))).png" --json) || true
python3 - "$near" "$far" <<'PY' || fail "decoded frame 0 is not close to frame_0000.png"
import json, sys
near, far = json.loads(sys.argv[1]), json.loads(sys.argv[2])
print(f"decoded frame 0 vs frame_0000.png: mean {near['mean_diff']:.3f}, psnr {near['psnr_db']:.2f} dB; "
      f"vs the opposite frame: mean {far['mean_diff']:.3f}")
assert near["mean_diff"] < 4.0 and near["psnr_db"] > 30.0
assert near["mean_diff"] < far["mean_diff"] / 2
PY
echo "ok: the video decodes to $n frames of 64x64"

# (c) bad input: one line, exit 2, nothing written
leftovers() { find "$work" -maxdepth 1 -name '*.tmp.*' | head -1; }
for value in 0 -3 abc 100001 ''; do
    expect_exit 2 "--turntable must be a whole number of frames in \[1, 10000\]" -- \
        "$oit" render "${common[@]}" --turntable "$value" --out "$work/bad"
done
expect_exit 2 "--turntable needs a value" -- "$oit" render "${common[@]}" --turntable
expect_exit 2 "needs --out DIR" -- "$oit" render "${common[@]}" --turntable 4
expect_exit 2 "cannot take --frames" -- "$oit" render "${common[@]}" --turntable 4 --frames 3 --out "$work/bad"
expect_exit 2 "cannot take --error-vs-reference" -- \
    "$oit" render "${common[@]}" --turntable 4 --error-vs-reference --out "$work/bad"
expect_exit 2 "cannot take --error-map" -- \
    "$oit" render "${common[@]}" --turntable 4 --error-map "$work/map.png" --out "$work/bad"
expect_exit 2 "go with --turntable" -- "$oit" render "${common[@]}" --fps 24 --out "$work/bad.png"
expect_exit 2 "cannot go with --no-video" -- \
    "$oit" render "${common[@]}" --turntable 4 --no-video --fps 24 --out "$work/bad"
expect_exit 2 "--fps must be a whole number in \[1, 240\]" -- \
    "$oit" render "${common[@]}" --turntable 4 --fps 0 --out "$work/bad"
expect_exit 2 "--turntable-up must be x, y, z or view" -- \
    "$oit" render "${common[@]}" --turntable 4 --turntable-up w --out "$work/bad"
expect_exit 2 "even width and height.*65x64.*--no-video" -- \
    "$oit" render --model "$model" --size 65x64 --turntable 4 --out "$work/bad"
touch "$work/file"
expect_exit 2 "bad/sub" -- "$oit" render "${common[@]}" --turntable 4 --out "$work/bad/sub"
expect_exit 2 "file" -- "$oit" render "${common[@]}" --turntable 4 --out "$work/file"
expect_exit 2 "" -- "$oit" render "${common[@]}" --turntable 4 --out /proc/turntable
mkdir "$work/foreign"; echo keep >"$work/foreign/notes.txt"
expect_exit 2 "not empty and not a turntable" -- "$oit" render "${common[@]}" --turntable 4 --out "$work/foreign"
[ "$(cat "$work/foreign/notes.txt")" = keep ] && [ "$(ls "$work/foreign")" = notes.txt ] ||
    fail "a foreign folder was touched"
[ ! -e "$work/bad" ] || fail "a refused run left $work/bad"
[ -z "$(leftovers)" ] || fail "a refused run left $(leftovers)"
# SIGTERM while the frames are written: no folder, no temporary
"$oit" render "${common[@]}" --turntable 3000 --out "$work/killed" >/dev/null 2>&1 &
pid=$!
for _ in $(seq 600); do [ -n "$(leftovers)" ] && break; sleep 0.05; done
[ -n "$(leftovers)" ] || fail "no temporary folder appeared"
kill -TERM $pid; wait $pid
[ ! -e "$work/killed" ] && [ -z "$(leftovers)" ] || fail "SIGTERM left $(leftovers) $(ls -d "$work/killed" 2>/dev/null)"
echo "ok: SIGTERM left nothing"
# a previous turntable is replaced whole (8 frames -> 4)
"$oit" render "${common[@]}" --turntable 4 --out "$work/tt" >/dev/null || fail "second run: exit $?"
[ "$(ls "$work/tt" | tr '\n' ' ')" = "frame_0000.png frame_0001.png frame_0002.png frame_0003.png turntable.mp4 " ] ||
    fail "the previous turntable was not replaced whole: $(ls "$work/tt")"
[ -z "$(leftovers)" ] || fail "the replacement left $(leftovers)"
echo "ok: turntable"
