"""quality_map.py: the cost/quality map of docs/benchmarks.md (issue 12), used by bat/report.py.

Reads three oit bench JSON files that bat/run_comparison.sh writes into the results directory:
  quality.json      every scene x every algorithm and parameter (kbuffer:4/8/16, mboit:power4/...),
                    one size, each run compared with the CPU reference (error_* figures)
  stability.json    oit bench --orbit-sequence N on some scenes: flicker per algorithm
  depth_sweep.json  onion scenes of growing depth (layers per pixel): time, memory, error
and emits the sections through the report (emit / save): a Pareto plot per scene class (error
against frame time, marker area = memory), the table of each algorithm's median error and cost,
the stability table, the depth sweep, and each algorithm's worst image beside the reference with
its error map (the images come from the bundle the quality run writes with --bundle).
Every figure is read from those files; nothing is typed in.
"""
import json
import math
import os
import statistics

# scene classes, from config/bench-scenes.json ("class" of each model)
CLASS_TITLES = {"cad": "CAD assemblies", "scanned": "scanned and modelled meshes", "synthetic": "synthetic deep scenes"}


def read_bench_json(path):
    if not os.path.exists(path):
        return None
    try:
        data = json.load(open(path))
    except json.JSONDecodeError:
        return None
    return data


def family(label):
    """'kbuffer:8' -> 'kbuffer'."""
    return label.split(":")[0]


def label_order(label):
    """kbuffer:4 before kbuffer:16; moments by name."""
    name, _, parameter = label.partition(":")
    return (name, int(parameter) if parameter.isdigit() else 0, parameter)


def spearman_rank(xs, ys):
    """Spearman's rho of two rankings without ties (1 - 6 sum d^2 / (n (n^2 - 1)))."""
    n = len(xs)
    if n < 2:
        return float("nan")
    return 1.0 - 6.0 * sum((x - y) ** 2 for x, y in zip(xs, ys)) / (n * (n * n - 1))


def median_or_none(values):
    values = [v for v in values if v is not None and not (isinstance(v, float) and math.isnan(v))]
    return statistics.median(values) if values else None


class QualityMap:
    def __init__(self, report, results, config_path):
        self.report = report
        self.results = results
        self.quality = read_bench_json(os.path.join(results, "quality.json"))
        self.stability = read_bench_json(os.path.join(results, "stability.json"))
        self.sweep = read_bench_json(os.path.join(results, "depth_sweep.json"))
        self.classes = {}
        if os.path.exists(config_path):
            for model in json.load(open(config_path)).get("models", []):
                self.classes[model["name"]] = model.get("class", "other")

    def rows(self, data):
        if not data:
            return []
        return [r for r in data.get("results", []) if not r.get("error") or isinstance(r.get("error"), dict)]

    @staticmethod
    def time_ms(row):
        value = row.get("gpu_ms")
        if isinstance(value, dict):
            value = value.get("median")
        return value

    @staticmethod
    def rmse(row):
        value = row.get("error_rmse")
        if value is None and isinstance(row.get("error"), dict):
            value = row["error"].get("rmse")
        return value

    def emit(self):
        r = self.report
        r.emit("## The cost/quality map of the approximations", "")
        if not self.quality:
            r.emit(f"Not measured: {os.path.join(self.results, 'quality.json')} is missing "
                   "(bat/run_comparison.sh writes it).", "")
            return
        rows = [x for x in self.rows(self.quality) if self.rmse(x) is not None and self.time_ms(x)]
        command = self.quality.get("command", "?")
        size = f"{rows[0]['width']}x{rows[0]['height']}" if rows else "?"
        r.emit(f"Every scene with every algorithm and parameter at {size}, each frame compared with the CPU "
               f"reference of the same frame (`{command}`). Error is the RMSE over the RGB channels on the "
               "0..255 scale (docs/cli.md, --error-vs-reference); time is the median frame time; memory "
               "what the algorithm holds after the frame. The table adds the median SSIM and the median "
               "mean FLIP (the perceptual error of Andersson et al. 2020, LDR, at 67 pixels per degree: 0 "
               "identical, 1 the largest; docs/algorithms.md, Error figures), where the results have it.", "")
        self.pareto(rows)
        self.table(rows)
        self.metric_orders(rows)
        self.worst_images(rows)
        self.stability_table()
        self.depth_sweep()

    def pareto(self, rows):
        import matplotlib.pyplot as plt

        r = self.report
        by_class = {}
        for row in rows:
            by_class.setdefault(self.classes.get(row["scene"].split("-")[0], "other"), []).append(row)
        for name, members in sorted(by_class.items()):
            labels = sorted({x["algorithm"] for x in members})
            fig, ax = plt.subplots(figsize=(7.5, 4.8))
            largest = max(x.get("memory_bytes", 0) for x in members) or 1
            for label in labels:
                mine = [x for x in members if x["algorithm"] == label]
                t = median_or_none([self.time_ms(x) for x in mine])
                e = median_or_none([self.rmse(x) for x in mine])
                m = median_or_none([x.get("memory_bytes", 0) for x in mine]) or 0
                if t is None or e is None:
                    continue
                ax.scatter([t], [max(e, 1e-3)], s=30 + 600 * m / largest, alpha=0.6)
                ax.annotate(label, (t, max(e, 1e-3)), fontsize=7, xytext=(3, 3), textcoords="offset points")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("median frame time over the class's scenes (ms, log)")
            ax.set_ylabel("median RMSE vs reference (0..255, log; exact at 1e-3)")
            ax.set_title(f"{CLASS_TITLES.get(name, name)}: error against time (marker area: memory)")
            ax.grid(True, which="both", alpha=0.3)
            r.emit(f"### {CLASS_TITLES.get(name, name)} ({len({x['scene'] for x in members})} scenes)", "",
                   r.save(fig, f"pareto-{name}"), "")

    def table(self, rows):
        r = self.report
        labels = sorted({x["algorithm"] for x in rows}, key=label_order)
        # FLIP (the mean LDR FLIP, 0..1; oit bench's error_flip): empty for results measured before it
        lines = ["| algorithm | median RMSE | worst RMSE (scene) | median SSIM | median FLIP | median time (ms) | "
                 "median memory (MB) |",
                 "|---|---:|---|---:|---:|---:|---:|"]
        for label in labels:
            mine = [x for x in rows if x["algorithm"] == label]
            worst = max(mine, key=self.rmse)
            ssim = median_or_none([x.get("error_ssim") for x in mine])
            flip = median_or_none([x.get("error_flip") for x in mine])
            lines.append(f"| {label} | {median_or_none([self.rmse(x) for x in mine]):.3g} | "
                         f"{self.rmse(worst):.3g} ({worst['scene']}) | "
                         f"{'' if ssim is None else f'{ssim:.4f}'} | "
                         f"{'' if flip is None else f'{flip:.4f}'} | "
                         f"{median_or_none([self.time_ms(x) for x in mine]):.1f} | "
                         f"{median_or_none([x.get('memory_bytes', 0) for x in mine]) / 2**20:.2f} |")
        r.emit(*lines, "")

    @staticmethod
    def approximate_labels(rows):
        """The variants that are approximate on these scenes: somewhere more pixels than the exact
        algorithms' tests allow (EXACT_MISMATCH %) are more than EXACT_TOLERANCE off."""
        from report_data import tests_bound

        mismatch = tests_bound("EXACT_MISMATCH")
        return sorted({x["algorithm"] for x in rows if (x.get("error_share_over_2") or 0) > mismatch},
                      key=label_order)

    def metric_orders(self, rows):
        """How RMSE, SSIM and FLIP order the approximate methods (by their medians over the scenes),
        the pairs the metrics order differently, and one such pair of images from the bundle."""
        r = self.report
        labels = [a for a in self.approximate_labels(rows)
                  if median_or_none([x.get("error_flip") for x in rows if x["algorithm"] == a]) is not None]
        r.emit("### RMSE, SSIM and FLIP: how they order the approximations", "")
        if len(labels) < 2:
            r.emit("Not enough approximate methods with FLIP figures in quality.json to order them.", "")
            return
        # a larger value is a worse image for each key: RMSE, 1 - SSIM, FLIP
        metrics = {"RMSE": lambda x: self.rmse(x),
                   "SSIM": lambda x: None if x.get("error_ssim") is None else 1.0 - x["error_ssim"],
                   "FLIP": lambda x: x.get("error_flip")}
        medians = {a: {m: median_or_none([f(x) for x in rows if x["algorithm"] == a]) for m, f in metrics.items()}
                   for a in labels}
        ranks = {m: {a: i + 1 for i, a in enumerate(sorted(labels, key=lambda a: medians[a][m]))} for m in metrics}
        lines = ["| method | rank by RMSE | rank by SSIM | rank by FLIP | median FLIP |", "|---|---:|---:|---:|---:|"]
        for a in sorted(labels, key=lambda a: ranks["FLIP"][a]):
            lines.append(f"| {a} | {ranks['RMSE'][a]} | {ranks['SSIM'][a]} | {ranks['FLIP'][a]} | "
                         f"{medians[a]['FLIP']:.4f} |")
        swapped = [(a, b) for i, a in enumerate(labels) for b in labels[i + 1:]
                   if (ranks["RMSE"][a] - ranks["RMSE"][b]) * (ranks["FLIP"][a] - ranks["FLIP"][b]) < 0]
        swapped_ssim = [(a, b) for i, a in enumerate(labels) for b in labels[i + 1:]
                        if (ranks["SSIM"][a] - ranks["SSIM"][b]) * (ranks["FLIP"][a] - ranks["FLIP"][b]) < 0]
        pairs = len(labels) * (len(labels) - 1) // 2
        rho_rmse = spearman_rank([ranks["RMSE"][a] for a in labels], [ranks["FLIP"][a] for a in labels])
        rho_ssim = spearman_rank([ranks["SSIM"][a] for a in labels], [ranks["FLIP"][a] for a in labels])
        r.emit("The variants approximate on these scenes (on some scene more pixels than the exact algorithms' "
               "tests allow are more than 2/255 off) ranked by their median over the "
               "scenes, 1 the closest to the reference (SSIM ranked by 1 - SSIM). FLIP orders "
               f"{pairs - len(swapped)} of the {pairs} pairs as RMSE does (Spearman's rho {rho_rmse:.3f}) and "
               f"{pairs - len(swapped_ssim)} as SSIM does (rho {rho_ssim:.3f}).", "", *lines, "")
        if swapped:
            r.emit("Pairs FLIP orders against RMSE: " + ", ".join(
                f"{a} / {b}" for a, b in sorted(swapped, key=lambda p: (ranks["FLIP"][p[0]], ranks["FLIP"][p[1]]))) + ".",
                "")
        self.disagreement_images(rows, labels)

    def disagreement_images(self, rows, labels):
        """One scene where two methods' images are ordered one way by RMSE and the other by FLIP, the
        largest such disagreement (relative FLIP difference), shown beside the reference."""
        import matplotlib.image as mpimg
        import matplotlib.pyplot as plt

        r = self.report
        bundle = os.path.join(self.results, "quality-bundle")
        best = None
        by = {(x["scene"], x["algorithm"]): x for x in rows}
        for scene in sorted({x["scene"] for x in rows}):
            for i, a in enumerate(labels):
                for b in labels[i + 1:]:
                    x, y = by.get((scene, a)), by.get((scene, b))
                    if not x or not y or None in (self.rmse(x), self.rmse(y), x.get("error_flip"), y.get("error_flip")):
                        continue
                    if (self.rmse(x) - self.rmse(y)) * (x["error_flip"] - y["error_flip"]) >= 0:
                        continue
                    # the disagreement's size: the smaller of the two relative gaps
                    gap = min(abs(self.rmse(x) - self.rmse(y)) / max(self.rmse(x), self.rmse(y)),
                              abs(x["error_flip"] - y["error_flip"]) / max(x["error_flip"], y["error_flip"]))
                    if best is None or gap > best[0]:
                        best = (gap, scene, x, y)
        if best is None:
            r.emit("On no scene do RMSE and FLIP order two of these methods differently.", "")
            return
        _, scene, x, y = best
        size = f"{x['width']}x{x['height']}"
        paths = [os.path.join(bundle, f"{scene}_{size}.reference.png")] + \
            [os.path.join(bundle, f"{scene}_{v['algorithm'].replace(':', '-')}_{size}.png") for v in (x, y)]
        text = (f"The clearest disagreement: on {scene}, {x['algorithm']} has RMSE {self.rmse(x):.2f}, SSIM "
                f"{x.get('error_ssim', 0):.4f}, FLIP {x['error_flip']:.4f}; {y['algorithm']} has RMSE "
                f"{self.rmse(y):.2f}, SSIM {y.get('error_ssim', 0):.4f}, FLIP {y['error_flip']:.4f}.")
        if not all(os.path.exists(p) for p in paths):
            r.emit(text + " (The bundle has no images of it.)", "")
            return
        fig, axes = plt.subplots(1, 3, figsize=(9, 3.4))
        for ax, path, title in zip(axes, paths, ["reference", x["algorithm"], y["algorithm"]]):
            ax.imshow(mpimg.imread(path))
            ax.set_title(title, fontsize=9)
            ax.axis("off")
        fig.suptitle(f"{scene}: RMSE and FLIP disagree", fontsize=10)
        r.emit(text, "", r.save(fig, "metric-disagreement"), "")

    def worst_images(self, rows):
        """Each algorithm's worst image (largest RMSE) beside the reference and its error map, from the
        quality run's bundle (oit bench --bundle)."""
        import matplotlib.image as mpimg
        import matplotlib.pyplot as plt

        r = self.report
        bundle = os.path.join(self.results, "quality-bundle")
        if not os.path.isdir(bundle):
            r.emit("(No image bundle: the worst images are left out.)", "")
            return
        r.emit("### The worst image of each algorithm", "",
               "Reference, the algorithm's image and its error map (black: exact; blue to red: 1 to 64+ of "
               "255 on a logarithmic scale; docs/cli.md, --error-map), on the scene where its RMSE is largest.", "")
        for label in sorted({x["algorithm"] for x in rows}, key=label_order):
            mine = [x for x in rows if x["algorithm"] == label]
            worst = max(mine, key=self.rmse)
            if (worst.get("error_max") or 0) <= 2:  # within the exact algorithms' tolerance: nothing to see
                continue
            size = f"{worst['width']}x{worst['height']}"
            stem = f"{worst['scene']}_{label.replace(':', '-')}_{size}"
            paths = [os.path.join(bundle, f"{worst['scene']}_{size}.reference.png"),
                     os.path.join(bundle, f"{stem}.png"), os.path.join(bundle, f"{stem}.error.png")]
            if not all(os.path.exists(p) for p in paths):
                continue
            fig, axes = plt.subplots(1, 3, figsize=(9, 3.4))
            for ax, path, title in zip(axes, paths, ["reference", label, "error map"]):
                ax.imshow(mpimg.imread(path))
                ax.set_title(title, fontsize=9)
                ax.axis("off")
            fig.suptitle(f"{label} on {worst['scene']}: RMSE {self.rmse(worst):.2f}", fontsize=10)
            r.emit(r.save(fig, f"worst-{label.replace(':', '-')}"), "")

    def stability_table(self):
        r = self.report
        r.emit("### Temporal stability", "")
        if not self.stability:
            r.emit("Not measured (stability.json is missing).", "")
            return
        rows = [x for x in self.rows(self.stability) if x.get("flicker") is not None]
        r.emit(f"`{self.stability.get('command', '?')}`: the mean absolute change of the error image between "
               "consecutive frames of a slow orbit (0..255 scale), what users see as popping; an exact "
               "algorithm's error is rounding, so its flicker is near 0.", "")
        scenes = sorted({x["scene"] for x in rows})
        labels = sorted({x["algorithm"] for x in rows}, key=label_order)
        lines = ["| algorithm | " + " | ".join(scenes) + " |", "|---|" + "---:|" * len(scenes)]
        for label in labels:
            cells = []
            for scene in scenes:
                hit = [x for x in rows if x["algorithm"] == label and x["scene"] == scene]
                cells.append(f"{hit[0]['flicker']:.3f}" if hit else "")
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
        r.emit(*lines, "")

    def depth_sweep(self):
        import matplotlib.pyplot as plt

        r = self.report
        r.emit("### Depth sweep", "")
        if not self.sweep:
            r.emit("Not measured (depth_sweep.json is missing).", "")
            return
        rows = self.rows(self.sweep)
        # the depth of each scene: the longest list ll measured there
        depth = {x["scene"]: x.get("max_list") for x in rows if x["algorithm"] == "ll" and x.get("max_list")}
        labels = sorted({x["algorithm"] for x in rows}, key=label_order)
        fig, axes = plt.subplots(1, 3, figsize=(13, 4))
        for label in labels:
            points = sorted((depth[x["scene"]], self.time_ms(x), x.get("memory_bytes", 0), self.rmse(x))
                            for x in rows if x["algorithm"] == label and x["scene"] in depth)
            if not points:
                continue
            xs = [p[0] for p in points]
            axes[0].plot(xs, [p[1] for p in points], marker="o", label=label)
            axes[1].plot(xs, [p[2] / 2**20 for p in points], marker="o", label=label)
            if all(p[3] is not None for p in points):
                axes[2].plot(xs, [max(p[3], 1e-3) for p in points], marker="o", label=label)
        for ax, title in zip(axes, ["frame time (ms)", "memory (MB)", "RMSE vs reference (log)"]):
            ax.set_xlabel("layers per pixel (longest list)")
            ax.set_title(title)
            ax.grid(True, alpha=0.3)
        axes[2].set_yscale("log")
        axes[0].legend(fontsize=7)
        r.emit(f"`{self.sweep.get('command', '?')}`: nested spheres of growing depth. A k-layer budget breaks "
               "where the layers pass k (its error leaves zero); ll's memory grows with the fragments; the "
               "moment and weighted methods cost the same at every depth.", "", r.save(fig, "depth-sweep"), "")


def read_published(path):
    """docs/data/published_approximations.csv: frame times the papers published (with their source)."""
    import csv

    if not os.path.exists(path):
        return []
    return list(csv.DictReader(open(path, encoding="utf-8")))


def published_section(report, quality_rows, published, time_ms):
    """The papers' time ratios to depth peeling beside ours, where both measured the same algorithm."""
    if not published:
        return
    ours = {}
    for label in {x["algorithm"] for x in quality_rows}:
        ratios = []
        for row in quality_rows:
            if row["algorithm"] != label:
                continue
            dp = [x for x in quality_rows if x["algorithm"] == "dp" and x["scene"] == row["scene"]]
            if dp and time_ms(dp[0]) and time_ms(row):
                ratios.append(time_ms(row) / time_ms(dp[0]))
        if ratios:
            ours[label] = statistics.median(ratios)
    lines = ["| source (setting) | algorithm | their time / depth peeling | ours (median over scenes) |",
             "|---|---|---:|---:|"]
    by_source = {}
    for row in published:
        by_source.setdefault((row["source"], row["setting"]), []).append(row)
    for (source, setting), rows in by_source.items():
        dp = [r for r in rows if r["label"] == "dp"]
        if not dp:
            continue
        for row in rows:
            if row["label"] == "dp":
                continue
            theirs = float(row["frame_ms"]) / float(dp[0]["frame_ms"])
            mine = ours.get(row["label"])
            lines.append(f"| [{source}]({rows[0]['url']}) ({setting}) | {row['label']} | {theirs:.3f} | "
                         f"{'not measured' if mine is None else f'{mine:.3f}'} |")
    report.emit("### Beside the papers", "",
                "Frame time relative to depth peeling on the same scene, as the papers published it "
                "(docs/data/published_approximations.csv) and as measured here (a GPU against llvmpipe: "
                "only the ratios compare).", "", *lines, "")


def read_claims(path):
    """docs/data/published_claims.csv: the papers' own claims (ratios, shares), quoted with their source."""
    import csv

    if not os.path.exists(path):
        return []
    return list(csv.DictReader(open(path, encoding="utf-8")))


def _frame_ms(row):
    value = row.get("gpu_ms")
    return value.get("median") if isinstance(value, dict) else value


def _sort_share(row):
    stages = {s["name"]: s.get("median") for s in row.get("stages") or [] if isinstance(s, dict)}
    total = sum(v for v in stages.values() if v)
    return stages.get("sort", 0) / total if total and stages.get("sort") else None


def _spread(values, percent=False):
    values = sorted(values)
    if not values:
        return None
    f = (lambda v: f"{100 * v:.0f}%") if percent else (lambda v: f"{v:.2f}x")
    if len(values) == 1:
        return f"{f(values[0])} (1 scene)"
    if f(values[0]) == f(values[-1]):
        return f"{f(values[0])} ({len(values)} scenes)"
    return f"{f(values[0])}-{f(values[-1])} (median {f(statistics.median(values))}, {len(values)} scenes)"


def claims_section(report, results, claims):
    """The papers' claims (docs/data/published_claims.csv) beside the same ratio measured here: a
    speed-up is the baseline's frame time over the method's, both from one bench run (side by side);
    a sort share is the sort stage over the sum of the stages."""
    if not claims:
        return
    runs = []  # (what, rows) per bench run that can hold the labels
    for name, what in (("sorts.json", "ll's sorts run"), ("quality.json", "quality run")):
        data = read_bench_json(os.path.join(results, name))
        if data:
            size = {f"{r.get('width')}x{r.get('height')}" for r in data.get("results", [])}
            runs.append((f"{what}, {', '.join(sorted(size))}",
                         [r for r in data.get("results", []) if not r.get("error") or isinstance(r.get("error"), dict)]))

    def matches(label, algorithm):
        return label == algorithm or label.startswith(algorithm + ":")

    lines = ["| source | claim | theirs | ours: same ratio, range over scenes (run) |", "|---|---|---:|---|"]
    for claim in claims:
        low, high = claim["low"].strip(), claim["high"].strip()
        share = "sort_share" in claim["measure"].split()
        if not low and not high:
            theirs = "no figure"
        elif share:
            theirs = f"{100 * float(low):.0f}-{100 * float(high):.0f}%" if low else f"up to {100 * float(high):.0f}%"
        else:
            theirs = f"{float(low):g}-{float(high):g}x" if low else f"up to {float(high):g}x"
        ours = []
        for what, rows in runs:
            by = {}
            for r in rows:
                by.setdefault(r["algorithm"], {})[r["scene"]] = r
            for label in sorted((x for x in by if matches(x, claim["algorithm"])), key=label_order):
                if share:
                    values = [v for v in map(_sort_share, by[label].values()) if v]
                    text = _spread(values, percent=True)
                    name = f"`{label}`'s sort"
                else:
                    base = by.get(claim["baseline"], {})
                    values = [_frame_ms(base[s]) / _frame_ms(r) for s, r in by[label].items()
                              if s in base and _frame_ms(base[s]) and _frame_ms(r)]
                    text = _spread(values)
                    name = f"`{claim['baseline']}` / `{label}`"
                    if text and "memory" in claim["measure"].split():
                        memory = [base[s]["memory_bytes"] / r["memory_bytes"] for s, r in by[label].items()
                                  if s in base and base[s].get("memory_bytes") and r.get("memory_bytes")]
                        if memory:
                            text += f", memory {_spread(memory).split(' (')[0]}"
                if text:
                    ours.append(f"{name}: {text} ({what})")
        claim_text = claim["claim"].replace("|", "/")
        lines.append(f"| [{claim['source']}]({claim['url']}) ({claim['where']}) | {claim_text} | {theirs} | "
                     f"{'<br>'.join(ours) if ours else 'not measured in this run'} |")
    report.emit("### The papers' claims beside the same ratios here", "",
                "What the papers of the newer methods claim in their abstracts (their tables were not "
                "reachable here), quoted in docs/data/published_claims.csv, beside the same ratio from this "
                "page's runs: a speed-up is the baseline's frame time over the method's (gpu median, both in "
                "one run), a sort share the sort stage over the frame's stages, memory the baseline's bytes over the method's. Their figures are GPUs' "
                "(with the occupancy and memory hierarchy the methods were built for), ours llvmpipe's: "
                "[algorithms.md](algorithms.md) says for each method what carries over and why.", "",
                *lines, "")
