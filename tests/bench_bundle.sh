#!/usr/bin/env bash
# bench_bundle.sh OIT WORKDIR SCENES SOURCE: `oit bench --bundle DIR`: every file is there,
# bundle.json holds the command, commit, machine, driver, scenes (model checksums, cameras
# equal to oit render --json's), parameters and the rows of --json; a bundle replaces a
# previous one and nothing else, also through a link to it, keeping its permissions;
# bat/report.py compares two bundles (egl and osmesa: the same images) and names the
# runs only one has; bad --bundle paths are one line, exit 2.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 scenes=$3 source=$4
rm -rf "$work"; mkdir -p "$work"
export OIT_COMMIT=bundle-test-0123abc  # the commit to record (else git describe in the source tree)

# bad paths
touch "$work/a-file"
expect_exit 2 "--bundle .*/a-file: not a directory" -- "$oit" bench --model "$scenes/onion.obj" --bundle "$work/a-file"
mkdir -p "$work/busy" && touch "$work/busy/notes.txt"
expect_exit 2 "--bundle .*/busy: the directory is not empty and not a bundle" -- \
    "$oit" bench --model "$scenes/onion.obj" --bundle "$work/busy"
expect_exit 2 "--bundle .*/no/such/x: the directory .* does not exist" -- \
    "$oit" bench --model "$scenes/onion.obj" --bundle "$work/no/such/x"
expect_exit 2 "--bundle: algorithms 'll' and 'll' would share" -- \
    "$oit" bench --model "$scenes/onion.obj" --algorithms ll,dp,ll --bundle "$work/b"
[ -e "$work/b" ] && fail "a refused bundle left $work/b"
[ "$(cat "$work/busy/notes.txt")" = "" ] && [ "$(ls "$work/busy")" = notes.txt ] || fail "busy/ was touched"

printf 'onion %s/onion.obj\ngear %s/gearbox.obj --orbit 30,20 --alpha 0.4\n' "$scenes" "$scenes" >"$work/scenes.txt"
common=(--scene-list "$work/scenes.txt" --sizes 32,40x24 --frames 2 --warmup 0 --reference-max-pixels 1024 --quiet)
"$oit" bench "${common[@]}" --algorithms ll,blend,wboit --orbit-sequence 2 --bundle "$work/a/" \
    --json "$work/a.json" >"$work/a.out" || fail "bench --bundle a"
[ -s "$work/a.out" ] && fail "--bundle without --csv must not print the CSV"
for run in ll:32x32 ll:40x24 blend:40x24; do
    alg=${run%%:*} s=${run#*:}
    "$oit" render --model "$scenes/gearbox.obj" --orbit 30,20 --alpha 0.4 --algorithm "$alg" --size "$s" \
        --frames 2 --json --out "$work/render_${alg}_$s.png" >"$work/render_${alg}_$s.json" || fail "render"
done
python3 - "$work" "$oit" <<'PY' || fail "bundle contents"
import json, os, subprocess, sys
work, oit = sys.argv[1], sys.argv[2]
bundle_dir = os.path.join(work, "a")
bundle = json.load(open(os.path.join(bundle_dir, "bundle.json")))
for key in ("format", "version", "date", "command", "commit", "machine", "driver", "parameters", "scenes", "results",
            "failures"):
    assert key in bundle, key
assert bundle["commit"] == "bundle-test-0123abc" and bundle["commit_from"] == "OIT_COMMIT", bundle["commit"]
assert bundle["command"][:2] == ["oit", "bench"] and "--bundle" in bundle["command"], bundle["command"]
m = bundle["machine"]
assert m["logical_cpus"] == os.cpu_count() and m["sysname"] == os.uname().sysname and m["cpu"], m
mem_kb = int([l.split()[1] for l in open("/proc/meminfo") if l.startswith("MemTotal:")][0])
assert abs(m["memory_bytes"] - 1024 * mem_kb) <= 0.02 * 1024 * mem_kb, (m["memory_bytes"], mem_kb)
d = bundle["driver"]
assert d["backend"] == "egl" and d["renderer"] and d["gl_version"], d
p = bundle["parameters"]
assert p["sizes"] == [[32, 32], [40, 24]] and p["frames"] == 2 and p["warmup"] == 0 and p["orbit_sequence"] == 2, p
assert [a["label"] for a in p["algorithms"]] == ["ll", "blend", "wboit"] and p["algorithms"][0]["exact"], p
# the model files, checksummed here too (FNV-1a 64)
def fnv1a64(path):
    h = 0xcbf29ce484222325
    for byte in open(path, "rb").read():
        h = ((h ^ byte) * 0x100000001b3) & 0xffffffffffffffff
    return f"{h:016x}"
assert [s["name"] for s in bundle["scenes"]] == ["onion", "gear"], bundle["scenes"]
for s in bundle["scenes"]:
    assert s["model_bytes"] == os.path.getsize(s["model"]) and s["model_fnv1a64"] == fnv1a64(s["model"]), s
    assert [(c["width"], c["height"]) for c in s["cameras"]] == [(32, 32), (40, 24)], s["cameras"]
gear = bundle["scenes"][1]
assert gear["view"] == "--orbit 30,20 --alpha 0.4" and abs(gear["render_options"]["alpha"] - 0.4) < 1e-6, gear
for camera in gear["cameras"]:
    size = f"{camera['width']}x{camera['height']}"
    render = json.load(open(os.path.join(work, f"render_ll_{size}.json")))
    assert camera["modelview"] == render["modelview"] and camera["projection"] == render["projection"], size
# the rows: the same as --json's (timings aside), with their files, which are all there
rows, plain = bundle["results"], json.load(open(os.path.join(work, "a.json")))["results"]
assert len(rows) == 12 == len(plain) and bundle["failures"] == 0, len(rows)
timing = {"cpu_ms", "gpu_ms", "stages"}
files = {"image", "reference_image", "error_map"}
for row, other in zip(rows, plain):
    assert set(row) - files == set(other), set(row) ^ set(other)
    for key in set(other) - timing - {"memory_bytes"}:
        assert row[key] == other[key], (key, row[key], other[key])
    assert files <= set(row), row
    for key in files:
        assert os.path.isfile(os.path.join(bundle_dir, row[key])), row[key]
    assert "error_rmse" in row and "flicker" in row, row
    size = f"{row['width']}x{row['height']}"
    assert row["image"] == f"{row['scene']}_{row['algorithm']}_{size}.png", row["image"]
    assert row["reference_image"] == f"{row['scene']}_{size}.reference.png", row
    assert row["error_map"] == f"{row['scene']}_{row['algorithm']}_{size}.error.png", row
    other_png = os.path.join(work, f"render_{row['algorithm']}_{size}.png")
    if row["scene"] == "gear" and os.path.exists(other_png):  # the last frame: oit render's image of the run
        same = subprocess.run([oit, "compare", os.path.join(bundle_dir, row["image"]), other_png],
                              capture_output=True)
        assert same.returncode == 0, (row["image"], "differs from oit render's")
expected = {r[k] for r in rows for k in files} | {"bundle.json"}
assert set(os.listdir(bundle_dir)) == expected, set(os.listdir(bundle_dir)) ^ expected
print("bundle ok:", len(os.listdir(bundle_dir)), "files,", len(rows), "rows")
PY
[ $? -eq 0 ] || exit 1

# a previous bundle is replaced (its stale files go), and nothing is left beside it
"$oit" bench "${common[@]}" --algorithms ll,blend --bundle "$work/a" || fail "bench --bundle over a previous bundle"
ls "$work/a" | grep -q wboit && fail "the previous bundle's wboit images are still there"
ls -d "$work"/a.tmp.* "$work"/a.old.* 2>/dev/null && fail "temporary directories left beside the bundle"

# a link to a bundle stays a link: the bundle it names is replaced and keeps its permissions
mkdir -p "$work/real"
quick=(--model "$scenes/onion.obj" --sizes 16 --frames 1 --warmup 0 --reference-max-pixels 0 --quiet)
"$oit" bench "${quick[@]}" --algorithms ll --bundle "$work/real/run" || fail "bench --bundle real/run"
chmod 750 "$work/real/run"
ln -s real/run "$work/link"
"$oit" bench "${quick[@]}" --algorithms blend --bundle "$work/link/" || fail "bench --bundle through a link to a bundle"
[ -L "$work/link" ] || fail "a link given as --bundle must stay a link"
[ -f "$work/real/run/onion_blend_16x16.png" ] && [ ! -e "$work/real/run/onion_ll_16x16.png" ] \
    || fail "the bundle the link names was not replaced: $(ls "$work/real/run")"
[ "$(stat -c %a "$work/real/run")" = 750 ] || fail "the replaced bundle must keep its permissions (750)"
ls -d "$work"/*.tmp.* "$work"/*.old.* "$work"/real/*.tmp.* "$work"/real/*.old.* 2>/dev/null \
    && fail "temporary directories left beside the linked bundle"
# a new bundle gets 0777 less the umask, as mkdir would give it
( umask 022 && "$oit" bench "${quick[@]}" --algorithms blend --bundle "$work/fresh" ) || fail "bench --bundle fresh"
[ "$(stat -c %a "$work/fresh")" = 755 ] || fail "a new bundle must be 0777 less the umask (755), not $(stat -c %a "$work/fresh")"
# a link to something that is not a bundle is refused before the work, the link kept
ln -s busy "$work/link-to-busy"
expect_exit 2 "--bundle .*/link-to-busy: the directory is not empty and not a bundle" -- \
    "$oit" bench "${quick[@]}" --algorithms blend --bundle "$work/link-to-busy"

# the same run on the other back end, and a third bundle with other runs
"$oit" bench "${common[@]}" --algorithms ll,blend --bundle "$work/osmesa" --backend osmesa || fail "osmesa bundle"
"$oit" bench "${common[@]}" --scenes gear --algorithms ll,wboit --bundle "$work/third" || fail "third bundle"
python3 "$source/bat/report.py" "$work/a" "$work/osmesa" --out "$work/compare.md" --oit "$oit" >/dev/null \
    || fail "report.py on two bundles"
python3 - "$work" <<'PY' || { cat "$work/compare.md"; fail "comparison of egl and osmesa bundles"; }
import json, os, sys
work = sys.argv[1]
text = open(os.path.join(work, "compare.md")).read()
a, b = (json.load(open(os.path.join(work, d, "bundle.json"))) for d in ("a", "osmesa"))
assert "egl back end" in text and "osmesa back end" in text and a["driver"]["renderer"] in text, text
table = [l for l in text.splitlines() if l.startswith("| ") and "---" not in l]
assert table[0].startswith("| scene | algorithm | size | cpu ms A | cpu ms B | B/A"), table[0]
assert len(table) == 1 + 8, table
for line in table[1:]:
    cells = [c.strip() for c in line.strip("|").split("|")]
    row_a = [r for r in a["results"] if (r["scene"], f"`{r['algorithm']}`", f"{r['width']}x{r['height']}")
             == tuple(cells[:3])][0]
    row_b = [r for r in b["results"] if (r["scene"], f"`{r['algorithm']}`", f"{r['width']}x{r['height']}")
             == tuple(cells[:3])][0]
    cpu_a, cpu_b = row_a["cpu_ms"]["median"], row_b["cpu_ms"]["median"]
    assert cells[3] == f"{cpu_a:.2f}" and cells[4] == f"{cpu_b:.2f}" and cells[5] == f"{cpu_b / cpu_a:.2f}", cells
    assert cells[-2:] == ["0", "0.0000"], ("the back ends' images differ", cells)
assert "8 runs in both; 8 image pairs compared, 8 identical" in text, text
assert "Only in" not in text
print("egl vs osmesa: 8 runs, identical images")
PY
[ $? -eq 0 ] || exit 1
# the Python PNG reader (no oit), and runs in one bundle only
python3 "$source/bat/report.py" "$work/osmesa" "$work/third" --oit none >"$work/third.md" || fail "report.py third"
grep -qF "2 runs in both; 2 image pairs compared, 2 identical" "$work/third.md" || { cat "$work/third.md"; fail "gear ll"; }
grep -A8 "## Only in A" "$work/third.md" | grep -qF -- "- onion \`blend\` 32x32" || fail "runs only in A not listed"
grep -A8 "## Only in B" "$work/third.md" | grep -qF -- "- gear \`wboit\` 40x24" || fail "runs only in B not listed"
if python3 "$source/bat/report.py" "$work/a" "$work/busy" >/dev/null 2>"$work/notbundle.err"; then
    fail "report.py compared a directory that is not a bundle"
fi
grep -q "busy: not a bundle (no bundle.json" "$work/notbundle.err" || fail "no clear message for a non-bundle"
echo "bench bundle ok"
