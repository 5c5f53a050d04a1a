#!/usr/bin/env bash
# bench_report.sh OIT WORKDIR SCENES SOURCE: bat/report.py turns a tiny bench run
# into benchmarks.md with its sections and plots (shape only, no timings).
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 source=$4
rm -rf "$work"; mkdir -p "$work/results" "$work/docs"
printf 'onion-a %s/onion.obj --orbit 0,0\nspheres-b %s/spheres.obj --orbit 30,20\n' "$scenes" "$scenes" >"$work/scenes.txt"
"$oit" bench --scene-list "$work/scenes.txt" --algorithms blend,dp,ddp,ll,ll-array,ib,wboit --sizes 32 --frames 1 \
    --warmup 0 --quiet --reference-max-pixels 0 --csv "$work/results/bench.csv" --json "$work/results/bench.json" \
    || fail "bench"
"$oit" bench --scene-list "$work/scenes.txt" --algorithms ll,ib --sizes 24 --frames 1 --warmup 0 --quiet \
    --reference-max-pixels 1000 --csv "$work/results/accuracy.csv" || fail "accuracy bench"
mv="1 0 0 0 0 1 0 0 0 0 1 -3 0 0 0 1"
p="1.8 0 0 0 0 1.8 0 0 0 0 -1.2 -2.2 0 0 -1 0"
for size in 24 32; do
    # shellcheck disable=SC2086
    "$oit" measure --results "$work/results/ib_resolutions.txt" --frames 1 --warmup 0 2 1 onion "$scenes/onion.obj" $mv $p $size >/dev/null || fail "measure"
done
python3 "$source/bat/pages.py" machine --oit "$oit" >"$work/results/machine.json" || fail "pages.py machine"
python3 "$source/bat/report.py" --results "$work/results" --docs "$work/docs" --command "tests/bench_report.sh" \
    || fail "report.py"
page=$work/docs/benchmarks.md
for heading in "## Targets" "## Scenes" "## Frame time per algorithm and scene" "## Our ratios beside the thesis's" \
    "## Illustration Buffer: stage breakdown" "## Parallel coordinates" "## Memory per algorithm" "## Resolution sweep" \
    "## Difference from the reference" "## Depth complexity per scene"; do
    grep -qF "$heading" "$page" || fail "benchmarks.md lacks '$heading'"
done
grep -q "llvmpipe" "$page" || fail "benchmarks.md must name the driver"
for image in frame-times ratios ib-stages parallel memory resolutions depth-complexity; do
    [ -s "$work/docs/images/bench-$image.png" ] || fail "no plot bench-$image.png"
done
# the depth-complexity table is ll's list_histogram of bench.csv (no reference there), recomputed
python3 - "$work/results/bench.csv" "$page" <<'PY' || fail "the depth-complexity table does not show bench.csv's histograms"
import csv, sys
rows, page = list(csv.DictReader(open(sys.argv[1]))), open(sys.argv[2]).read()
for scene in ("onion-a", "spheres-b"):
    ll = next(r for r in rows if r["scene"] == scene and r["algorithm"] == "ll")
    h = [int(c) for c in ll["list_histogram"].split(";")]
    assert sum(h) == 32 * 32 and ll["scene_histogram"] == "", ll
    covered = 32 * 32 - h[0]
    mean = sum(i * c for i, c in enumerate(h)) / covered
    assert sum(i * c for i, c in enumerate(h)) == int(ll["fragments"]), (h, ll["fragments"])
    p50 = next(i for i in range(1, len(h)) if sum(h[1:i + 1]) >= covered / 2)
    line = f"| {scene} | 32×32 | `ll` | {100 * covered / 1024:.1f} | {mean:.2f} | {p50} | "
    assert line in page, (line, [l for l in page.splitlines() if l.startswith(f"| {scene} | 32×32 | `")])
print("depth complexity ok")
PY

# The sentences about the machine and the thesis are computed from the inputs: this machine's ...
grep -qF "$(nproc) logical CPUs" "$page" || fail "benchmarks.md must say this machine's $(nproc) logical CPUs"
grep -q "at commit [0-9a-f]" "$page" || fail "benchmarks.md must name the commit"
renderer=$(python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["renderer"])' "$work/results/bench.json")
grep -qF -- "- **Driver**: $renderer" "$page" || fail "benchmarks.md must name the renderer of bench.json ($renderer)"
case $renderer in
*llvmpipe* | *softpipe* | *swrast*) grep -q "back end, no GPU$" "$page" || fail "a software renderer is 'no GPU'" ;;
*) grep -q "back end, on the GPU$" "$page" || fail "a GPU renderer is 'on the GPU'" ;;
esac
# ... another machine's (8 cores, a GPU, frames that varied) ...
cp -r "$work/results" "$work/other"
python3 - "$work/other" <<'PY' || fail "could not write the other machine's results"
import csv, json, os, sys
results = sys.argv[1]
meta = json.load(open(os.path.join(results, "bench.json")))
meta["renderer"] = "NVIDIA GeForce RTX 3060/PCIe/SSE2"
json.dump(meta, open(os.path.join(results, "bench.json"), "w"))
json.dump({"cpu": "Test CPU 9000", "logical_cpus": 8, "virtual_machine": False, "kernel": "Linux 9.9",
           "mesa": None, "lp_num_threads": None, "renderer": meta["renderer"], "backend": "egl",
           "commit": "abcdef1"}, open(os.path.join(results, "machine.json"), "w"))
rows = list(csv.DictReader(open(os.path.join(results, "bench.csv"))))
for r in rows:
    if r["scene"] == "onion-a" and r["algorithm"] == "ll":
        r.update(frames="3", cpu_ms_min="10", cpu_ms_median="20", cpu_ms_max="40")
with open(os.path.join(results, "bench.csv"), "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
PY
python3 "$source/bat/report.py" --results "$work/other" --docs "$work/other-docs" --command "tests/bench_report.sh" \
    >/dev/null || fail "report.py on the other machine's results"
other=$work/other-docs/benchmarks.md
for text in "Test CPU 9000, 8 logical CPUs, Linux 9.9" "NVIDIA GeForce RTX 3060/PCIe/SSE2" "back end, on the GPU" \
    "timed by \`GL_TIME_ELAPSED\` queries" "The machine has 8 logical CPUs." "at commit abcdef1" \
    "by up to 150% of their median (onion-a's \`ll\`: 10.0 to 40.0 ms)"; do
    grep -qF -- "$text" "$other" || fail "the other machine's page lacks '$text'"
done
for text in "no GPU" "llvmpipe runs" "two cores" "AMD EPYC"; do
    ! grep -qF -- "$text" "$other" || fail "the other machine's page still says '$text'"
done
# ... ll's sorts come from sorts.json (step 3d), and the papers' claims sit beside the same ratios ...
mkdir -p "$work/sorted"
"$oit" bench --scene-list "$work/scenes.txt" --scenes onion-a --algorithms ll-insertion,ll-array,ll-bma,ll-merge \
    --sizes 24 --frames 1 --warmup 0 --quiet --reference-max-pixels 0 --json "$work/sorted/sorts.json" || fail "sorts bench"
cp "$work/results/"* "$work/sorted/"
python3 "$source/bat/report.py" --results "$work/sorted" --docs "$work/sorted-docs" --command "tests/bench_report.sh" \
    >/dev/null || fail "report.py with sorts.json"
python3 - "$work/sorted/sorts.json" "$work/sorted-docs/benchmarks.md" <<'PY' || fail "the sorts section does not show sorts.json"
import json, sys
run, page = json.load(open(sys.argv[1])), open(sys.argv[2]).read()
assert "## ll's sorts: Knowles' against the plain ones" in page, "no sorts section"
rows = {r["algorithm"]: r for r in run["results"]}
def ms(v):
    return f"{v:,.0f}" if v >= 1000 else f"{v:.2f}"
sort = [ms(next(s["median"] for s in rows[a]["stages"] if s["name"] == "sort"))
        for a in ("ll-insertion", "ll-array", "ll-bma", "ll-merge")]
frame = [ms(rows[a]["gpu_ms"]["median"]) for a in ("ll-insertion", "ll-array", "ll-bma", "ll-merge")]
line = "| onion-a | " + f"{rows['ll-array']['max_list']}, {rows['ll-array']['mean_list']:.1f} | " + " | ".join(sort + frame) + " |"
assert line in page, (line, [l for l in page.splitlines() if l.startswith("| onion-a | ")])
# the BMA claim (docs/data/published_claims.csv) beside array's frame over bma's, from the same run
ratio = rows["ll-array"]["gpu_ms"]["median"] / rows["ll-bma"]["gpu_ms"]["median"]
claim = next(l for l in page.splitlines() if "Backwards Memory Allocation" in l)
assert "| up to 3x |" in claim and f"`ll-array` / `ll-bma`: {ratio:.2f}x (1 scene)" in claim, claim
PY
! grep -qF "## ll's sorts" "$page" || fail "a page without sorts.json has a sorts section"
# ... the scale section comes from scale.json (bat/scale.py): figures, ll's and ib's bands and a refusal ...
"$oit" bench --model "$scenes/onion.obj" --name onion-bands --algorithms blend,ll,ib --sizes 48 --frames 1 --warmup 0 \
    --quiet --reference-max-pixels 0 --buffer-fragment-limit 1000 --json "$work/scale-run.json" || fail "scale bench"
cp -r "$work/results" "$work/scaled"
python3 - "$work/scale-run.json" "$work/scaled/scale.json" <<'PY' || fail "could not write scale.json"
import copy, json, sys
run = json.load(open(sys.argv[1]))
run["label"] = "screens"
big = copy.deepcopy(run)
big["label"] = "big"
big["results"].append(dict(big["results"][0], algorithm="ib", error="ib: the frame needs 9 fragments, more than this GL can address in one shader storage buffer (8)"))
json.dump({"command": "python3 bat/scale.py", "runs": [run, big]}, open(sys.argv[2], "w"))
PY
python3 "$source/bat/report.py" --results "$work/scaled" --docs "$work/scaled-docs" --command "tests/bench_report.sh" \
    >/dev/null || fail "report.py with scale.json"
python3 - "$work/scale-run.json" "$work/scaled-docs/benchmarks.md" <<'PY' || fail "the scale section does not show the run"
import json, sys
run, page = json.load(open(sys.argv[1])), open(sys.argv[2]).read()
assert "## Scale: screen sizes and a large model" in page, "no scale section"
for name in ("ll", "ib"):
    banded = next(r for r in run["results"] if r["algorithm"] == name)
    assert banded["bands"] > 1, banded
    row = f"| onion-bands | 48×48 | `{name}` | "
    lines = [l for l in page.splitlines() if l.startswith(row) and "refused" not in l]
    assert len(lines) == 2, lines  # one per run
    assert lines[0].endswith(f"| {banded['fragments']:,} | {banded['max_list']} | {banded['bands']} |"), lines[0]
assert "| onion-bands | 48×48 | `ib` | refused |" in page and "more than this GL can address in one shader storage buffer (8)" in page
PY
! grep -qF "## Scale" "$page" || fail "a page without scale.json has a scale section"
# ... and the thesis's figures come from ../shared (a changed copy changes them) ...
mkdir -p "$work/shared"
cp -r "$source/../shared/data" "$source/../shared/sources" "$work/shared/" || fail "no ../shared beside $source"
chmod -R u+w "$work/shared"   # CI's shared/ has no write bits, and cp keeps them
sed -i 's/^GPU 2,17.111233,58,27.447712,36,20.68,50,[0-9.]*,/GPU 2,17.111233,58,27.447712,36,20.68,50,300.0,/' \
    "$work/shared/data/thesis_table_5_4_oit_comparison.csv"
sed -i 's/need 208 bytes per fragment/need 999 bytes per fragment/' "$work/shared/sources/001_d33ee0e5babd5f13.txt"
python3 "$source/bat/report.py" --results "$work/results" --docs "$work/thesis-docs" --shared "$work/shared" \
    --command "tests/bench_report.sh" >/dev/null || fail "report.py with a changed thesis"
grep -qF "worst 14.51)" "$work/thesis-docs/benchmarks.md" || fail "the thesis's worst ib/ll is not read from table 5.4"
grep -qF "the thesis: 999 bytes" "$work/thesis-docs/benchmarks.md" || fail "the thesis's bytes per fragment are not read"
! grep -qF "worst 14.51)" "$page" || fail "the real table 5.4 gives 14.51?"
# ... which must be there
rm -rf "$work/shared/data/thesis_table_5_4_oit_comparison.csv"
if python3 "$source/bat/report.py" --results "$work/results" --docs "$work/thesis-docs" --shared "$work/shared" \
    >/dev/null 2>"$work/missing.err"; then
    fail "report.py ran without table 5.4"
fi
grep -q "thesis_table_5_4_oit_comparison.csv is missing: the thesis's figures are read from ../shared" \
    "$work/missing.err" || { cat "$work/missing.err" >&2; fail "no clear message for a missing thesis table"; }
echo "report ok"
