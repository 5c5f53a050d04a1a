#!/usr/bin/env python3
"""compare_bundles.py: two `oit bench --bundle` directories side by side, as markdown.

    python3 bat/compare_bundles.py BUNDLE_A BUNDLE_B [--out FILE.md] [--oit PATH]
    python3 bat/report.py BUNDLE_A BUNDLE_B [--out FILE.md] [--oit PATH]     (the same)

Prints (or writes to --out) the two machines and drivers, then one row per scene x
algorithm x size: the median CPU and GPU frame times in each and their ratio B/A, the
memory in each, the error against the reference in each (rmse, where the bundle has it),
the flicker where both measured it, and how far the two bundles' images of the run are
apart (largest channel difference and mean, RGB, 0..255): with `oit compare` (--oit PATH,
else $OIT, else build/src/cli/oit, else oit on PATH), or without one (or with --oit none)
by reading the PNGs here (tests/ib_png.py). Runs present in only one bundle, and runs that failed, are listed.
Every figure comes from the bundles' bundle.json and images. Standard library only.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class BundleError(Exception):
    pass


def load_bundle(directory):
    path = os.path.join(directory, "bundle.json")
    if not os.path.isdir(directory):
        raise BundleError(f"{directory}: not a directory")
    if not os.path.isfile(path):
        raise BundleError(f"{directory}: not a bundle (no bundle.json; oit bench --bundle DIR writes one)")
    try:
        with open(path) as f:
            bundle = json.load(f)
    except (OSError, ValueError) as e:
        raise BundleError(f"{path}: cannot read: {e}")
    if bundle.get("format") != "oit-bench-bundle":
        raise BundleError(f"{path}: not an oit bench bundle (format {bundle.get('format')!r})")
    return bundle


def run_key(row):
    return (row["scene"], row["algorithm"], int(row["width"]), int(row["height"]))


def find_oit(given):
    for candidate in (given, os.environ.get("OIT"), os.path.join(ROOT, "build", "src", "cli", "oit")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    return shutil.which("oit")


class ImageDiff:
    """Largest and mean channel difference (RGB) of two PNGs."""

    def __init__(self, oit):
        self.oit = oit
        self.reader = None

    def __call__(self, a, b):
        with open(a, "rb") as fa, open(b, "rb") as fb:
            if fa.read() == fb.read():
                return 0, 0.0
        if self.oit:
            result = subprocess.run([self.oit, "compare", a, b, "--json"], capture_output=True, text=True)
            if result.returncode in (0, 1):
                figures = json.loads(result.stdout)
                return figures["max_channel_diff"], figures["mean_diff"]
            raise BundleError(f"oit compare {a} {b}: {result.stderr.strip()}")
        if self.reader is None:
            sys.path.insert(0, os.path.join(ROOT, "tests"))
            from ib_png import read_png
            self.reader = read_png
        wa, ha, rows_a = self.reader(a)
        wb, hb, rows_b = self.reader(b)
        if (wa, ha) != (wb, hb):
            raise BundleError(f"{a} is {wa}x{ha}, {b} is {wb}x{hb}")
        largest, total = 0, 0
        for ra, rb in zip(rows_a, rows_b):
            for k in range(len(ra)):
                if k % 4 != 3:
                    d = abs(ra[k] - rb[k])
                    total += d
                    largest = max(largest, d)
        return largest, total / (3 * wa * ha)


def fmt(value, digits=2):
    if value is None:
        return "–"
    if isinstance(value, (int, float)) and not isinstance(value, bool) and digits is not None:
        return f"{value:.{digits}f}"
    return str(value)


def mib(value):
    return "–" if value is None else f"{value / (1 << 20):.2f}"


def ratio(a, b):
    return f"{b / a:.2f}" if a and b is not None and a > 0 else "–"


def describe(label, directory, bundle):
    machine, driver = bundle.get("machine", {}), bundle.get("driver", {})
    memory = machine.get("memory_bytes")
    memory_text = f"{memory / (1 << 30):.1f} GiB" if isinstance(memory, (int, float)) and memory > 0 else "?"
    renderer = driver.get("renderer") or "no GL (CPU reference only)"
    return [
        f"- **{label}**: `{directory}`, {bundle.get('date', '?')}, commit `{bundle.get('commit', 'unknown')}`",
        f"  - machine: {machine.get('cpu', '?')}, {machine.get('logical_cpus', '?')} logical CPUs, "
        f"{memory_text}, {machine.get('sysname', '')} {machine.get('release', '')} {machine.get('machine', '')}",
        f"  - driver: {renderer}" + (f", OpenGL {driver['gl_version']}" if driver.get("gl_version") else "")
        + f", {driver.get('backend', '?')} back end",
        "  - command: `" + " ".join(bundle.get("command", [])) + "`",
    ]


def compare(dir_a, dir_b, oit):
    a, b = load_bundle(dir_a), load_bundle(dir_b)
    rows_a = {run_key(r): r for r in a.get("results", [])}
    rows_b = {run_key(r): r for r in b.get("results", [])}
    diff = ImageDiff(oit)
    lines = ["# Bench bundles compared", ""]
    lines += describe("A", dir_a, a) + describe("B", dir_b, b)
    params_a, params_b = a.get("parameters", {}), b.get("parameters", {})
    changed = [k for k in ("frames", "warmup", "time_budget_s", "orbit_sequence", "orbit_step_degrees")
               if params_a.get(k) != params_b.get(k)]
    if changed:
        lines += ["", "The two ran with different parameters: " + ", ".join(
            f"{k} {params_a.get(k)} (A) / {params_b.get(k)} (B)" for k in changed) + "."]
    models_a = {s["name"]: s.get("model_fnv1a64") for s in a.get("scenes", [])}
    models_b = {s["name"]: s.get("model_fnv1a64") for s in b.get("scenes", [])}
    other_models = sorted(n for n in models_a if n in models_b and models_a[n] != models_b[n])
    if other_models:
        lines += ["", "Scenes whose model file differs (FNV-1a 64 checksum): " + ", ".join(other_models) + "."]
    flicker = any("flicker" in r for r in list(rows_a.values()) + list(rows_b.values()))
    header = ["scene", "algorithm", "size", "cpu ms A", "cpu ms B", "B/A", "gpu ms A", "gpu ms B", "B/A",
              "memory MiB A", "memory MiB B", "rmse A", "rmse B"]
    if flicker:
        header += ["flicker A", "flicker B"]
    header += ["image A vs B: max", "mean"]
    lines += ["", "## Runs in both", "", "| " + " | ".join(header) + " |",
              "|" + "|".join(" --- " if k < 3 else " ---: " for k in range(len(header))) + "|"]
    both = [k for k in rows_a if k in rows_b]
    identical = compared = 0
    largest = 0
    failed = []
    for key in both:
        ra, rb = rows_a[key], rows_b[key]
        scene, algorithm, width, height = key
        cells = [scene, f"`{algorithm}`", f"{width}x{height}"]
        if "error" in ra or "error" in rb:
            failed += [f"- {scene} `{algorithm}` {width}x{height} in {label}: {r['error']}"
                       for label, r in (("A", ra), ("B", rb)) if "error" in r]
            cells += ["failed" if "error" in ra else fmt(ra["cpu_ms"]["median"]),
                      "failed" if "error" in rb else fmt(rb["cpu_ms"]["median"])]
            cells += ["–"] * (len(header) - len(cells))
            lines.append("| " + " | ".join(cells) + " |")
            continue
        cpu_a, cpu_b = ra["cpu_ms"]["median"], rb["cpu_ms"]["median"]
        gpu_a, gpu_b = ra["gpu_ms"]["median"], rb["gpu_ms"]["median"]
        cells += [fmt(cpu_a), fmt(cpu_b), ratio(cpu_a, cpu_b), fmt(gpu_a), fmt(gpu_b), ratio(gpu_a, gpu_b),
                  mib(ra.get("memory_bytes")), mib(rb.get("memory_bytes")),
                  fmt(ra.get("error_rmse"), 3), fmt(rb.get("error_rmse"), 3)]
        if flicker:
            cells += [fmt(ra.get("flicker"), 4), fmt(rb.get("flicker"), 4)]
        if ra.get("image") and rb.get("image"):
            image_a, image_b = os.path.join(dir_a, ra["image"]), os.path.join(dir_b, rb["image"])
            if os.path.isfile(image_a) and os.path.isfile(image_b):
                most, mean = diff(image_a, image_b)
                compared += 1
                identical += most == 0
                largest = max(largest, most)
                cells += [str(most), f"{mean:.4f}"]
            else:
                missing = image_a if not os.path.isfile(image_a) else image_b
                cells += [f"missing {os.path.basename(missing)}", "–"]
        else:
            cells += ["no image", "–"]
        lines.append("| " + " | ".join(cells) + " |")
    lines += ["", f"{len(both)} runs in both; {compared} image pairs compared, {identical} identical"
              + (f", largest channel difference {largest}." if compared else ".")]
    if failed:
        lines += ["", "## Failed runs", ""] + failed
    for label, mine, theirs in (("A", rows_a, rows_b), ("B", rows_b, rows_a)):
        alone = [k for k in mine if k not in theirs]
        if alone:
            lines += ["", f"## Only in {label}", ""]
            lines += [f"- {s} `{alg}` {w}x{h}" for s, alg, w, h in alone]
    return "\n".join(lines) + "\n"


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("bundle_a")
    parser.add_argument("bundle_b")
    parser.add_argument("--out", help="write the markdown here instead of stdout")
    parser.add_argument("--oit", help="the oit whose `compare` measures the image differences ('none': read "
                                      "the PNGs in Python)")
    args = parser.parse_args(argv)
    try:
        text = compare(args.bundle_a, args.bundle_b, None if args.oit == "none" else find_oit(args.oit))
    except BundleError as e:
        print(f"compare_bundles: error: {e}", file=sys.stderr)
        return 2
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        print(args.out)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
