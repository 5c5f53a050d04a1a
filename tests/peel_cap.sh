#!/usr/bin/env bash
# peel_cap.sh OIT WORKDIR: depth peeling never cuts a frame without a word
# (issue "Exact means exact", part 4). 300 parallel sheets at alpha 0.01: by
# default dp and ddp peel all 300 layers and match the reference; an explicit
# --max-layers 16 still gives an image, one warning line and "truncated": true;
# a cap the scene does not reach is not a cut.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2
rm -rf "$work"; mkdir -p "$work"
python3 - "$work/sheets.obj" <<'PY'
import sys
sheets = 300
with open(sys.argv[1], "w") as f:
    for k in range(sheets):
        z = -1 + 2 * k / (sheets - 1)
        half = 1.0 + 0.3 * (k % 7) / 7  # sizes vary, so pixels differ in depth
        f.write(f"o sheet{k}\n")
        for x, y in ((-half, -half), (half, -half), (half, half), (-half, half)):
            f.write(f"v {x} {y} {z}\n")
        b = 4 * k
        f.write(f"f {b + 1} {b + 2} {b + 3}\nf {b + 1} {b + 3} {b + 4}\n")
PY
render() { # NAME ALGORITHM [args...]: PNG, JSON, stderr in $work
    local name=$1 algorithm=$2
    shift 2
    "$oit" render --model "$work/sheets.obj" --algorithm "$algorithm" --alpha 0.01 --size 48x48 --shading flat \
        --out "$work/$name.png" --json "$@" >"$work/$name.json" 2>"$work/$name.err" || { cat "$work/$name.err"; fail "$name"; }
}
field() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])" "$work/$1.json" "$2"; }
render reference reference
for algorithm in dp ddp; do
    render $algorithm $algorithm
    [ "$(field $algorithm layers)" = 300 ] || fail "$algorithm must peel all 300 layers by default, got $(field $algorithm layers)"
    [ "$(field $algorithm truncated)" = False ] || fail "$algorithm: an uncapped frame is not truncated"
    [ ! -s "$work/$algorithm.err" ] || { cat "$work/$algorithm.err"; fail "$algorithm: no warning without a cut"; }
    "$oit" compare "$work/reference.png" "$work/$algorithm.png" --tolerance 2 --max-mismatch 0.1 \
        || fail "$algorithm with no cap must match the reference (2/255 on 99.9% of pixels)"

    render ${algorithm}_16 $algorithm --max-layers 16
    [ "$(field ${algorithm}_16 truncated)" = True ] || fail "$algorithm --max-layers 16 must say truncated"
    [ "$(wc -l <"$work/${algorithm}_16.err")" -eq 1 ] && grep -q "^oit: warning: $algorithm: --max-layers 16 cut the frame short" \
        "$work/${algorithm}_16.err" || { cat "$work/${algorithm}_16.err"; fail "$algorithm --max-layers 16: one warning line"; }
    if "$oit" compare "$work/reference.png" "$work/${algorithm}_16.png" --tolerance 2 --max-mismatch 0.1 >/dev/null; then
        fail "$algorithm --max-layers 16 cannot match the reference on 300 layers"
    fi

    render ${algorithm}_300 $algorithm --max-layers 300
    [ "$(field ${algorithm}_300 truncated)" = False ] || fail "$algorithm: a cap of exactly 300 layers cuts nothing"
    [ ! -s "$work/${algorithm}_300.err" ] || fail "$algorithm --max-layers 300: no warning"
done
# every exact algorithm, both back ends: 300 layers at alpha 0.01 match the reference
for backend in egl osmesa; do
    for variant in dp ddp ll ll:--sort:array ib; do
        IFS=: read -r -a args <<<"$variant"
        label=$(IFS=_; echo "${args[*]}" | tr -d '-')_$backend
        render "$label" "${args[@]}" --backend $backend
        [ "$(field "$label" truncated)" = False ] || fail "$variant ($backend): nothing is cut without a cap"
        "$oit" compare "$work/reference.png" "$work/$label.png" --tolerance 2 --max-mismatch 0.1 \
            || fail "$variant ($backend) on 300 layers must match the reference (2/255 on 99.9% of pixels)"
    done
done
expect_exit 2 "--max-layers must be a whole number from 1 to 1000000" -- "$oit" render --model "$work/sheets.obj" --max-layers 0
expect_exit 2 "--max-layers must be a whole number from 1 to 1000000" -- "$oit" render --model "$work/sheets.obj" --max-layers 1000001
echo "peeling caps: all behaved"
