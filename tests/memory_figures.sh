#!/usr/bin/env bash
# memory_figures.sh OIT WORK MODEL BACKEND|reference: the memory figures
# against what was really allocated, never against the formula that made them.
#
# BACKEND (egl, osmesa): for every GPU algorithm (and the variants that
# allocate more targets), memory_bytes must equal gl_allocated_bytes, which
# `oit render --json` counts by enumerating the GL objects that exist after
# the frame and did not before the algorithm was created
# (oit_gl_enumerate_allocated_bytes: GL_BUFFER_SIZE and texture level sizes
# from the component sizes GL reports; it knows nothing of the algorithms'
# tracker). Then, from those enumerated bytes alone:
# - per pixel: two image sizes (same pool) give the bytes per pixel, which
#   bytes_per_pixel must equal; algorithms without a pool hold nothing else;
# - per fragment (ll, ib, adaptive: those reading --fragment-pool): two pool capacities that both hold the frame give
#   the bytes per fragment, which bytes_per_fragment must equal; a pool forced
#   small (--fragment-pool) must grow, and the memory must rise by at least
#   (fragments - initial capacity) x those bytes over what the small pool held.
# reference: memory_bytes against the CPU arrays' sizes from their layouts
# (fragments x 28 + pixels x 16 + 8 + vertices x 80, vertices from
# `oit info`), and the per-fragment and per-pixel bytes solved from three
# renders with different fragment and pixel counts.
source "$(dirname "$0")/lib.sh"
oit=$1 work=$2 model=$3 mode=$4
rm -rf "$work"; mkdir -p "$work"

shared_header="$(cd "$(dirname "$0")/.." && pwd)/shaders/common/oit_shared.h"
python3 - "$oit" "$work" "$model" "$mode" "$shared_header" <<'PY' || fail "memory figures ($mode)"
import json, re, subprocess, sys

oit, work, model, mode = sys.argv[1:5]
# every GPU algorithm holds the frame's parameter block beside its targets
FRAME_BLOCK = int(re.search(r"#define OIT_FRAME_BLOCK_BYTES (\d+)", open(sys.argv[5]).read()).group(1))
failures = []


def check(ok, message):
    print(("ok:   " if ok else "FAIL: ") + message)
    if not ok:
        failures.append(message)


def render(algorithm, size, *args):
    command = [oit, "render", "--model", model, "--algorithm", algorithm, "--size", size,
               "--json", *args]
    if mode != "reference":
        command += ["--backend", mode]
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    if run.returncode != 0:
        sys.exit(f"render failed ({run.returncode}): {' '.join(command)}\n{run.stderr}")
    return json.loads(run.stdout)


def pixels(size):
    w, h = size.split("x")
    return int(w) * int(h)


if mode == "reference":
    info = subprocess.run([oit, "info", "--model", model, "--json"], capture_output=True,
                          text=True, check=True)
    vertices = json.loads(info.stdout)["vertices"]
    # the reference's arrays (alg_reference.c): per fragment depth, triangle,
    # rgb[3], alpha, local (7 x 4 bytes); per vertex clip[4], eye[3], normal[3]
    # (10 doubles); per pixel the RGBA8 output, a uint32 count and a uint64
    # offset, and one more offset at the end.
    FRAGMENT, VERTEX, PIXEL, EXTRA = 7 * 4, 10 * 8, 4 + 4 + 8, 8
    runs = [("64x64", ()), ("128x128", ()), ("128x128", ("--orbit", "40,25"))]
    results = []
    for size, args in runs:
        d = render("reference", size, *args)
        expected = d["fragments"] * FRAGMENT + pixels(size) * PIXEL + EXTRA + vertices * VERTEX
        check(d["memory_bytes"] == expected,
              f"reference {size} {' '.join(args)}: memory_bytes {d['memory_bytes']} == "
              f"{d['fragments']} fragments x {FRAGMENT} + {pixels(size)} pixels x {PIXEL} + "
              f"{EXTRA} + {vertices} vertices x {VERTEX} = {expected}")
        results.append((pixels(size), d))
    # the two 128x128 renders differ in fragments only, the first two in both
    (p1, a), (p2, b), (p3, c) = results
    if c["fragments"] == b["fragments"]:
        sys.exit("the orbit did not change the fragment count; pick another view")
    per_fragment = (c["memory_bytes"] - b["memory_bytes"]) / (c["fragments"] - b["fragments"])
    per_pixel = (b["memory_bytes"] - a["memory_bytes"] -
                 per_fragment * (b["fragments"] - a["fragments"])) / (p2 - p1)
    for d, p in ((a, p1), (b, p2), (c, p3)):
        check(d["bytes_per_fragment"] == per_fragment,
              f"reference: bytes_per_fragment {d['bytes_per_fragment']} == {per_fragment} "
              "(memory difference per fragment between two views)")
        check(abs(d["bytes_per_pixel"] - (per_pixel + EXTRA / p)) < 1e-3,
              f"reference: bytes_per_pixel {d['bytes_per_pixel']} == {per_pixel} + {EXTRA}/{p} "
              "(memory difference per pixel between two sizes)")
else:
    SIZE, SMALL = "128x128", "64x64"
    # every GPU algorithm the build has (`oit algorithms --json`, so a new one is checked
    # without a line here), and the variants that allocate more or other targets
    listed = json.loads(subprocess.run([oit, "algorithms", "--json"], capture_output=True, text=True,
                                       check=True).stdout)
    gpu_algorithms = [(a["name"],) for a in listed if a["uses_gl"]]
    # the algorithms with a fragment pool (ll, ib, adaptive on ll's lists): those reading --fragment-pool
    pooled = [a["name"] for a in listed if a["uses_gl"] and "--fragment-pool" in a.get("options", [])]
    check({"ll", "ib"} <= set(pooled), f"ll and ib read --fragment-pool ({pooled})")
    check(len(gpu_algorithms) >= 10, f"oit algorithms --json lists {len(gpu_algorithms)} GPU algorithms")
    variants = gpu_algorithms + [
                ("ll", "--sort", "array"), ("dp", "--modulation", "distance"),
                ("dp", "--modulation", "dist-curv"), ("ddp", "--modulation", "distance"),
                ("ll", "--modulation", "distance"), ("ib", "--modulation", "fields"),
                ("ll", "--frames", "3"), ("ib", "--frames", "3"),
                ("kbuffer", "--layers", "3"), ("hybrid", "--layers", "64"),
                ("mboit", "--moments", "power6"), ("mboit", "--moments", "trig3"),
                ("wavelet", "--wavelet-rank", "1"), ("wavelet", "--wavelet-rank", "2"),
                ("mlab", "--layers", "4"), ("mlab", "--frames", "3")]
    figures = {}
    for algorithm, *args in variants:
        d = render(algorithm, SIZE, *args)
        label = " ".join([algorithm, *args])
        check("gl_allocated_bytes" in d and d["memory_bytes"] == d["gl_allocated_bytes"],
              f"{label}: memory_bytes {d['memory_bytes']} == GL objects' bytes "
              f"{d.get('gl_allocated_bytes')}")
        figures.setdefault(algorithm, d)
    fragments = figures["ll"]["fragments"]
    check(fragments == figures["ib"]["fragments"] and fragments > 1000,
          f"ll and ib store the same fragments ({fragments})")

    # per pixel: two image sizes, the pool (ll, ib) fixed and big enough for both
    pool = ("--fragment-pool", str(2 * fragments))
    for algorithm, *variant in gpu_algorithms + [("mboit", "--moments", "power6"), ("mboit", "--moments", "trig3"),
                                                 ("wavelet", "--wavelet-rank", "1"), ("wavelet", "--wavelet-rank", "2")]:
        args = pool if algorithm in pooled else tuple(variant)
        big, small = render(algorithm, SIZE, *args), render(algorithm, SMALL, *args)
        if algorithm in pooled:
            check(big["overflow_retries"] == 0 and small["overflow_retries"] == 0,
                  f"{algorithm}: the pool of {2 * fragments} holds both sizes")
        for d in (big, small):
            check(d["memory_bytes"] == d["gl_allocated_bytes"],
                  f"{algorithm} {d['width']}x{d['height']}: memory_bytes == GL objects' bytes")
        per_pixel = ((big["gl_allocated_bytes"] - small["gl_allocated_bytes"]) /
                     (pixels(SIZE) - pixels(SMALL)))
        for d in (big, small):
            check(d["bytes_per_pixel"] == per_pixel,
                  f"{algorithm} {d['width']}x{d['height']}: bytes_per_pixel "
                  f"{d['bytes_per_pixel']} == {per_pixel:g} (GL bytes per pixel between two sizes)")
        if algorithm == "mboit": # b0 4, moments 16, (power6, trig3: 8 more), accumulation 16, output 4
            want = 48 if variant else 40
            check(per_pixel == want, f"mboit {' '.join(variant)}: {per_pixel:g} bytes per pixel == {want}")
        if algorithm == "wavelet": # b0 4, 2^(R+1) coefficients of 4 (rank R, default 3), accumulation 16, output 4
            rank = int(variant[1]) if variant else 3
            want = 4 + 4 * 2 ** (rank + 1) + 16 + 4
            check(per_pixel == want, f"wavelet rank {rank}: {per_pixel:g} bytes per pixel == {want}")
        if algorithm in ("kbuffer", "hybrid"):  # per pixel, and 69 counters
            check(big["gl_allocated_bytes"] == pixels(SIZE) * per_pixel + 69 * 4 + FRAME_BLOCK,
                  f"{algorithm}: everything it holds is per pixel (output included) but its counters "
                  f"and the frame block")
        elif algorithm == "mlab":
            # per pixel k = 8 layers of 16 bytes, count, lock and output (4 each), and a
            # fixed block of counters (the same at both sizes, by the subtraction above)
            check(per_pixel == 8 * 16 + 12, f"mlab: {per_pixel:g} GL bytes per pixel == 8 x 16 + 12")
            fixed = big["gl_allocated_bytes"] - pixels(SIZE) * per_pixel - FRAME_BLOCK
            check(0 < fixed <= 64, f"mlab: {fixed:g} bytes beside the per-pixel ones and the frame block "
                                   f"(its counters)")
        elif algorithm not in pooled:
            check(big["gl_allocated_bytes"] == pixels(SIZE) * per_pixel + FRAME_BLOCK,
                  f"{algorithm}: everything it holds is per pixel (output included) but the frame block")

    # per fragment: two pool capacities that both hold the frame
    for algorithm in pooled:
        c1, c2 = fragments + 1000, fragments + 6000
        one = render(algorithm, SIZE, "--fragment-pool", str(c1))
        two = render(algorithm, SIZE, "--fragment-pool", str(c2))
        check(one["overflow_retries"] == 0 and two["overflow_retries"] == 0,
              f"{algorithm}: pools of {c1} and {c2} hold {fragments} fragments")
        per_fragment = (two["gl_allocated_bytes"] - one["gl_allocated_bytes"]) / (c2 - c1)
        check(per_fragment == int(per_fragment) and per_fragment > 0,
              f"{algorithm}: {per_fragment:g} GL bytes per pool fragment, a whole number")
        for d, c in ((one, c1), (two, c2)):
            check(d["bytes_per_fragment"] == per_fragment,
                  f"{algorithm} pool {c}: bytes_per_fragment {d['bytes_per_fragment']} == "
                  f"{per_fragment:g} (GL bytes between two capacities)")
        rest = one["gl_allocated_bytes"] - c1 * per_fragment  # pixels, counters, tables
        # a pool forced small must grow, and the growth must show
        initial = 1000
        forced = render(algorithm, SIZE, "--fragment-pool", str(initial))
        check(forced["overflow_retries"] == 1 and forced["fragments"] == fragments,
              f"{algorithm}: a pool of {initial} grows once and keeps all {fragments} fragments")
        check(forced["memory_bytes"] == forced["gl_allocated_bytes"],
              f"{algorithm} grown: memory_bytes {forced['memory_bytes']} == GL objects' bytes "
              f"{forced['gl_allocated_bytes']}")
        before = rest + initial * per_fragment
        growth = forced["gl_allocated_bytes"] - before
        check(growth >= (fragments - initial) * per_fragment,
              f"{algorithm}: grown by {growth:.0f} bytes >= ({fragments} - {initial}) x "
              f"{per_fragment:g} = {(fragments - initial) * per_fragment:.0f}")
        capacity = (forced["memory_bytes"] - rest) / per_fragment
        check(capacity == int(capacity) and capacity >= fragments,
              f"{algorithm}: memory_bytes counts the grown pool at its capacity "
              f"({capacity:.0f} fragments, headroom {capacity - fragments:.0f})")

if failures:
    sys.exit(f"{len(failures)} check(s) failed")
PY
echo "memory figures ok ($mode)"
