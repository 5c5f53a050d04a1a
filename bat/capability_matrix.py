#!/usr/bin/env python3
"""capability_matrix.py: which opacity modulation each algorithm can express, at what cost.

For every modulation (rows) and algorithm (columns) it renders a scene with
`oit render`, and
- if the algorithm refuses the flags (exit 2), records "not expressible" with
  the algorithm's own one-line reason;
- otherwise compares the image with the reference renderer's (local modulations
  and distance) or with ib's (non-local modulations the reference cannot do),
  and records the error, the frame time, the stages (passes) and the memory,
  each next to the same algorithm without modulation.
A last section measures dp's curvature and edges (neighbours in the same peeled
layer) against ib's on more scenes: largest and mean difference, PSNR, share over
tolerance, and the cost against plain dp and against ib.
Writes docs/generated/modulation_matrix.md; docs/modulation.md explains it.
Run from the repository root after a build:

    python3 bat/capability_matrix.py [--oit build/src/cli/oit] [--size 128x128] [--frames 3] [--jobs N]

A render that appears in more than one cell (the same model, flags and
algorithm) runs once. --jobs N runs N renders at a time: the page is the same
but for its timings, which concurrent renders slow down; the committed page is
made with one (tests/generated_pages.sh, which ignores timings, uses two).
"""
import argparse
import atexit
import concurrent.futures
import datetime
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
from pages import commits, machine, machine_line

ALGORITHMS = []  # from `oit algorithms --json` (algorithms()): the approximations, the exact GPU ones, the CPU reference
EXACT = set()
TOLERANCE = 2          # the exact algorithms' tolerance (tests/CMakeLists.txt)
MISMATCH_PERCENT = 1.0  # share of pixels allowed over it

SCENES = {
    "gearbox": None,  # generated
    "spider": "/usr/share/assimp/models/OBJ/spider.obj",
}
# dp's curvature against ib's (the last section): scenes, generator complexity
# (as tests/gen_scenes.sh) and modes
CURVATURE_SCENES = {
    "onion": None,
    "gearbox": None,
    "spider": "/usr/share/assimp/models/OBJ/spider.obj",
    "menger": None,
}
GEN_COMPLEXITY = {"menger": "3"}
CURVATURE_MODES = [
    ("curvature", ["--modulation", "curvature"]),
    ("dist-curv", ["--modulation", "dist-curv"]),
    ("curvature, 8 neighbours", ["--modulation", "curvature", "--curvature-neighbours", "8"]),
    ("edges", ["--modulation", "edges"]),
]
# Per scene: the flags of each local focus shape and of the part opacities.
SCENE_FLAGS = {
    "gearbox": {
        "parts": ["--component-alpha", "housing=0.1", "--hide", "gear_1", "--component-alpha", "5=0.8"],
        "point": ["--focus-point", "0,0,0.6"],
        "plane": ["--focus-plane", "0,1,0,0"],
        "box": ["--focus-box", "-0.5,-0.5,-1,0.5,0.5,1"],
    },
    "spider": {
        "parts": ["--hide", "Kopf", "--component-alpha", "HLeib01=0.15", "--component-alpha", "3=0.9"],
        "point": ["--focus-point", "-17,0,-10"],
        "plane": ["--focus-plane", "1,0,1,20", "--focus-region", "30"],
        "box": ["--focus-box", "-60,-50,-60,20,40,40"],
    },
}

# Rows: (key, label, flags or a scene key, what to compare with)
ROWS = [
    ("parts", "part opacity and hiding (`--component-alpha`, `--hide`)", "parts", "reference"),
    ("point", "focus point (`--focus-point`)", "point", "reference"),
    ("plane", "focus plane (`--focus-plane`)", "plane", "reference"),
    ("box", "focus box (`--focus-box`)", "box", "reference"),
    ("contrast", "contrast (`--contrast 2.5`)", ["--contrast", "2.5"], "reference"),
    ("light", "headlight and background", ["--shading", "headlight", "--background", "0.1,0.2,0.3"],
     "reference"),
    ("distance", "distance along the ray, adjacent, auto region (`--modulation distance`)",
     ["--modulation", "distance"], "reference"),
    ("distance_region", "distance, adjacent, fixed region (`--focus-region R`)",
     ["--modulation", "distance", "--focus-region", "REGION"], "reference"),
    ("distance_skip", "distance, skip 2 (`--distance skip:2`)",
     ["--modulation", "distance", "--distance", "skip:2"], "reference"),
    ("distance_far", "distance to the far end (`--distance far`)",
     ["--modulation", "distance", "--distance", "far"], "reference"),
    ("curvature", "curvature (`--modulation curvature`)", ["--modulation", "curvature"], "ib"),
    ("dist_curv", "distance and curvature (`--modulation dist-curv`)",
     ["--modulation", "dist-curv"], "ib"),
    ("fields", "transparency fields (`--modulation fields`)", ["--modulation", "fields"], "ib"),
    ("edges", "edges (`--modulation edges`)", ["--modulation", "edges"], "ib"),
]
# eye-space focus region for the fixed-region distance row (model units ~ eye units here)
DISTANCE_REGION = {"gearbox": "0.5", "spider": "40"}

LOCAL = {"parts", "point", "plane", "box", "contrast", "light"}
LOCAL_CODE = "[local_modulation.glsl](../../shaders/common/local_modulation.glsl)"
# Where each supported cell is implemented, and what the implementation changes.
CODE = {
    ("reference", "local"): "[reference_raster.c](../../src/core/reference_raster.c), "
                            "[local_modulation.c](../../src/core/local_modulation.c)",
    ("reference", "distance"): "[alg_reference.c](../../src/core/alg_reference.c) `distances()`",
    ("dp", "distance"): "[alg_dp.c](../../src/core/alg_dp.c), "
                        "[dp/blend_distance.frag](../../shaders/dp/blend_distance.frag)",
    ("ddp", "distance"): "[alg_ddp.c](../../src/core/alg_ddp.c), "
                         "[ddp/blend_distance.frag](../../shaders/ddp/blend_distance.frag)",
    ("ll", "distance"): "[ll/compose.frag](../../shaders/ll/compose.frag) `ll_distance()`",
    ("ib", "distance"): "[curvature_distance.comp](../../shaders/ib/curvature_distance.comp)",
    ("ib", "nonlocal"): "[alg_ib.c](../../src/core/alg_ib.c), [shaders/ib](../../shaders/ib)",
    ("dp", "nonlocal"): "[alg_dp.c](../../src/core/alg_dp.c), "
                        "[dp/blend_curvature.frag](../../shaders/dp/blend_curvature.frag): neighbours "
                        "in the same peeled layer and component; + two RG32UI normal targets"
                        " (dist-curv: with the delayed blending of the distance)",
    ("dp", "edges"): "[alg_dp.c](../../src/core/alg_dp.c), "
                     "[dp/blend_curvature.frag](../../shaders/dp/blend_curvature.frag): neighbours "
                     "in the same peeled layer and component; + two RG32UI normal targets",
}
# Cells that need a modified algorithm, and what changes (exact (algorithm, row) keys).
MODIFIED = {
    ("dp", "distance"): "blending delayed by one layer (a second layer-colour target); "
                        "auto region: a first peeling sweep for the largest distance",
    ("dp", "distance_region"): "blending delayed by one layer (a second layer-colour target)",
    ("ddp", "distance"): "delayed blending: a full-screen pass after each peel pass, the last "
                         "far depth kept; auto region: a first sweep for the largest distance",
    ("ddp", "distance_region"): "delayed blending: a full-screen pass after each peel pass, "
                                "the last far depth kept",
    ("ll", "distance"): "auto region: one more full-screen pass for the largest distance",
}


def scene_model(oit, work, scene, path):
    """The model file of a scene: generated into work when path is None."""
    if path is not None:
        return path if os.path.exists(path) else None
    model = os.path.join(work, scene + ".obj")
    if not os.path.exists(model):
        command = [oit, "gen", scene, "--out", model]
        if scene in GEN_COMPLEXITY:
            command += ["--complexity", GEN_COMPLEXITY[scene]]
        if run(command).returncode != 0:
            sys.exit(f"cannot generate {scene}")
    return model


class Runner:
    """Renders and comparisons, each distinct one run once (memoised on its
    inputs), up to jobs at a time; every call returns a future."""

    def __init__(self, oit, work, size, frames, jobs):
        self.oit, self.work, self.size, self.frames = oit, work, size, frames
        self.pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
        self.done = {}
        self.lock = threading.Lock()
        self.renderers, self.backends = set(), set()

    def _once(self, key, function, *args):
        with self.lock:
            if key not in self.done:
                self.done[key] = self.pool.submit(function, *args)
            return self.done[key]

    def render(self, model, flags, algorithm):
        """A future of (JSON, refusal, png): the JSON of the render, or None and the refusal message."""
        key = ("render", model, tuple(flags), algorithm)
        out = os.path.join(self.work, f"render_{len(self.done)}_{algorithm}.png")
        return self._once(key, self._render, model, flags, algorithm, out)

    def _render(self, model, flags, algorithm, out):
        info, refusal = render(self.oit, model, flags, algorithm, out, self.size, self.frames)
        if info:
            with self.lock:
                self.renderers.add(info.get("renderer"))
                self.backends.add(info.get("backend"))
        return info, refusal, out

    def compare(self, a, b):
        """A future of `oit compare A B --json` (a and b: futures of renders)."""
        return self._once(("compare", id(a), id(b)), lambda: compare(self.oit, a.result()[2], b.result()[2]))


def curvature_queue(runner, work, scenes):
    """Queues the renders and comparisons of the last section: [(scene, label, plain, renders, comparison)]."""
    cases = []
    for scene in scenes:
        model = scene_model(runner.oit, work, scene, CURVATURE_SCENES[scene])
        if model is None:
            print(f"skipping {scene}: model missing", file=sys.stderr)
            continue
        plain = runner.render(model, [], "dp")
        for label, flags in CURVATURE_MODES:
            renders = {algorithm: runner.render(model, flags, algorithm) for algorithm in ("dp", "ib")}
            cases.append((scene, label, plain, renders, runner.compare(renders["dp"], renders["ib"])))
    return cases


def curvature_section(cases):
    """dp's curvature against ib's: error and cost per scene and mode."""
    lines = ["## Curvature and edges outside the Illustration Buffer: dp against ib", "",
             "dp approximates the surface neighbours by the fragments of the same peeled layer "
             "in the adjacent pixels, when they are on the same component "
             "([blend_curvature.frag](../../shaders/dp/blend_curvature.frag)); ib finds them "
             "through the surface. Error of dp's image against ib's: largest channel difference, "
             "mean difference, PSNR (dB), share of pixels more than "
             f"{TOLERANCE} off. Time (ms, median of frames 2..N, sum of the stages), stages and "
             "memory (MB): dp with the modulation / plain dp / ib with the modulation.", "",
             "| scene | modulation | largest | mean | PSNR | over tolerance | ms dp / plain dp / ib "
             "| stages | MB |",
             "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for scene, label, plain_render, renders, comparison in cases:
        plain = plain_render.result()[0]
        infos = {}
        for algorithm, future in renders.items():
            infos[algorithm], refusal, _ = future.result()
            if refusal:
                sys.exit(f"{algorithm} refuses {label} on {scene}: {refusal}")
        diff = comparison.result()
        psnr = "inf" if diff["psnr_db"] is None else f"{diff['psnr_db']:.1f}"
        dp, ib = infos["dp"], infos["ib"]
        lines.append(
            f"| {scene} | {label} | {diff['max_channel_diff']} | {diff['mean_diff']:.2f} | "
            f"{psnr} | {diff['over_tolerance_percent']:.2f}% | "
            f"{stage_ms(dp):.1f} / {stage_ms(plain):.1f} / {stage_ms(ib):.1f} | "
            f"{len(dp['stages'])} / {len(plain['stages'])} / {len(ib['stages'])} | "
            f"{dp['memory_bytes'] / 1048576:.2f} / {plain['memory_bytes'] / 1048576:.2f} / "
            f"{ib['memory_bytes'] / 1048576:.2f} |")
    return lines + [""]


def run(command):
    return subprocess.run(command, capture_output=True, text=True)


def render(oit, model, flags, algorithm, out, size, frames):
    """The JSON of one render, or the refusal message (exit 2)."""
    command = [oit, "render", "--model", model, "--size", size, "--shading", "flat",
               "--algorithm", algorithm, "--frames", str(frames), "--json", "--out", out, *flags]
    # --shading given twice: the last wins (the light row sets headlight)
    result = run(command)
    if result.returncode == 2:
        return None, result.stderr.strip().removeprefix("oit: error: ")
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stderr}")
    return json.loads(result.stdout), None


def compare(oit, a, b):
    result = run([oit, "compare", a, b, "--tolerance", str(TOLERANCE), "--json"])
    if result.returncode not in (0, 1):
        sys.exit(f"compare failed: {result.stderr}")
    return json.loads(result.stdout)


def stage_ms(info):
    return sum(stage["gpu_ms"] for stage in info["stages"])


def kind(row):
    if row in LOCAL:
        return "local"
    if row.startswith("distance"):
        return "distance"
    return "nonlocal"



def algorithms(oit):
    """The columns, from the algorithms' own capability tables (`oit algorithms
    --json`): the approximations, then the exact GPU algorithms, then the CPU
    reference, each group in the registry's order."""
    listed = json.loads(subprocess.run([oit, "algorithms", "--json"], check=True, capture_output=True,
                                       text=True).stdout)
    rank = lambda a: (not a["uses_gl"], a["exact"])  # noqa: E731
    ALGORITHMS[:] = [a["name"] for a in sorted(listed, key=rank)]
    EXACT.clear()
    EXACT.update(a["name"] for a in listed if a["exact"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--oit", default="build/src/cli/oit")
    parser.add_argument("--size", default="128x128")
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--out", default="docs/generated/modulation_matrix.md")
    parser.add_argument("--scenes", default=",".join(SCENES))
    parser.add_argument("--curvature-scenes", default=",".join(CURVATURE_SCENES))
    parser.add_argument("--jobs", type=int, default=1,
                        help="renders at a time (more: the same page but for slower timings)")
    args = parser.parse_args()
    algorithms(args.oit)

    work = tempfile.mkdtemp(prefix="oit-matrix-")
    atexit.register(shutil.rmtree, work, ignore_errors=True)
    runner = Runner(args.oit, work, args.size, args.frames, max(args.jobs, 1))
    try:
        write_page(args, runner, work)
    finally:
        # on an error, the renders still queued are dropped rather than waited for
        runner.pool.shutdown(cancel_futures=True)


def write_page(args, runner, work):
    results = {}  # (scene, row, algorithm) -> dict
    plain = {}    # (scene, algorithm) -> info
    queued = {}   # (scene, row, algorithm) -> future of the render
    plain_queued = {}
    for scene in [s for s in args.scenes.split(",") if s]:
        model = scene_model(args.oit, work, scene, SCENES[scene])
        if model is None:
            print(f"skipping {scene}: {SCENES[scene]} missing", file=sys.stderr)
            continue
        for algorithm in ALGORITHMS:
            plain_queued[(scene, algorithm)] = runner.render(model, [], algorithm)
        for row, _, flags, oracle in ROWS:
            if isinstance(flags, str):
                flags = SCENE_FLAGS[scene][flags]
            flags = [DISTANCE_REGION[scene] if f == "REGION" else f for f in flags]
            for algorithm in ALGORITHMS:
                queued[(scene, row, algorithm)] = runner.render(model, flags, algorithm)
    curvature_scenes = [s for s in args.curvature_scenes.split(",") if s]
    curvature_cases = curvature_queue(runner, work, curvature_scenes)
    for (scene, algorithm), future in plain_queued.items():
        info, refusal, _ = future.result()
        if refusal:
            sys.exit(f"{algorithm} refuses to render {scene}: {refusal}")
        plain[(scene, algorithm)] = info
    for (scene, row, algorithm), future in queued.items():
        info, refusal, _ = future.result()
        results[(scene, row, algorithm)] = {"info": info, "refusal": refusal}
    comparisons = {}
    for (scene, row, algorithm), future in queued.items():
        oracle = next(o for r, _, _, o in ROWS if r == row)
        cell = results[(scene, row, algorithm)]
        oracle_render = queued[(scene, row, oracle)]
        if cell["info"] and results[(scene, row, oracle)]["info"] and algorithm != oracle:
            comparisons[(scene, row, algorithm, "diff")] = runner.compare(future, oracle_render)
            cell["oracle"] = oracle
        if algorithm in ("blend", "wboit") and cell["info"] and results[(scene, row, "reference")]["info"]:
            # the approximation's own error without modulation, for scale
            comparisons[(scene, row, algorithm, "plain_diff")] = runner.compare(
                plain_queued[(scene, algorithm)], plain_queued[(scene, "reference")])
    for (scene, row, algorithm, key), future in comparisons.items():
        results[(scene, row, algorithm)][key] = future.result()
    print(f"matrix: done ({sum(k[0] == 'render' for k in runner.done)} renders, "
          f"{sum(k[0] == 'compare' for k in runner.done)} comparisons so far)", file=sys.stderr)

    scenes = sorted({k[0] for k in results}, key=list(SCENES).index)
    jobs = f" --jobs {args.jobs}" if args.jobs != 1 else ""
    lines = [
        "# Capability matrix: opacity modulation per algorithm",
        "",
        f"Generated by `python3 bat/capability_matrix.py --size {args.size} --frames {args.frames}{jobs}` "
        f"on {datetime.date.today().isoformat()} at commit {commits(__file__, args.oit)}; do not edit by hand. "
        "Definitions and the reasons behind each cell: [docs/modulation.md](../modulation.md).",
        "",
        "MACHINE",
        "",
        "Legend: **yes** = supported, same passes; **modified** = supported with a modified "
        "algorithm; **approx.** = runs, but the image is not the reference's; **no** = not "
        "expressible (the algorithm refuses the flags; its reason is in the details). "
        f"Errors are against `reference` (`ib` for the non-local rows): largest channel "
        f"difference / share of pixels more than {TOLERANCE} off. Exact algorithms pass when at "
        f"most {MISMATCH_PERCENT}% of the pixels are over the tolerance (edge pixels).",
        "",
    ]
    for scene in scenes:
        lines += [f"## {scene}", "",
                  "| modulation | " + " | ".join(ALGORITHMS) + " |",
                  "| --- |" + " :---: |" * len(ALGORITHMS)]
        for row, label, _, oracle in ROWS:
            cells = []
            for algorithm in ALGORITHMS:
                cells.append(summary(results[(scene, row, algorithm)], algorithm, row, oracle))
            lines.append(f"| {label} | " + " | ".join(cells) + " |")
        lines += [""]

    lines += ["## Cost and details", "",
              "Time: median frame time of frames 2..N (sum of the stages, ms), with modulation / "
              "without. Stages: timed stages (geometry and full-screen passes) with / without. "
              "Memory: MB held with / without.", ""]
    for scene in scenes:
        lines += [f"### {scene}", "",
                  "| modulation | algorithm | verdict | error | ms | stages | MB | code / reason |",
                  "| --- | --- | --- | ---: | ---: | ---: | ---: | --- |"]
        for row, label, _, oracle in ROWS:
            for algorithm in ALGORITHMS:
                cell = results[(scene, row, algorithm)]
                base = plain[(scene, algorithm)]
                verdict = summary(cell, algorithm, row, oracle)
                if cell["refusal"]:
                    lines.append(f"| {row} | {algorithm} | {verdict} | | | | | {cell['refusal']} |")
                    continue
                info = cell["info"]
                error = ""
                if "diff" in cell:
                    error = f"{cell['diff']['max_channel_diff']} / {cell['diff']['over_tolerance_percent']:.2f}%"
                    if "plain_diff" in cell:
                        error += (f" (unmodulated: {cell['plain_diff']['max_channel_diff']} / "
                                  f"{cell['plain_diff']['over_tolerance_percent']:.2f}%)")
                ms = f"{stage_ms(info):.1f} / {stage_ms(base):.1f}"
                stages = f"{len(info['stages'])} / {len(base['stages'])}"
                mb = f"{info['memory_bytes'] / 1048576:.2f} / {base['memory_bytes'] / 1048576:.2f}"
                code = code_for(algorithm, row)
                lines.append(f"| {row} | {algorithm} | {verdict} | {error} | {ms} | {stages} | {mb} | {code} |")
        lines += [""]
    if curvature_scenes:
        lines += curvature_section(curvature_cases)
    print(f"{sum(k[0] == 'render' for k in runner.done)} renders, "
          f"{sum(k[0] == 'compare' for k in runner.done)} comparisons", file=sys.stderr)
    lines[lines.index("MACHINE")] = (machine_line(machine(), runner.renderers, runner.backends)
                                     + " The ms columns are wall times on it"
                                     + (f", {args.jobs} renders at a time" if jobs else "") + ".")
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        f.write("\n".join(lines))
    print(f"wrote {args.out}", file=sys.stderr)


def code_for(algorithm, row):
    k = kind(row)
    if k == "local":
        return CODE.get((algorithm, "local"), LOCAL_CODE)
    if k == "distance":
        text = CODE.get((algorithm, "distance"), "")
        note = MODIFIED.get((algorithm, row), "")
        return f"{text}; {note}" if note else text
    return CODE.get((algorithm, row), CODE.get((algorithm, "nonlocal"), ""))


def summary(cell, algorithm, row, oracle):
    if cell["refusal"]:
        return "no"
    if algorithm == oracle:
        return "yes (oracle)"
    diff = cell.get("diff")
    figures = ""
    if diff:
        figures = f" {diff['max_channel_diff']} / {diff['over_tolerance_percent']:.1f}%"
    within = diff is not None and diff["over_tolerance_percent"] <= MISMATCH_PERCENT
    # the non-local rows outside ib are approximations by construction (other neighbours)
    if algorithm not in EXACT or not within or kind(row) == "nonlocal":
        return "approx." + figures
    return ("modified" if (algorithm, row) in MODIFIED else "yes") + figures


if __name__ == "__main__":
    main()
