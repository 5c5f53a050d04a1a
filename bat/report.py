#!/usr/bin/env python3
"""report.py: turns the benchmark's CSV and result files into docs/benchmarks.md.

Reads RESULTS/bench.csv (+ bench.json: renderer, back end, command), machine.json (the
machine the benchmark ran on, written by bat/run_comparison.sh with `bat/pages.py machine`),
accuracy.csv, sorts.json (ll's four sorts), quality.json/stability.json/depth_sweep.json (the
cost/quality map, bat/quality_map.py, with docs/data/published_*.csv), the result files of
bat/measure_*.sh, and the thesis's figures from SHARED
(../shared beside the repository): its tables in data/*.csv, and from the thesis's and the
paper's text (sources/) the figures no table holds (tables B.1-B.2, the GPU, the bytes per
fragment). Writes DOCS/benchmarks.md and DOCS/images/bench-*.png (matplotlib). Every figure
and every statement about the machine on the page is computed from these inputs. Run by
bat/run_comparison.sh; by hand:

    python3 bat/report.py --results build/bench/results [--docs docs] [--shared ../shared]

Given two `oit bench --bundle` directories instead, it compares them (bat/compare_bundles.py):

    python3 bat/report.py BUNDLE_A BUNDLE_B [--out FILE.md] [--oit PATH]
"""
import argparse
import csv
import datetime
import json
import math
import os
import re
import statistics
import sys

if __name__ == "__main__" and len(sys.argv) > 2 and not sys.argv[1].startswith("-") \
        and not sys.argv[2].startswith("-"):
    # report.py BUNDLE_A BUNDLE_B: two `oit bench --bundle` directories compared (no matplotlib needed)
    from compare_bundles import main as compare_bundles_main
    sys.exit(compare_bundles_main(sys.argv[1:]))

from pages import commit_of, software_renderer  # noqa: E402

try:
    import matplotlib
except ImportError:
    # Debian's python3-matplotlib belongs to /usr/bin/python3; another python3 (pyenv,
    # a virtualenv) first on PATH does not see it
    system_python = "/usr/bin/python3"
    if os.path.exists(system_python) and os.path.realpath(sys.executable) != os.path.realpath(system_python):
        os.execv(system_python, [system_python] + sys.argv)
    sys.exit("report: matplotlib is missing: install python3-matplotlib (config/debian-packages.txt)")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_data import (  # noqa: E402
    ROOT,
    SHARED,
    read_csv,
    stages_of,
    stage_sum,
    HISTOGRAM_BINS,
    scene_histogram,
    histogram_quantile,
    number,
    read_measure,
    missing_shared,
    decimal,
    text_tables,
    Thesis,
    sizes_text,
    frames_text,
    tests_bound,
    fmt,
    compact,
    table,
    spearman,
    spread,
    spread_text)
ALGORITHMS = ["blend", "dp", "ddp", "ll", "ll-array", "ib", "wboit"]
IB_CONSTRUCTION = ("clear", "fill", "sort", "neighbours")  # prefixes: clear_retry, fill_retry too
# The targets: ll/blend frame time, dp/ll where the longest list reaches deep_list,
# ib construction / ll, ib bytes per fragment
TARGETS = {"ll_blend": 2.0, "dp_ll": 3.0, "deep_list": 16, "ib_ll": 2.0, "ib_bytes": 64.0}


# ----------------------------------------------------------------- report

class Report:
    def __init__(self, args):
        self.args = args
        self.lines = []
        self.images = os.path.join(args.docs, "images")
        os.makedirs(self.images, exist_ok=True)
        self.bench = [r for r in read_csv(os.path.join(args.results, "bench.csv"))]
        if not self.bench:
            sys.exit(f"report: {args.results}/bench.csv is missing or empty: run bat/run_comparison.sh")
        meta_path = os.path.join(args.results, "bench.json")
        self.meta = {}
        if os.path.exists(meta_path):
            try:
                self.meta = json.load(open(meta_path))
            except json.JSONDecodeError:
                self.meta = {}
        self.ok = [r for r in self.bench if not r["error"]]
        self.failed = [r for r in self.bench if r["error"]]
        self.scenes = list(dict.fromkeys(r["scene"] for r in self.bench))
        self.algorithms = [a for a in ALGORITHMS if any(r["algorithm"] == a for r in self.bench)]
        self.by = {(r["scene"], r["algorithm"]): r for r in self.ok}
        profile_path = os.path.join(args.results, "profile.txt")
        self.profile = open(profile_path).read().strip() if os.path.exists(profile_path) else ""
        # the machine the benchmark ran on, measured then (bat/run_comparison.sh), not the one reporting
        machine_path = os.path.join(args.results, "machine.json")
        self.machine = json.load(open(machine_path)) if os.path.exists(machine_path) else {}
        self.renderer = self.meta.get("renderer") or self.machine.get("renderer") or "?"
        self.software = software_renderer(self.renderer)
        self.thesis = Thesis(args.shared)
        self.tolerance = tests_bound("EXACT_TOLERANCE")
        self.mismatch = tests_bound("EXACT_MISMATCH")

    def renderer_name(self):
        """'llvmpipe' of 'llvmpipe (LLVM 15.0.6, 256 bits)': for titles."""
        return self.renderer.split(" (")[0]

    def machine_text(self):
        m = self.machine
        if not m:
            return (f"not recorded ({os.path.join(self.args.results, 'machine.json')} is missing: "
                    f"bat/run_comparison.sh writes it); the kernel: {self.meta.get('machine', '?')}")
        return (f"{m.get('cpu', '?')}, {m.get('logical_cpus', '?')} logical CPUs"
                + (" (a virtual machine)" if m.get("virtual_machine") else "") + f", {m.get('kernel', '?')}")

    def commit_text(self):
        """The commit of the oit that measured (machine.json), and of this script when it differs."""
        measured, reporting = self.machine.get("commit"), commit_of(__file__)
        if not measured:
            return f"at commit {reporting} (report; the benchmark's commit not recorded: no machine.json)"
        return f"at commit {measured}" + (f" (benchmark) / {reporting} (report)" if measured != reporting else "")

    def gpu_text(self):
        if self.renderer == "?":
            return "GPU unknown (no renderer recorded)"
        return "no GPU" if self.software else "on the GPU"

    def timing_text(self):
        """How the stages were timed and what the machine adds to it: from the renderer and machine.json."""
        name = self.renderer_name()
        cpus = self.machine.get("logical_cpus")
        if self.software:
            text = (f"**Timing on {name}.** Its `GL_TIME_ELAPSED` queries do not measure the work, so every stage "
                    "is timed as wall time between `glFinish()` calls (the \"GPU\" columns), and the frame time is "
                    "the wall time of the whole frame. Ratios measured in the same run are what carry over to a GPU; "
                    "absolute times do not.")
            if cpus and name == "llvmpipe":
                threads = self.machine.get("lp_num_threads")
                text += (f" The machine has {cpus} logical CPUs, so llvmpipe runs "
                         + (f"{threads} threads (LP_NUM_THREADS)." if threads
                            else f"{min(cpus, 32)} threads (one per CPU, at most 32)."))
            elif cpus:
                text += f" The machine has {cpus} logical CPUs."
        else:
            text = (f"**Timing on {name}.** Every stage is timed by `GL_TIME_ELAPSED` queries (the \"GPU\" "
                    "columns), and the frame time is the wall time of the whole frame on the CPU."
                    + (f" The machine has {cpus} logical CPUs." if cpus else ""))
        return text + " " + self.spread_text()

    def spread_text(self):
        """How much one scene's frame times moved between its measured frames, in this run."""
        spreads = []
        for r in self.ok:
            lo, hi, median = (number(r.get(k)) for k in ("cpu_ms_min", "cpu_ms_max", "cpu_ms_median"))
            if (number(r.get("frames")) or 0) >= 2 and median and lo is not None and hi is not None:
                spreads.append(((hi - lo) / median, r, lo, hi))
        if not spreads:
            return "Each run measured one frame, so this run shows nothing of how much a frame's time varies."
        worst = max(spreads, key=lambda x: x[0])
        where = "On this virtual machine" if self.machine.get("virtual_machine") else "On this machine"
        return (f"{where} a scene's frame times varied between its measured frames by up to "
                f"{100 * worst[0]:.0f}% of their median ({worst[1]['scene']}'s `{worst[1]['algorithm']}`: "
                f"{worst[2]:.1f} to {worst[3]:.1f} ms)"
                + (f", by {100 * statistics.median(x[0] for x in spreads):.0f}% in the median over the "
                   f"{len(spreads)} runs" if len(spreads) > 1 else "") + "; the tables give medians.")

    def row(self, scene, algorithm):
        return self.by.get((scene, algorithm))

    def value(self, scene, algorithm, key):
        r = self.row(scene, algorithm)
        return number(r[key]) if r else None

    def ib_construction(self, scene):
        r = self.row(scene, "ib")
        return stage_sum(stages_of(r), IB_CONSTRUCTION) if r else None

    def emit(self, *lines):
        self.lines.extend(lines)

    def save(self, fig, name):
        path = os.path.join(self.images, f"bench-{name}.png")
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        rel = os.path.relpath(path, self.args.docs)
        return f"![{name}]({rel})"

    # ------------------------------------------------------------ sections

    def header(self):
        a = self.args
        size = f"{self.bench[0]['width']}x{self.bench[0]['height']}"
        frames = self.meta.get("frames", "?")
        self.emit("# Benchmarks: the algorithms compared on real models", "",
                  f"Generated by `{a.command}` (then `python3 bat/report.py`) {self.commit_text()}; do not edit "
                  "by hand. "
                  "How to run it and what each figure means: [cli.md](cli.md#oit-bench) and the end of this page.",
                  "",
                  f"- **Date**: {self.meta.get('date', datetime.datetime.utcnow().isoformat(timespec='seconds') + 'Z')}"
                  + (f"; the whole run took {int(a.elapsed) // 60} min" if a.elapsed else ""),
                  f"- **Machine**: {self.machine_text()}",
                  f"- **Driver**: {self.renderer}"
                  + (f" (Mesa {self.machine['mesa']})" if self.machine.get("mesa") else "") + ", "
                  f"{self.meta.get('backend', '?')} back end, {self.gpu_text()}",
                  f"- **Command**: `{self.meta.get('command', '?')}`",
                  f"- **Measured**: {len(self.scenes)} scenes × {len(self.algorithms)} algorithms at {size}, "
                  f"{self.meta.get('warmup', '?')} warm-up frame(s) then up to {frames} measured frames each, "
                  "reported as medians" + (f" (a run stops after {self.meta['time_budget_s']:g} s of measured frames "
                                           "once it has 3)" if self.meta.get("time_budget_s") else ""),
                  "")
        if "--quick" in a.command:
            self.emit("> **A quick run** (the config's quick models at a small size, few frames): a smoke test of "
                      "the pipeline, not the comparison. `bat/run_comparison.sh` without `--quick` measures every "
                      "scene at the full size and replaces this page.", "")
        self.emit(self.timing_text(), "")
        if self.failed:
            self.emit(f"**{len(self.failed)} run(s) failed** and are left out of the tables:", "")
            for r in self.failed:
                self.emit(f"- {r['scene']} {r['algorithm']}: {r['error']}")
            self.emit("")

    def targets(self):
        ll_blend = [self.value(s, "ll", "cpu_ms_median") / self.value(s, "blend", "cpu_ms_median")
                    for s in self.scenes if self.value(s, "ll", "cpu_ms_median") and self.value(s, "blend", "cpu_ms_median")]
        deep = [s for s in self.scenes if (self.value(s, "ll", "max_list") or 0) >= TARGETS["deep_list"]]
        dp_ll = {s: self.value(s, "dp", "cpu_ms_median") / self.value(s, "ll", "cpu_ms_median")
                 for s in deep if self.value(s, "dp", "cpu_ms_median") and self.value(s, "ll", "cpu_ms_median")}
        ib_ll = {s: self.ib_construction(s) / self.value(s, "ll", "gpu_ms_median")
                 for s in self.scenes if self.ib_construction(s) and self.value(s, "ll", "gpu_ms_median")}
        ib_bytes = [self.value(s, "ib", "bytes_per_fragment") for s in self.scenes if self.value(s, "ib", "bytes_per_fragment")]
        self.ratios = {"ll_blend": ll_blend, "dp_ll": dp_ll, "ib_ll": ib_ll}
        rows = []

        def verdict(ok, text):
            return ("**met**" if ok else "**missed**") + f" ({text})"

        t = TARGETS
        if ll_blend:
            m = statistics.median(ll_blend)
            rows.append([f"`ll` frame time ≤ {t['ll_blend']:.1f} × `blend` (median over the scenes)", f"{m:.2f}×",
                         verdict(m <= t["ll_blend"], f"{m / t['ll_blend'] * 100 - 100:+.0f}% against the target")])
        if dp_ll:
            worst = min(dp_ll, key=dp_ll.get)
            rows.append([f"`ll` ≥ {t['dp_ll']:g} × faster than `dp` where the longest list ≥ {t['deep_list']} "
                         f"({len(dp_ll)} scenes)",
                         f"lowest {dp_ll[worst]:.2f}× ({worst}), median {statistics.median(dp_ll.values()):.2f}×",
                         verdict(dp_ll[worst] >= t["dp_ll"],
                                 f"{sum(v >= t['dp_ll'] for v in dp_ll.values())} of {len(dp_ll)} scenes at "
                                 f"{t['dp_ll']:g}× or more")])
        if ib_ll:
            worst = max(ib_ll, key=ib_ll.get)
            theirs = self.thesis.ib_ll()
            rows.append([f"`ib` construction (fill, sort, neighbours) ≤ {t['ib_ll']:.1f} × `ll` on every scene",
                         f"median {statistics.median(ib_ll.values()):.2f}×, worst {ib_ll[worst]:.2f}× ({worst})",
                         verdict(ib_ll[worst] <= t["ib_ll"],
                                 f"{sum(v <= t['ib_ll'] for v in ib_ll.values())} of {len(ib_ll)} scenes within; "
                                 f"the worst is {ib_ll[worst] / t['ib_ll']:.1f}× the target; the thesis: median "
                                 f"{statistics.median(theirs):.2f}, worst {max(theirs):.2f}")])
        if ib_bytes:
            rows.append([f"`ib` memory ≤ {t['ib_bytes']:.0f} bytes per fragment", f"{max(ib_bytes):.0f} bytes",
                         verdict(max(ib_bytes) <= t["ib_bytes"],
                                 f"the thesis: {self.thesis.bytes_per_fragment} bytes")])
        self.emit("## Targets", "", *table(["target (issue)", "measured", "verdict"], rows, ["---", "---", "---"]), "")
        self.target_rows = rows

    def scenes_table(self):
        rows = []
        for s in self.scenes:
            ll = self.row(s, "ll") or {}
            rows.append([s, fmt(number(ll.get("vertices")), 0), fmt(number(ll.get("triangles")), 0),
                         fmt(number(ll.get("fragments")), 0), fmt(number(ll.get("max_list")), 0),
                         fmt(100 * number(ll.get("psi"), float("nan")), 2), fmt(number(ll.get("mean_list")), 2)])
        self.emit("## Scenes", "",
                  self.views_text() + " Models and views: "
                  "[config/bench-scenes.json](../config/bench-scenes.json). Figures from `ll` at the bench size; "
                  "Ψ is the share of non-empty pixels whose list is longer than 2/3 of the longest (the thesis's "
                  "\"worst third\"), in percent.", "",
                  *table(["scene", "vertices", "triangles", "fragments", "longest list", "Ψ %", "mean list"], rows), "")

    def depth_complexity(self):
        """Per scene, the histogram of list lengths (fragments per pixel) at the bench size: from the
        reference's scene_histogram when bench rendered it, else the exact algorithms' list_histogram."""
        found = []
        for s in self.scenes:
            rows = [r for r in self.bench if r["scene"] == s]
            h, source = scene_histogram(rows)
            if h:
                found.append((s, h, source, rows[0]))
        if not found:
            return  # a bench.csv from before the histogram columns, or no exact algorithm ran
        rows = []
        for s, h, source, r in found:
            pixels = sum(h)
            lit = pixels - h[0]
            fragments = sum(i * c for i, c in enumerate(h))
            rows.append([s, f"{r['width']}×{r['height']}", f"`{source}`", fmt(100 * lit / pixels, 1),
                         fmt(fragments / lit if lit else None, 2)
                         + ("+" if h[-1] else ""),
                         fmt(histogram_quantile(h, 0.5), 0), fmt(histogram_quantile(h, 0.9), 0),
                         fmt(histogram_quantile(h, 0.99), 0), fmt(h[-1], 0)])
        columns = min(4, len(found))
        lines = (len(found) + columns - 1) // columns
        fig, axes = plt.subplots(lines, columns, figsize=(3.2 * columns, 2.2 * lines), squeeze=False)
        for k, (s, h, source, r) in enumerate(found):
            ax = axes[k // columns][k % columns]
            last = max((i for i, c in enumerate(h) if c), default=1)
            xs = list(range(1, max(last, 1) + 1))
            ax.bar(xs, [h[i] for i in xs], width=1.0, color=["C3" if i == HISTOGRAM_BINS - 1 else "C0" for i in xs])
            ax.set_yscale("log")
            ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
            ax.set_title(s, fontsize=8)
            ax.tick_params(labelsize=7)
            if k % columns == 0:
                ax.set_ylabel("pixels (log)", fontsize=7)
            if k // columns == lines - 1:
                ax.set_xlabel("fragments per pixel", fontsize=7)
        for k in range(len(found), lines * columns):
            axes[k // columns][k % columns].axis("off")
        fig.suptitle("Depth complexity: pixels per list length (empty pixels left out; red: 64 or more)",
                     fontsize=9)
        fig.tight_layout()
        self.emit("## Depth complexity per scene", "",
                  "How many fragments each pixel's list holds, at the bench size: the axis the OIT papers "
                  "plot quality and cost against. From `oit bench`'s `scene_histogram` (the CPU reference's "
                  "frame) where it rendered the reference, else the `list_histogram` of the exact algorithm "
                  "named (`ll`'s lists; [cli.md](cli.md#oit-bench)). Covered: the share of pixels with at "
                  "least one fragment; mean: fragments per covered pixel (`+`: some lists are in the open "
                  "bin of 64 or more, counted as 64); p50, p90, p99: the list length that half, 90% and 99% "
                  "of the covered pixels do not exceed; ≥ 64: pixels in the open bin.", "",
                  *table(["scene", "size", "from", "covered %", "mean", "p50", "p90", "p99", "≥ 64"], rows), "",
                  self.save(fig, "depth-complexity"), "")

    def views_text(self):
        """How many views of each model the run measured (bench.csv's model and scene columns), beside the
        thesis's (its tables name a scene 'Model N')."""
        per_model = {}
        for r in self.bench:
            per_model.setdefault(r["model"], set()).add(r["scene"])
        counts = sorted({len(v) for v in per_model.values()})
        views = sorted({s.rsplit("-", 1)[-1] for s in self.scenes})
        theirs = {}
        for r in self.thesis.tables["comparison"]:
            theirs.setdefault(r["model"].rsplit(" ", 1)[0], set()).add(r["model"])
        their_counts = {len(v) for v in theirs.values()}
        words = {1: "one view", 2: "two views", 3: "three views", 4: "four views"}
        if len(counts) == 1:
            text = f"Every model in {words.get(counts[0], f'{counts[0]} views')}"
        else:
            text = f"The models in {counts[0]} to {counts[-1]} views"
        if their_counts == set(counts):
            text += ", as the thesis measured them"
        if set(views) == {"general", "longest"}:
            return (text + ": `general` (a three-quarter view) and `longest` (the orbit with the longest lists, "
                    "found by `bat/find_views.py`).")
        return text + ": " + ", ".join(f"`{v}`" for v in views) + " (the end of each scene's name)."

    def frame_times(self):
        rows = []
        for s in self.scenes:
            rows.append([s] + [fmt(self.value(s, a, "cpu_ms_median")) for a in self.algorithms])
        fig, ax = plt.subplots(figsize=(12, 5))
        width = 0.8 / len(self.algorithms)
        for k, a in enumerate(self.algorithms):
            xs = [i + k * width for i in range(len(self.scenes))]
            ys = [self.value(s, a, "cpu_ms_median") or 0 for s in self.scenes]
            ax.bar(xs, ys, width, label=a)
        ax.set_yscale("log")
        ax.set_xticks([i + 0.4 - width / 2 for i in range(len(self.scenes))])
        ax.set_xticklabels(self.scenes, rotation=60, ha="right", fontsize=8)
        ax.set_ylabel("frame time, ms (log)")
        ax.legend(ncol=len(self.algorithms), fontsize=8)
        ax.set_title("Frame time per algorithm and scene (median)")
        self.emit("## Frame time per algorithm and scene", "",
                  "Median wall time of a whole frame (ms). `ll-array` is `ll --sort array` (the thesis's table 5.3).", "",
                  self.save(fig, "frame-times"), "",
                  *table(["scene"] + [f"`{a}`" for a in self.algorithms], rows), "")

    def ratios_section(self):
        ours = {
            "ib/ll": [self.ib_construction(s) / self.value(s, "ll", "gpu_ms_median") for s in self.scenes
                      if self.ib_construction(s) and self.value(s, "ll", "gpu_ms_median")],
            "dp/ll": [self.value(s, "dp", "gpu_ms_median") / self.value(s, "ll", "gpu_ms_median") for s in self.scenes
                      if self.value(s, "dp", "gpu_ms_median") and self.value(s, "ll", "gpu_ms_median")],
            "ddp/dp": [self.value(s, "ddp", "gpu_ms_median") / self.value(s, "dp", "gpu_ms_median") for s in self.scenes
                       if self.value(s, "ddp", "gpu_ms_median") and self.value(s, "dp", "gpu_ms_median")],
            "ll-array/ll": [self.value(s, "ll-array", "gpu_ms_median") / self.value(s, "ll", "gpu_ms_median")
                            for s in self.scenes if self.value(s, "ll-array", "gpu_ms_median") and self.value(s, "ll", "gpu_ms_median")],
        }
        t4 = self.thesis.tables["comparison"]
        t3 = self.thesis.tables["sort"]
        theirs = {
            "ib/ll": [float(r["ib_ms"]) / float(r["ll_ms"]) for r in t4],
            "dp/ll": [float(r["dp_ms"]) / float(r["ll_ms"]) for r in t4],
            "ddp/dp": [float(r["ddp_ms"]) / float(r["dp_ms"]) for r in t4],
            "ll-array/ll": [float(r["array_ms"]) / float(r["dynamic_ms"]) for r in t3],
        }
        rows = [[f"{k}", spread_text(ours[k]), spread_text(theirs[k]), str(len(ours[k]))] for k in ours]
        fig, ax = plt.subplots(figsize=(8, 4))
        keys = list(ours)
        ax.boxplot([ours[k] or [float("nan")] for k in keys], positions=[i * 3 for i in range(len(keys))], widths=0.8)
        ax.boxplot([theirs[k] for k in keys], positions=[i * 3 + 1 for i in range(len(keys))], widths=0.8,
                   boxprops={"color": "tab:orange"}, medianprops={"color": "tab:orange"})
        ax.set_xticks([i * 3 + 0.5 for i in range(len(keys))])
        ax.set_xticklabels(keys)
        ax.axhline(1.0, color="grey", lw=0.5)
        ax.set_yscale("log")
        ax.set_ylabel("time ratio (log)")
        ax.set_title(f"Our ratios (black, {self.renderer_name()}) beside the thesis's (orange, {self.thesis.gpu})")
        self.emit("## Our ratios beside the thesis's", "",
                  "Per scene, GPU (stage) time of one algorithm over another; median (minimum–maximum) over the "
                  "scenes. `ib` is its construction (fill, sort, neighbours), as in the thesis's table 5.4; the "
                  f"thesis's figures are from its tables 5.3 and 5.4 ({self.thesis.gpu}, {self.thesis.size_text()}, "
                  f"its own {self.thesis.scenes()} scenes, depth peeling from the NVIDIA SDK).", "",
                  *table(["ratio", "ours", "thesis", "our scenes"], rows, ["---", "---:", "---:", "---:"]), "",
                  self.save(fig, "ratios"), "")

    def ll_sorts(self):
        """Knowles' sorts beside the plain ones (issue 30): sorts.json, run_comparison.sh step 3d."""
        import quality_map

        data = quality_map.read_bench_json(os.path.join(self.args.results, "sorts.json"))
        if not data:
            return
        sorts = ["ll-insertion", "ll-array", "ll-bma", "ll-merge"]
        by = {}
        for r in data.get("results", []):
            if not r.get("error"):
                by.setdefault(r["scene"], {})[r["algorithm"]] = r
        errors = sorted({f"`{r['algorithm']}` on {r['scene']}: {r['error']}" for r in data.get("results", [])
                         if r.get("error")})

        def stage(r, name):
            return next((x.get("median") for x in r.get("stages") or [] if x.get("name") == name), None)

        def frame(r):
            return (r.get("gpu_ms") or {}).get("median")

        rows = []
        for scene, runs in by.items():
            any_run = next(iter(runs.values()))
            longest = f"{any_run.get('max_list')}, {any_run.get('mean_list', 0):.1f}"
            rows.append([scene, longest] + [fmt(stage(runs[a], "sort")) if a in runs else "" for a in sorts]
                        + [fmt(frame(runs[a])) if a in runs else "" for a in sorts])
        ratio_lines = []
        for a in ("ll-insertion", "ll-bma", "ll-merge"):
            sort_ratio = [stage(v["ll-array"], "sort") / stage(v[a], "sort") for v in by.values()
                          if a in v and "ll-array" in v and stage(v[a], "sort") and stage(v["ll-array"], "sort")]
            frame_ratio = [frame(v["ll-array"]) / frame(v[a]) for v in by.values()
                           if a in v and "ll-array" in v and frame(v[a]) and frame(v["ll-array"])]
            if sort_ratio:
                ratio_lines.append(f"- `{a}` against `ll-array`: sort stage {spread_text(sort_ratio, 2)} times as fast "
                                   f"(median, range over the scenes), whole frame {spread_text(frame_ratio, 2)} times.")
        width = {r.get("width") for r in data.get("results", [])}
        self.emit("## ll's sorts: Knowles' against the plain ones", "",
                  f"`{data.get('command', '?')}` (step 3d): the deepest views, all four sorts of `ll` in one run "
                  f"at {', '.join(str(w) for w in sorted(width))} pixels square. `insertion` sorts each list in "
                  "place, `array` in a private array sized for the longest list, `bma` groups the pixels by list "
                  "length and sorts each group in an array of its size (Knowles et al. 2013) with register "
                  "blocks, `merge` (the default) merges the register blocks in the list itself (after their "
                  "register-based block sort, 2014). All four give the same image byte for byte "
                  "(tests/ll_sort_bma.sh). Median ms of the sort stage, then of the whole frame; longest and "
                  "mean list per scene. Why llvmpipe ranks them as it does: "
                  "[algorithms.md](algorithms.md#ll-per-pixel-linked-lists-yang-et-al-2010).", "",
                  *table(["scene", "longest, mean list"] + [f"sort `{a[3:]}`" for a in sorts]
                         + [f"frame `{a[3:]}`" for a in sorts], rows), "",
                  *ratio_lines, *(["", "Failed runs: " + "; ".join(errors)] if errors else []), "")

    def ib_stages(self):
        names = ["clear", "fill", "sort", "neighbours", "neighbours_epsilon", "compose"]
        rows, data = [], []
        for s in self.scenes:
            r = self.row(s, "ib")
            if not r:
                continue
            st = stages_of(r)
            values = [st.get(n, 0.0) + st.get(n + "_retry", 0.0) for n in names]
            data.append((s, values))
            total = sum(values)
            rows.append([s] + [fmt(v) for v in values] + [fmt(total),
                                                           f"{100 * (values[3] + values[4]) / total:.0f}%" if total else "–"])
        if not data:
            return
        fig, ax = plt.subplots(figsize=(12, 4.5))
        # shares stacked to 100 % (a log axis would distort a stack); the ms are in the table
        bottom = [0.0] * len(data)
        totals = [sum(v) or 1.0 for _, v in data]
        for k, n in enumerate(names):
            ys = [100 * v[k] / t for (_, v), t in zip(data, totals)]
            ax.bar(range(len(data)), ys, bottom=bottom, label=n)
            bottom = [b + y for b, y in zip(bottom, ys)]
        ax.set_xticks(range(len(data)))
        ax.set_xticklabels([f"{s} ({fmt(t, 0)} ms)" for (s, _), t in zip(data, totals)], rotation=60, ha="right",
                           fontsize=8)
        ax.set_ylabel("% of the frame's stages")
        ax.set_ylim(0, 100)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.0, 1.0))
        ax.set_title("Illustration Buffer: each stage's share of the frame (medians)")
        shares = self._thesis_shares()
        ours = []
        for _, v in data:
            c = v[0] + v[1] + v[2] + v[3] + v[4]
            if c:
                ours.append(((v[0] + v[1]) / c, v[2] / c, (v[3] + v[4]) / c))
        share_rows = []
        for k, label in enumerate(["fill", "sort", "neighbours"]):
            share_rows.append([label, spread_text([100 * x[k] for x in ours], 0) + " %",
                               spread_text([100 * x[k] for x in shares], 0) + " %"])
        self.emit("## Illustration Buffer: stage breakdown", "",
                  "Median ms per stage of `ib` (no modulation: the construction and the compose). "
                  "`neighbours` is the triangle table and the welded-id search, `neighbours_epsilon` the epsilon "
                  "fallback for the fragments the id search left without a neighbour in some direction "
                  "where a candidate lies within `--epsilon-max` of the predicted depth. "
                  "`oit bench` leaves out the `neighbour_stats` pass (link quality, a diagnostic of "
                  "`oit render --json` and the workbench), as the thesis's timings did.", "",
                  self.save(fig, "ib-stages"), "",
                  *table(["scene"] + names + ["total", "neighbours share"], rows), "",
                  "Share of each stage in the construction, ours beside the thesis's table 5.1 (which lists "
                  "cumulative times):", "",
                  *table(["stage", "ours", "thesis"], share_rows, ["---", "---:", "---:"]), "")

    def parallel(self):
        algorithms = [a for a in ("dp", "ddp", "ll", "ib") if a in self.algorithms]
        if not algorithms:
            return
        axes_names = ["vertices", "fragments", "longest list", "Ψ %", "time ms"]
        fig, axes = plt.subplots(1, len(algorithms), figsize=(4.2 * len(algorithms), 4), squeeze=False)
        for ax, a in zip(axes[0], algorithms):
            points = []
            for s in self.scenes:
                ll = self.row(s, "ll")
                t = self.ib_construction(s) if a == "ib" else self.value(s, a, "gpu_ms_median")
                if not ll or t is None:
                    continue
                points.append([number(ll["vertices"]), number(ll["fragments"]), number(ll["max_list"]),
                               100 * number(ll["psi"]), t])
            if not points:
                continue
            lows = [min(p[k] for p in points) for k in range(5)]
            highs = [max(p[k] for p in points) for k in range(5)]
            tmin, tmax = lows[4], highs[4]
            for p in points:
                norm = [(p[k] - lows[k]) / (highs[k] - lows[k]) if highs[k] > lows[k] else 0.5 for k in range(5)]
                third = (p[4] - tmin) / (tmax - tmin) if tmax > tmin else 0
                colour = "tab:green" if third < 1 / 3 else "tab:blue" if third < 2 / 3 else "tab:red"
                ax.plot(range(5), norm, color=colour, alpha=0.7, lw=1)
            ax.set_xticks(range(5))
            ax.set_xticklabels([f"{n}\n{compact(lows[k])}–\n{compact(highs[k])}" for k, n in enumerate(axes_names)],
                               fontsize=7)
            ax.set_yticks([])
            ax.set_title(f"{a}" + (" construction" if a == "ib" else ""))
        fig.suptitle("Parallel coordinates (each axis min–max); colour by thirds of the time range: "
                     "green fastest, blue, red slowest", fontsize=9)
        self.emit("## Parallel coordinates", "",
                  "As the thesis's figures 5.4 and 5.7–5.10: one line per scene through vertices, fragments, "
                  "longest list, Ψ and time, coloured by the third of the time range it falls in.", "",
                  self.save(fig, "parallel"), "")

    def memory(self):
        rows = []
        for s in self.scenes:
            rows.append([s] + [fmt((self.value(s, a, "memory_bytes") or float("nan")) / 2 ** 20) for a in self.algorithms])
        per_fragment = []
        thesis_ib = self.thesis.bytes_per_fragment
        for a in ("ll", "ib"):
            values = [self.value(s, a, "bytes_per_fragment") for s in self.scenes if self.value(s, a, "bytes_per_fragment")]
            if values:
                per_fragment.append(f"`{a}` {max(values):.0f} bytes per fragment")
        fig, ax = plt.subplots(figsize=(8, 4))
        data = [[(self.value(s, a, "memory_bytes") or float("nan")) / 2 ** 20 for s in self.scenes] for a in self.algorithms]
        ax.boxplot([[v for v in d if not math.isnan(v)] or [float("nan")] for d in data])
        ax.set_xticklabels(self.algorithms)
        ax.set_yscale("log")
        ax.set_ylabel("MB held by the algorithm (log)")
        ax.set_title("Memory per algorithm over the scenes")
        self.emit("## Memory per algorithm", "",
                  "MB of GPU buffers and targets each algorithm holds at the bench size (the model's own buffers "
                  "not included). " + ("; ".join(per_fragment) + " (every per-fragment buffer, ping-pong copies "
                                       f"included), the thesis's Illustration Buffer {thesis_ib}." if per_fragment else ""), "",
                  self.save(fig, "memory"), "",
                  *table(["scene"] + [f"`{a}`" for a in self.algorithms], rows), "")

    def resolutions(self):
        rows = read_measure(os.path.join(self.args.results, "ib_resolutions.txt"))
        if not rows:
            self.emit("## Resolution sweep", "", "Not measured in this run (bat/measure_resolutions.sh).", "")
            return
        series = {}
        for r in rows:
            series.setdefault(f"{r['name']} {r['counter']}", []).append(
                (int(r["width"]), int(r["fragments"]), float(r["task_ms"])))
        fig, ax = plt.subplots(figsize=(8, 5))
        for name, points in series.items():
            points.sort()
            ax.plot([p[1] for p in points], [p[2] for p in points], marker="o", ms=3, lw=1, label=name)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("fragments (log)")
        ax.set_ylabel("ib construction ms (log)")
        ax.legend(fontsize=6, ncol=2)
        sizes = sorted({int(r["width"]) for r in rows})
        ax.set_title(f"Illustration Buffer construction against fragments, {sizes[0]}x{sizes[0]}..{sizes[-1]}x{sizes[-1]}")
        table_rows = []
        for name, points in series.items():
            by_size = {p[0]: p for p in points}
            table_rows.append([name] + [f"{by_size[s][1]:,} / {by_size[s][2]:.1f}" if s in by_size else "–" for s in sizes])
        # growth: time per fragment from the smallest to the largest size
        growth = []
        for points in series.values():
            if len(points) >= 2 and points[0][2] > 0 and points[0][1] > 0:
                growth.append((points[-1][2] / points[0][2]) / (points[-1][1] / points[0][1]))
        # the thesis's sweep (tables B.1-B.2), from its smallest size to its largest
        their_sizes = self.thesis.sweep_sizes
        first, last = their_sizes[0], their_sizes[-1]
        their = [(v[last][0] / v[first][0], v[last][1] / v[first][1]) for v in self.thesis.sweep.values()
                 if first in v and last in v and v[first][0] and v[first][1]]
        fragments_m, _, _ = spread([f for f, _ in their])
        time_m, time_lo, time_hi = spread([t for _, t in their])
        thesis_note = (f"In the thesis (tables B.1–B.2, {sizes_text(their_sizes).split(' in steps')[0]}) the "
                       f"fragments grew ×{fragments_m:.2f} and the time ×{time_lo:.2f}–{time_hi:.2f} (median "
                       f"{time_m:.2f}): {spread_text([t / f for f, t in their])} times as fast as the fragment count.")
        self.emit("## Resolution sweep", "",
                  "`bat/measure_resolutions.sh`: Illustration Buffer construction (`oit measure` task 2) at "
                  f"{sizes_text(sizes)}, each cell fragments / ms.", "",
                  self.save(fig, "resolutions"), "",
                  *table(["view"] + [f"{s}²" for s in sizes], table_rows), "",
                  f"Time grew {spread_text(growth)} times as fast as the fragment count over the sweep (1 = linear). "
                  + thesis_note, "")

    def modulation_passes(self):
        files = [("linked_lists.txt", "linked lists (task 1)"), ("ib_construction.txt", "construction (task 2)"),
                 ("diffusion.txt", "one diffusion pass (task 3)"),
                 ("diffusion_gauss.txt", "diffusion + Gaussian (task 4)"),
                 ("view_distance.txt", "distance + curvature (task 5)")]
        measured = {label: read_measure(os.path.join(self.args.results, f)) for f, label in files}
        if not any(measured.values()):
            return
        names = []
        for rows in measured.values():
            for r in rows:
                key = f"{r['name']} {r['counter']}"
                if key not in names:
                    names.append(key)
        widths = [r["width"] for rows in measured.values() for r in rows]
        viewport = max(set(widths), key=widths.count)
        table_rows = []
        for key in names:
            cells = [key]
            for label, rows in measured.items():
                match = [r for r in rows if f"{r['name']} {r['counter']}" == key and r["width"] == viewport]
                cells.append(f"{float(match[0]['task_ms']):.1f}" if match else "–")
            table_rows.append(cells)
        t5 = self.thesis.tables["modulation"]
        t1 = self.thesis.tables["stages"]
        ours_ratio = {}
        construction = {f"{r['name']} {r['counter']}": float(r["task_ms"]) for r in measured["construction (task 2)"]
                        if r["width"] == viewport}
        for label, rows in measured.items():
            if label.startswith(("one diffusion", "diffusion +", "distance")):
                ours_ratio[label] = [float(r["task_ms"]) / construction[f"{r['name']} {r['counter']}"]
                                     for r in rows if r["width"] == viewport
                                     and construction.get(f"{r['name']} {r['counter']}")]
        totals = {r["model"]: float(r["total_ms"]) for r in t1}
        theirs = {
            "one diffusion pass (task 3)": [float(r["diffusion_ms"]) / totals[r["model"]] for r in t5 if r["model"] in totals],
            "diffusion + Gaussian (task 4)": [(float(r["diffusion_ms"]) + float(r["blur_ms"])) / totals[r["model"]]
                                             for r in t5 if r["model"] in totals],
            "distance + curvature (task 5)": [float(r["dist_curv_ms"]) / totals[r["model"]] for r in t5 if r["model"] in totals],
        }
        ratio_rows = [[k, spread_text(ours_ratio.get(k, [])), spread_text(theirs[k])] for k in theirs]
        self.emit("## The thesis's measurements (`oit measure`)", "",
                  "The six scripts of the source, `bat/measure_*.sh`, run `oit measure TASK COUNTER NAME PATH "
                  f"m00..m33 p00..p33 {viewport}` per view (the views' matrices are in build/bench/views.txt). "
                  f"Median ms of the task's stages at {viewport}×{viewport}:", "",
                  *table(["view"] + [label for label in measured], table_rows), "",
                  "Each modulation pass relative to the construction of the same view, ours beside the thesis's "
                  "(table 5.5 over table 5.1):", "",
                  *table(["pass / construction", "ours", "thesis"], ratio_rows, ["---", "---:", "---:"]), "")

    def quality_map(self):
        """The approximations' cost/quality map (bat/quality_map.py): Pareto plots per scene class,
        the error table, temporal stability, the depth sweep, the papers' ratios beside ours."""
        import quality_map

        q = quality_map.QualityMap(self, self.args.results, os.path.join(ROOT, "config", "bench-scenes.json"))
        q.emit()
        if q.quality:
            rows = [x for x in q.rows(q.quality) if q.time_ms(x)]
            quality_map.published_section(self, rows, quality_map.read_published(
                os.path.join(ROOT, "docs", "data", "published_approximations.csv")), q.time_ms)
        quality_map.claims_section(self, self.args.results, quality_map.read_claims(
            os.path.join(ROOT, "docs", "data", "published_claims.csv")))

    def scale(self):
        """Screen sizes and the 13M-triangle model (bat/scale.py writes scale.json and renders it)."""
        import scale

        scale.section(self, self.args.results, table, fmt)

    def accuracy(self):
        rows_in = [r for r in read_csv(os.path.join(self.args.results, "accuracy.csv")) if not r["error"]]
        if not rows_in:
            return
        algorithms = [a for a in ALGORITHMS if any(r["algorithm"] == a for r in rows_in)]
        size = f"{rows_in[0]['width']}x{rows_in[0]['height']}"
        rows = []
        for a in algorithms:
            mine = [r for r in rows_in if r["algorithm"] == a and r["ref_max_diff"] != ""]
            if not mine:
                continue
            worst = max(mine, key=lambda r: float(r["ref_over_tolerance_percent"]))
            rows.append([f"`{a}`", str(max(int(r["ref_max_diff"]) for r in mine)),
                         fmt(statistics.median(float(r["ref_mean_diff"]) for r in mine), 3),
                         f"{float(worst['ref_over_tolerance_percent']):.2f} ({worst['scene']})"])
        outside = sorted({f"`{r['algorithm']}` on {r['scene']}" for r in rows_in
                          if r["algorithm"] in ("dp", "ddp", "ll", "ib") and r["ref_over_tolerance_percent"] != ""
                          and float(r["ref_over_tolerance_percent"]) > self.mismatch})
        bounds = f"{self.mismatch:g}% of the pixels more than {self.tolerance:g}/255 off"
        verdict = ("Every exact algorithm (`dp`, `ddp`, `ll`, `ib`) stays within the tests' bounds on every scene "
                   f"(at most {bounds})." if not outside else
                   f"**Outside the tests' bounds** (more than {bounds}): " + ", ".join(outside) + ".")
        self.emit("## Difference from the reference", "",
                  f"Every scene at {size}, {frames_text(rows_in)}, the algorithms in turn in one GL context, "
                  "against the exact CPU `reference`: the largest channel difference (0..255) over the scenes, the "
                  f"median of the mean difference, and the worst share of pixels more than {self.tolerance:g} off. " + verdict +
                  " `blend` and `wboit` are approximations.", "",
                  *table(["algorithm", "largest diff", "median mean diff", f"worst % over {self.tolerance:g}"], rows), "")

    def why_missed(self):
        """Where a target is missed: the stage breakdown says where the time goes."""
        notes = []
        ib_ll = self.ratios.get("ib_ll", {})
        if ib_ll and max(ib_ll.values()) > TARGETS["ib_ll"]:
            sort_ratio, fill_ratio = [], []
            shares = {}  # scene -> the search's and the epsilon fallback's shares of its construction
            for s in ib_ll:
                ib = stages_of(self.row(s, "ib"))
                ll = stages_of(self.row(s, "ll"))
                construction = stage_sum(ib, IB_CONSTRUCTION)
                if ll.get("sort"):
                    sort_ratio.append(ib.get("sort", 0) / ll["sort"])
                if ll.get("fill"):
                    fill_ratio.append(stage_sum(ib, ("fill",)) / stage_sum(ll, ("fill",)))
                if construction:
                    shares[s] = (stage_sum(ib, ("neighbours",)) / construction,
                                 ib.get("neighbours_epsilon", 0) / construction)
            nb_share = [search for search, _ in shares.values()]
            epsilon_share = [epsilon for _, epsilon in shares.values()]
            # does the search's cost follow the list length? (per fragment, across scenes)
            per_fragment, mean_list = [], []
            for s in ib_ll:
                ib_row = self.row(s, "ib")
                fragments = number(ib_row["fragments"])
                if fragments:
                    per_fragment.append(stage_sum(stages_of(ib_row), ("neighbours",)) / fragments)
                    mean_list.append(number(ib_row["mean_list"]))
            rho = spearman(per_fragment, mean_list)
            without = [stage_sum(stages_of(self.row(s, "ib")), ("clear", "fill", "sort")) / self.value(s, "ll", "gpu_ms_median")
                       for s in ib_ll]
            over = sorted((s for s, v in ib_ll.items() if v > TARGETS["ib_ll"]), key=ib_ll.get, reverse=True)

            def over_text(s):
                search, epsilon = shares.get(s, (0, 0))
                return (f"{s} {ib_ll[s]:.2f}× (the search {100 * search:.0f} % of its construction, the epsilon "
                        f"fallback within it {100 * epsilon:.0f} %)")
            notes.append(
                f"- **`ib` construction vs `ll`** (worst {max(ib_ll.values()):.2f}×, on "
                f"{max(ib_ll, key=ib_ll.get)}; {len(ib_ll) - len(over)} of {len(ib_ll)} scenes within "
                f"{TARGETS['ib_ll']:g}×, over it: " + ", ".join(over_text(s) for s in over) + "). "
                f"From the stage breakdown above: the neighbour search takes "
                f"{spread_text([100 * x for x in nb_share], 0)} % of the construction (the epsilon fallback alone "
                f"{spread_text([100 * x for x in epsilon_share], 0)} %); `ib`'s sort costs "
                f"{spread_text(sort_ratio)} × `ll`'s sort (it also writes each list into a contiguous run of "
                f"cores and links) and its fill {spread_text(fill_ratio)} × `ll`'s fill. Without the neighbour "
                f"search `ib` would be at {spread_text(without)} × `ll`. For every fragment and each of the four "
                "directions the search binary-searches the neighbouring pixel's sorted run for the depth the "
                "fragment's triangle plane predicts and tests candidates outwards for a shared welded vertex "
                "([illustration-buffer.md](illustration-buffer.md#neighbour-search---neighbours-indexweldedepsilon-default-welded)), "
                "so each fragment's cost depends on the neighbouring lists' lengths; across the scenes, the "
                f"neighbour time per fragment against the mean list length has Spearman ρ = {fmt(rho)} "
                "(1: it follows the list length exactly, 0: unrelated). The thesis's FindNeighbors "
                f"was {spread_text([100 * x[2] for x in self._thesis_shares()], 0)} % of its construction. "
                "What shortened the search so far, and what was tried and did not pay, with numbers: "
                "[illustration-buffer.md](illustration-buffer.md#speed-on-llvmpipe)."
                + (" The floor it shows: cutting the neighbour pass down step by step, its straight-line loads "
                   "(the fragment's triangle row and plane, the candidates beside each predicted depth) and the "
                   "four binary searches are nearly all of its time and the walk over candidates little: about "
                   "30 texels read per fragment, on every lane since llvmpipe runs a branch's body for all lanes "
                   "when one takes it, where the fill writes one node. Search starts from a hint, narrower "
                   "views, a finer epsilon queue and other sorts were measured there and did not pay."
                   if self.renderer_name() == "llvmpipe" else ""))
            if self.profile:
                notes.append("  " + self.profile)
        dp_ll = self.ratios.get("dp_ll", {})
        if dp_ll and min(dp_ll.values()) < TARGETS["dp_ll"]:
            parts = []
            for s in (s for s, v in dp_ll.items() if v < TARGETS["dp_ll"]):
                dp_row, ll_row = self.row(s, "dp"), self.row(s, "ll")
                layers = number(dp_row["layers"]) or 0
                peel = stage_sum(stages_of(dp_row), ("peel_",))
                llst = stages_of(ll_row)
                parts.append(f"{s}: {dp_ll[s]:.2f}×, `dp` peeled {layers:.0f} layers at "
                             f"{peel / max(layers + 1, 1):.1f} ms per geometry pass over {ll_row['triangles']} triangles; "
                             f"`ll` fill {stage_sum(llst, ('fill',)):.1f}, sort {llst.get('sort', 0):.1f}, "
                             f"compose {llst.get('compose', 0):.1f} ms")
            # does dp's disadvantage grow with the model? (dp/ll against the triangle count, every scene)
            pairs = [(number(self.row(s, "ll")["triangles"]), v) for s, v in dp_ll.items()]
            rho = spearman([p[0] for p in pairs], [p[1] for p in pairs])
            notes.append(f"- **`ll` vs `dp`** below {TARGETS['dp_ll']:g}×: " + "; ".join(parts) + ". Depth peeling "
                         "costs layers × geometry passes"
                         + (", so it is cheapest relative to `ll` on small models" if rho is not None and rho > 0
                            else "")
                         + f" (`ll`'s advantage against the triangle count over the {len(pairs)} scenes: "
                         f"Spearman ρ = {fmt(rho)}).")
        ll_blend = self.ratios.get("ll_blend", [])
        if ll_blend and statistics.median(ll_blend) > TARGETS["ll_blend"]:
            fill_share = []
            for s in self.scenes:
                ll = self.row(s, "ll")
                if ll:
                    st = stages_of(ll)
                    total = sum(st.values())
                    if total:
                        fill_share.append(stage_sum(st, ("fill",)) / total)
            fill_over_blend = []
            for s in self.scenes:
                ll, blend = self.row(s, "ll"), self.value(s, "blend", "cpu_ms_median")
                if ll and blend:
                    fill_over_blend.append(stage_sum(stages_of(ll), ("fill",)) / blend)
            notes.append(
                f"- **`ll` vs `blend`** (median {statistics.median(ll_blend):.2f}×): `ll`'s fill takes "
                f"{spread_text([100 * x for x in fill_share], 0)} % of its frame and alone costs "
                f"{spread_text(fill_over_blend)} × `blend`'s whole frame: the same geometry pass, but every "
                "fragment takes a node with an atomic counter, stores it and swaps its pixel's head with an "
                "image atomic"
                + (", and llvmpipe executes storage-buffer accesses lane by lane "
                   "([illustration-buffer.md](illustration-buffer.md#speed-on-llvmpipe)) where `blend`'s "
                   "blending is vectorised" if self.renderer_name() == "llvmpipe" else "")
                + ". The rest is the sort and the compose over every fragment, "
                "work `blend` does not do (they already read through buffer textures, "
                "[algorithms.md](algorithms.md#ll-per-pixel-linked-lists-yang-et-al-2010)). "
                "`bat/fill_profile.py` takes the fill apart piece by piece (rasterisation, shading, counter, "
                "canonical depth, node store, head swap): every piece past the shading costs something, none "
                "dominates, and the pieces `blend` does not have add up to more than its whole draw "
                "([algorithms.md](algorithms.md#where-lls-time-goes-llvmpipe)); the fill alone is the floor that keeps "
                "this ratio above the target.")
        if notes:
            self.emit("## Where a target is missed, and why", "", *notes, "")

    def _thesis_shares(self):
        out = []
        # table 5.1 gives cumulative times: fill, fill+sort, fill+sort+neighbours
        for r in self.thesis.tables["stages"]:
            fill, sort_cum, nb_cum = float(r["fill_ms"]), float(r["sort_ms"]), float(r["findneighbors_ms"])
            out.append((fill / nb_cum, (sort_cum - fill) / nb_cum, (nb_cum - sort_cum) / nb_cum))
        return out

    def footer(self):
        self.emit("## Reproducing", "",
                  "```", "config/install-debian-packages.sh     # Debian packages, incl. python3-matplotlib (npm: the machine's Node.js)",
                  "bat/run_comparison.sh                 # build, models, oit bench, the six measurements, this page",
                  "bat/run_comparison.sh --quick         # a smoke test in minutes; report in build/bench/quick-docs",
                  "```", "",
                  "Raw results: `build/bench/results/bench.csv` (one row per scene × algorithm: median, minimum and "
                  "maximum of frame and stage times, memory, fragments, longest list, Ψ, list-length histograms), `bench.json` (the same with "
                  "the renderer and the command), `machine.json` (the machine: CPU, cores, GL renderer), "
                  "`accuracy.csv`, and one text file per `oit measure` script.", "")

    def write(self):
        self.header()
        self.targets()
        self.scenes_table()
        self.depth_complexity()
        self.frame_times()
        self.ratios_section()
        self.ll_sorts()
        self.ib_stages()
        self.parallel()
        self.memory()
        self.resolutions()
        self.modulation_passes()
        self.accuracy()
        self.quality_map()
        self.scale()
        self.why_missed()
        self.footer()
        path = os.path.join(self.args.docs, "benchmarks.md")
        with open(path, "w") as f:
            f.write("\n".join(self.lines).rstrip() + "\n")
        print(path)


class QualitySection:
    """--section quality: rewrites only "## The cost/quality map of the approximations" of an
    existing DOCS/benchmarks.md from RESULTS' quality.json, stability.json and depth_sweep.json
    (bat/run_comparison.sh --quality-only), saying under its title which command and commit made
    it; the rest of the page stays what the run its header names measured."""
    TITLE = "## The cost/quality map of the approximations"

    def __init__(self, args):
        self.args = args
        self.lines = []
        self.images = os.path.join(args.docs, "images")
        os.makedirs(self.images, exist_ok=True)

    emit = Report.emit
    save = Report.save

    def write(self):
        import quality_map

        path = os.path.join(self.args.docs, "benchmarks.md")
        if not os.path.exists(path):
            sys.exit(f"report: --section quality rewrites a section of {path}, which is missing: "
                     "run bat/run_comparison.sh first")
        page = open(path).read().split("\n")
        try:
            start = page.index(self.TITLE)
        except ValueError:
            sys.exit(f"report: {path} has no '{self.TITLE}' section")
        end = next((i for i in range(start + 1, len(page)) if page[i].startswith("## ")), len(page))
        q = quality_map.QualityMap(self, self.args.results, os.path.join(ROOT, "config", "bench-scenes.json"))
        if not q.quality:
            sys.exit(f"report: {self.args.results}/quality.json is missing: run bat/run_comparison.sh --quality-only")
        q.emit()
        rows = [x for x in q.rows(q.quality) if q.time_ms(x)]
        quality_map.published_section(self, rows, quality_map.read_published(
            os.path.join(ROOT, "docs", "data", "published_approximations.csv")), q.time_ms)
        quality_map.claims_section(self, self.args.results, quality_map.read_claims(
            os.path.join(ROOT, "docs", "data", "published_claims.csv")))
        machine_path = os.path.join(self.args.results, "machine.json")
        machine = json.load(open(machine_path)) if os.path.exists(machine_path) else {}
        date = q.quality.get("date") or datetime.datetime.utcnow().isoformat(timespec="seconds") + "Z"
        note = (f"*This section alone was regenerated by `{self.args.command}` (then `python3 bat/report.py "
                f"--section quality`) at commit {machine.get('commit') or commit_of(__file__)} on {date}, on "
                f"{machine.get('cpu', 'the machine of machine.json')} with {machine.get('renderer', '?')}; "
                "the rest of the page is from the run its header names.*")
        self.lines[1:1] = ["", note]
        page[start:end] = self.lines
        with open(path, "w") as f:
            f.write("\n".join(page).rstrip() + "\n")
        print(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", default=os.path.join(ROOT, "build", "bench", "results"))
    parser.add_argument("--docs", default=os.path.join(ROOT, "docs"))
    parser.add_argument("--command", default="bat/run_comparison.sh")
    parser.add_argument("--elapsed", type=float, default=0)
    parser.add_argument("--shared", default=SHARED,
                        help="the shared folder with the thesis's data/ and sources/ (default: ../shared beside the "
                             "repository)")
    parser.add_argument("--section", choices=["quality"],
                        help="rewrite only this section of DOCS/benchmarks.md (quality: the cost/quality map, from "
                             "bat/run_comparison.sh --quality-only)")
    args = parser.parse_args()
    (QualitySection(args) if args.section == "quality" else Report(args)).write()


if __name__ == "__main__":
    main()
