#!/usr/bin/env python3
"""scale.py: the exact algorithms at the screen sizes users have and on a model of
more than ten million triangles; time and memory, or the message of a refusal.

Two runs of `oit bench`, each row a frame time (median of the measured frames),
the memory the algorithm holds, the fragments and, for ll and ib, the bands of rows
the frame was drawn in (a frame whose fragments exceed what one GL buffer can
address, 128 MiB on llvmpipe, is drawn in bands, and ib's also past the --max-memory
budget; docs/algorithms.md, Limits):

    screens   the deepest benchmark scenes (the longest mean lists at 600x600:
              menger4, spheres11, engine) at 1920x1080 and 3840x2160
    13M       a level-5 Menger sponge (`oit gen menger --complexity 5`:
              13,062,144 triangles, a 723 MB OBJ) at 600x600 and 1920x1080

Rows that fail carry the one-line error (the --max-memory budget, or a limit of
the GL) instead of figures. The host's peak memory (max_rss_kb) of each run is
recorded too: the 13M-triangle model's import dominates it.

    python3 bat/scale.py --oit build/src/cli/oit --results build/bench/results
        [--scene-list build/bench/scenes.txt] [--models build/bench/models] [--quick]

Writes RESULTS/scale.json; bat/report.py turns it into the "Scale" section of
docs/benchmarks.md. bat/run_comparison.sh runs it (step 3c).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCREEN_SCENES = "menger4-general,spheres11-general,engine-longest"
SCREEN_SIZES = "1920x1080,3840x2160"
BIG_SIZES = "600x600,1920x1080"
ALGORITHMS = "blend,ll,ib,wboit"
MENGER_LEVEL = 5


def bench(oit, args, label):
    """One `oit bench` run; its JSON (rows that failed carry "error")."""
    with tempfile.NamedTemporaryFile(suffix=".json", delete=False) as f:
        path = f.name
    try:
        command = [oit, "bench", *args, "--json", path]
        print(f"scale.py: {label}: {' '.join(command)}", file=sys.stderr, flush=True)
        result = subprocess.run(command)
        # exit 3: some runs failed, their rows say why; anything else is the script's problem
        if result.returncode not in (0, 3):
            sys.exit(f"scale.py: oit bench exited {result.returncode} ({label})")
        with open(path) as f:
            data = json.load(f)
        data["label"] = label
        return data
    finally:
        os.unlink(path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--oit", default=os.path.join(ROOT, "build", "src", "cli", "oit"))
    parser.add_argument("--results", default=os.path.join(ROOT, "build", "bench", "results"))
    parser.add_argument("--scene-list", default=os.path.join(ROOT, "build", "bench", "scenes.txt"))
    parser.add_argument("--models", default=os.path.join(ROOT, "build", "bench", "models"),
                        help="where the level-5 sponge is written (once; 723 MB)")
    parser.add_argument("--quick", action="store_true",
                        help="a smoke test: level 4, 800x450 and 1280x720, one frame")
    args = parser.parse_args()

    frames = ["--frames", "1", "--warmup", "0"] if args.quick else ["--frames", "2", "--warmup", "1",
                                                                     "--time-budget", "20"]
    level = 4 if args.quick else MENGER_LEVEL
    screen_sizes = "800x450,1280x720" if args.quick else SCREEN_SIZES
    big_sizes = "256x256,800x450" if args.quick else BIG_SIZES
    common = ["--algorithms", ALGORITHMS, "--reference-max-pixels", "0", "--quiet", *frames]

    runs = []
    runs.append(bench(args.oit, ["--scene-list", args.scene_list, "--scenes", SCREEN_SCENES,
                                 "--sizes", screen_sizes, *common], "screens"))
    os.makedirs(args.models, exist_ok=True)
    model = os.path.join(args.models, f"menger{level}.obj")
    if not os.path.exists(model):
        subprocess.run([args.oit, "gen", "menger", "--complexity", str(level), "--out", model], check=True)
    runs.append(bench(args.oit, ["--model", model, "--name", f"menger{level}", "--orbit", "30,20",
                                 "--sizes", big_sizes, *common], "big"))

    os.makedirs(args.results, exist_ok=True)
    out = os.path.join(args.results, "scale.json")
    with open(out, "w") as f:
        json.dump({"command": "python3 bat/scale.py" + (" --quick" if args.quick else ""), "runs": runs}, f,
                  indent=1)
    print(out)


# ------------------------------------------------------------------ the page

def section(report, results, table, fmt):
    """The "Scale" section of docs/benchmarks.md from RESULTS/scale.json (nothing if absent);
    table and fmt are report.py's."""
    path = os.path.join(results, "scale.json")
    if not os.path.exists(path):
        return
    with open(path) as f:
        data = json.load(f)
    big = [r for run in data["runs"] if run["label"] == "big" for r in run["results"]]
    triangles = max((r.get("triangles", 0) for r in big), default=0)
    report.emit("## Scale: screen sizes and a large model", "",
                f"`{data['command']}` (step 3c of `bat/run_comparison.sh`): the deepest scenes at screen "
                f"sizes, and a Menger sponge from `oit gen` ({triangles:,} triangles), with the exact "
                "algorithms beside blend and wboit. "
                "Frame time is the median of the measured frames; memory is what the algorithm holds "
                "(the scene's own buffers not included). A frame whose fragments exceed what one buffer "
                "can address on this GL is drawn by `ll` and `ib` in bands of rows (each band draws the "
                "whole scene again; `ib`'s also when it exceeds the memory budget, and its bands "
                "store the rows either side that their neighbour passes read); a row that fails "
                "shows its one-line error.", "")
    for run in data["runs"]:
        rows = []
        blend = {(r["scene"], r["width"], r["height"]): r["gpu_ms"]["median"] for r in run["results"]
                 if r["algorithm"] == "blend" and not r.get("error")}
        for r in run["results"]:
            size = f"{r['width']}×{r['height']}"
            if r.get("error"):
                rows.append([r["scene"], size, f"`{r['algorithm']}`", "refused", "", "", "", "", r["error"]])
                continue
            fragments = r.get("fragments")
            base = blend.get((r["scene"], r["width"], r["height"]))
            rows.append([r["scene"], size, f"`{r['algorithm']}`", fmt(r["gpu_ms"]["median"], 0),
                         fmt(r["gpu_ms"]["median"] / base, 2) if base else "",
                         fmt(r["memory_bytes"] / 2**20, 1),
                         f"{fragments:,}" if fragments is not None else "",
                         str(r.get("max_list", "")), str(r["bands"]) if r.get("bands", 1) > 1 else ""])
        first = run["results"][0] if run["results"] else {}
        title = ("The deepest benchmark scenes at screen sizes" if run["label"] == "screens" else
                 f"{first.get('scene', 'the sponge')}: {first.get('triangles', 0):,} triangles")
        report.emit(f"**{title}** (host peak memory of the run {run['max_rss_kb'] / 2**20:.1f} GB):", "",
                    *table(["scene", "size", "algorithm", "frame ms", "/ blend", "memory MB", "fragments",
                            "longest list", "bands / error"], rows,
                           ["---", "---", "---", "---:", "---:", "---:", "---:", "---:", "---"]),
                    "")


if __name__ == "__main__":
    main()
