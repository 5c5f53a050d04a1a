#!/usr/bin/env bash
# bench_order.sh OIT WORKDIR SCENES: every exact algorithm gives the reference image on
# its first frame even right after another algorithm in the same GL context (as in
# oit bench, oit demo and the app): no algorithm may depend on GL state left by another.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3
rm -rf "$work"; mkdir -p "$work"
"$oit" bench --model "$scenes/onion.obj" --algorithms ll,dp,ib,ddp,wboit,dp,blend,ll,ib,ddp --sizes 48 \
    --frames 1 --warmup 0 --reference-max-pixels 4096 --quiet --csv "$work/order.csv" || fail "bench"
python3 - "$work/order.csv" <<'PY' || fail "an algorithm depends on GL state left by the one before it"
import csv, sys
bad = []
rows = list(csv.DictReader(open(sys.argv[1])))
for k, r in enumerate(rows):
    if r["algorithm"] in ("dp", "ddp", "ll", "ib"):
        before = rows[k - 1]["algorithm"] if k else "nothing"
        ok = int(r["ref_max_diff"]) <= 2 and float(r["ref_over_tolerance_percent"]) <= 1.0
        print(f"{r['algorithm']:4} after {before:6}: max diff {r['ref_max_diff']:>3}, layers {r['layers'] or '-'}",
              "ok" if ok else "WRONG")
        if not ok:
            bad.append(f"{r['algorithm']} after {before}")
assert not bad, bad
PY
echo "order ok"
