"""report_data.py: what bat/report.py reads and the small helpers its page is written with:
the benchmark's CSV and result files, the thesis's tables and text (../shared), number
formatting, tables, rank correlation and spreads."""
import csv
import json
import math
import os
import re
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(ROOT), "shared")  # ../shared beside the repository (README.md)
THESIS_TABLES = {  # data/: the thesis's measurement tables
    "stages": "thesis_table_5_1_ib_stages.csv",
    "construction": "thesis_table_5_2_ib_construction.csv",
    "sort": "thesis_table_5_3_sort_methods.csv",
    "comparison": "thesis_table_5_4_oit_comparison.csv",
    "modulation": "thesis_table_5_5_modulation_passes.csv",
}
THESIS_TEXT = "sources/000_768ef58642674f75.txt"  # the thesis (shared/README.md)
PAPER_TEXT = "sources/001_d33ee0e5babd5f13.txt"   # the paper version of it


# ----------------------------------------------------------------- input

def read_csv(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def stages_of(row):
    """{'fill': median ms, ...} from the CSV's name=median/min/max;... column."""
    out = {}
    for item in filter(None, (row.get("stages") or "").split(";")):
        name, values = item.split("=")
        out[name] = float(values.split("/")[0])
    return out


HISTOGRAM_BINS = 65  # OIT_HISTOGRAM_BINS: list lengths 0..63, and 64 or more
# the algorithms whose list_histogram counts every fragment of the frame (oit bench's CSV)
HISTOGRAM_ALGORITHMS = ("reference", "ll", "ll-array", "ib", "kbuffer", "hybrid")


def histogram_of(row, key="list_histogram"):
    """A bench CSV row's histogram field (counts joined by ';', trailing zero bins left out) as a
    list of HISTOGRAM_BINS counts, or None when the row has none (or the CSV predates the column)."""
    field = (row or {}).get(key) or ""
    if not field:
        return None
    counts = [int(c) for c in field.split(";")]
    return counts + [0] * (HISTOGRAM_BINS - len(counts))


def scene_histogram(rows):
    """The depth complexity of one scene and size from its bench rows, and where it came from: the
    reference frame's (scene_histogram, on every row when bench rendered the reference), else the
    list_histogram of the first exact algorithm that has one (they count the same lists)."""
    for r in rows:
        h = histogram_of(r, "scene_histogram")
        if h:
            return h, "reference"
    for name in HISTOGRAM_ALGORITHMS:
        for r in rows:
            if r["algorithm"].split(":")[0] == name and not r.get("error"):
                h = histogram_of(r)
                if h:
                    return h, r["algorithm"]
    return None, None


def histogram_quantile(counts, q):
    """The list length below which a share q of the non-empty pixels lie (the open last bin counts
    as its lower bound); None without non-empty pixels."""
    total = sum(counts[1:])
    if total == 0:
        return None
    seen = 0
    for length, c in enumerate(counts[1:], start=1):
        seen += c
        if seen >= q * total:
            return length
    return len(counts) - 1


def stage_sum(stages, prefixes):
    return sum(ms for name, ms in stages.items() if any(name.startswith(p) for p in prefixes))


def number(value, default=None):
    try:
        return float(value)
    except (TypeError, ValueError):
        return default


def read_measure(path):
    """Rows of an `oit measure` results file."""
    rows = []
    if not os.path.exists(path):
        return rows
    keys = ["task", "name", "counter", "width", "height", "vertices", "triangles", "fragments", "max_list",
            "psi_percent", "task_ms", "frame_ms", "fps", "stages"]
    for line in open(path):
        if line.startswith("#") or not line.strip():
            continue
        values = line.rstrip("\n").split("\t")
        row = dict(zip(keys, values))
        row["stages"] = dict((kv.split("=")[0], float(kv.split("=")[1]))
                             for kv in filter(None, row.get("stages", "").split(";")))
        rows.append(row)
    return rows


def missing_shared(path):
    sys.exit(f"report: {path} is missing: the thesis's figures are read from ../shared beside the repository "
             "(shared/README.md; --shared DIR names another copy)")


def decimal(text):
    """A number of the thesis's text tables: 4,71 or 126296."""
    return float(text.replace(",", "."))


def text_tables(text, label):
    """The tab-separated tables of the thesis's text whose caption starts with
    label ('Table B.'): [(caption, [header lines], [data rows])]; a table is the
    block of non-empty lines just above its caption."""
    lines = text.split("\n")
    tables = []
    for k, line in enumerate(lines):
        if not line.startswith(label):
            continue
        end = k - 1
        while end >= 0 and not lines[end].strip():
            end -= 1
        start = end
        while start > 0 and lines[start - 1].strip():
            start -= 1
        block = [b.split("\t") for b in lines[start:end + 1]]
        header = [b for b in block if not re.fullmatch(r"\d+(,\d+)?", (b[1:] or [""])[0].strip())]
        rows = [b for b in block if b not in header]
        tables.append((line, header, rows))
    return tables


class Thesis:
    """The thesis's figures, read from SHARED at run time (never typed in here)."""

    def __init__(self, shared):
        self.tables = {}
        for key, name in THESIS_TABLES.items():
            path = os.path.join(shared, "data", name)
            if not os.path.exists(path):
                missing_shared(path)
            self.tables[key] = read_csv(path)
            if not self.tables[key]:
                sys.exit(f"report: {path} has no rows")
        texts = {}
        for name in (THESIS_TEXT, PAPER_TEXT):
            path = os.path.join(shared, name)
            if not os.path.exists(path):
                missing_shared(path)
            texts[name] = open(path, encoding="utf-8").read()
        gpu = re.search(r"\*\*GPU:\*\*\s*([^,\n]+)", texts[THESIS_TEXT])
        per_fragment = re.search(r"(\d+) bytes per fragment", texts[PAPER_TEXT])
        if not gpu or not per_fragment:
            sys.exit(f"report: the thesis's GPU ('**GPU:** ...' in {THESIS_TEXT}) or the Illustration Buffer's "
                     f"bytes per fragment ('N bytes per fragment' in {PAPER_TEXT}) not found under {shared}")
        self.gpu = gpu.group(1).strip()
        self.bytes_per_fragment = int(per_fragment.group(1))
        self.sweep = self._sweep(texts[THESIS_TEXT], shared)
        # the size of tables 5.1-5.5: the sweep's column whose fragments are table 5.2's
        construction = {r["model"]: int(r["fragments"]) for r in self.tables["construction"]}
        sizes = [size for size in self.sweep_sizes
                 if all(self.sweep.get(m, {}).get(size, (None,))[0] == f for m, f in construction.items())]
        self.size = sizes[0] if sizes else None

    def _sweep(self, text, shared):
        """Tables B.1-B.2: {model: {width: (fragments, ms)}} at 400x400..700x700."""
        sweep, sizes = {}, []
        tables = text_tables(text, "Table B.")
        for caption, header, rows in tables:
            widths = [int(m.group(1)) for h in header for c in h if (m := re.match(r"^(\d+)x\1$", c.strip()))]
            sizes += widths
            for row in rows:
                values = [c for c in row[1:] if c.strip()]
                if len(values) != 2 * len(widths):
                    sys.exit(f"report: {caption.split(':')[0]} of {THESIS_TEXT}: row '{row[0]}' does not have "
                             f"fragments and ms for each of {widths}")
                for k, width in enumerate(widths):
                    sweep.setdefault(row[0].strip(), {})[width] = (int(decimal(values[2 * k])),
                                                                   decimal(values[2 * k + 1]))
        if not sweep:
            sys.exit(f"report: tables B.1-B.2 (the resolution sweep) not found in {os.path.join(shared, THESIS_TEXT)}")
        self.sweep_sizes = sorted(set(sizes))
        return sweep

    def size_text(self):
        return f"{self.size}×{self.size}" if self.size else "an unknown size"

    def scenes(self):
        return len(self.tables["comparison"])

    def ib_ll(self):
        """Table 5.4: Illustration Buffer (construction) over linked lists, per scene."""
        return [float(r["ib_ms"]) / float(r["ll_ms"]) for r in self.tables["comparison"]]


def sizes_text(sizes):
    """'400×400 to 700×700 in steps of 50', or the sizes listed."""
    if len(sizes) >= 3 and len({b - a for a, b in zip(sizes, sizes[1:])}) == 1:
        return f"{sizes[0]}×{sizes[0]} to {sizes[-1]}×{sizes[-1]} in steps of {sizes[1] - sizes[0]}"
    return ", ".join(f"{s}×{s}" for s in sizes)


def frames_text(rows):
    """'one frame after no warm-up' from the rows' frames and warmup columns."""
    def count(key, noun, none):
        values = sorted({int(number(r.get(key), 0)) for r in rows})
        words = {0: none, 1: f"one {noun}"}
        if len(values) == 1:
            return words.get(values[0], f"{values[0]} {noun}s")
        return f"{values[0]} to {values[-1]} {noun}s"
    return f"{count('frames', 'frame', 'no frame')} after {count('warmup', 'warm-up', 'no warm-up')}"


def tests_bound(name):
    """A bound of tests/CMakeLists.txt (EXACT_TOLERANCE, EXACT_MISMATCH): what the page calls the tests' bounds
    (bat/run_comparison.sh passes the same tolerance to the accuracy run)."""
    path = os.path.join(ROOT, "tests", "CMakeLists.txt")
    match = re.search(rf"^set\({name} ([0-9.]+)\)", open(path).read(), re.M) if os.path.exists(path) else None
    if not match:
        sys.exit(f"report: no 'set({name} N)' in {path}")
    return float(match.group(1))


# ----------------------------------------------------------------- helpers

def fmt(value, digits=2):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    if isinstance(value, float):
        if abs(value) >= 1000:
            return f"{value:,.0f}"
        return f"{value:.{digits}f}"
    return str(value)


def compact(value):
    """1234567 -> 1.2M, 15056 -> 15k: axis labels that fit."""
    for limit, suffix in ((1e6, "M"), (1e3, "k")):
        if abs(value) >= limit:
            return f"{value / limit:.3g}{suffix}"
    return f"{value:.3g}"


def table(header, rows, align=None):
    align = align or ["---"] + ["---:"] * (len(header) - 1)
    lines = ["| " + " | ".join(header) + " |", "| " + " | ".join(align) + " |"]
    lines += ["| " + " | ".join(fmt(c) if not isinstance(c, str) else c for c in r) + " |" for r in rows]
    return lines


def spearman(xs, ys):
    """Spearman's rank correlation (no ties correction; enough for a report)."""
    pairs = [(x, y) for x, y in zip(xs, ys) if x is not None and y is not None]
    if len(pairs) < 3:
        return None

    def ranks(values):
        order = sorted(range(len(values)), key=values.__getitem__)
        out = [0.0] * len(values)
        for rank, index in enumerate(order):
            out[index] = float(rank)
        return out

    rx, ry = ranks([p[0] for p in pairs]), ranks([p[1] for p in pairs])
    n = len(pairs)
    return 1 - 6 * sum((a - b) ** 2 for a, b in zip(rx, ry)) / (n * (n * n - 1))


def spread(values):
    values = [v for v in values if v is not None and not math.isnan(v)]
    if not values:
        return None, None, None
    return statistics.median(values), min(values), max(values)


def spread_text(values, digits=2):
    m, lo, hi = spread(values)
    if m is None:
        return "–"
    return f"{m:.{digits}f} ({lo:.{digits}f}–{hi:.{digits}f})"
