#!/usr/bin/env python3
"""mlab_cost.py: multi-layer alpha blending's time and error against ll and the reference.

For each scene: the reference once, then rounds in which ll and mlab at each k
run one after the other (so a busy machine slows them alike), each with
--frames F (the CLI reports the median of frames 2..F). Prints a markdown
table: median frame time (GPU-stage sum, wall-clock bracketed on llvmpipe),
the median over rounds of the ratio to ll's time in the same round, mlab's
insert and resolve stages, and the error against the reference
(`oit compare --tolerance 2`: largest channel difference, share of pixels more
than 2/255 off, mean difference). Run from the repository root:

    python3 bat/mlab_cost.py [--oit build-h/src/cli/oit] [--size 256x256] [--rounds 5]
        [--frames 5] [--layers 4,8,16] [--scenes gearbox,spheres]

Scenes are `oit gen` output, written to a temporary directory.
"""
import argparse
import json
import statistics
import subprocess
import sys
import tempfile


def run(command):
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode not in (0, 1) or (result.returncode == 1 and command[1] != "compare"):
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stderr}")
    return result.stdout


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--oit", default="build-h/src/cli/oit")
    parser.add_argument("--size", default="256x256")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--layers", default="4,8,16")
    parser.add_argument("--scenes", default="gearbox,spheres")
    args = parser.parse_args()
    layers = [int(k) for k in args.layers.split(",")]
    work = tempfile.mkdtemp(prefix="mlab_cost_")
    variants = [("ll", ["--algorithm", "ll"])] + [
        (f"mlab k={k}", ["--algorithm", "mlab", "--layers", str(k)]) for k in layers]
    print(f"`python3 bat/mlab_cost.py --size {args.size} --rounds {args.rounds} "
          f"--frames {args.frames} --layers {args.layers} --scenes {args.scenes}`\n")
    print("| scene | variant | frame ms | / ll | insert ms | resolve ms | max | share > 2 | mean |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for scene in args.scenes.split(","):
        model = f"{work}/{scene}.obj"
        run([args.oit, "gen", scene, "--out", model])
        common = ["--model", model, "--size", args.size, "--shading", "flat"]
        reference = f"{work}/{scene}_reference.png"
        run([args.oit, "render", *common, "--algorithm", "reference", "--out", reference])
        times = {name: [] for name, _ in variants}
        stages = {name: {} for name, _ in variants}
        errors = {}
        for round_index in range(args.rounds):
            for name, flags in variants:
                out = f"{work}/{scene}_{name.replace(' ', '_')}.png"
                d = json.loads(run([args.oit, "render", *common, *flags, "--frames",
                                    str(args.frames), "--json", "--out", out]))
                times[name].append(d["gpu_ms"])
                for stage in d["stages"]:
                    stages[name].setdefault(stage["name"], []).append(stage["gpu_ms"])
                if round_index == 0:
                    c = json.loads(run([args.oit, "compare", out, reference, "--tolerance", "2",
                                        "--json"]))
                    errors[name] = c
        for name, _ in variants:
            ratio = statistics.median(t / l for t, l in zip(times[name], times["ll"]))
            s = stages[name]
            insert = f"{statistics.median(s['insert']):.2f}" if "insert" in s else ""
            resolve = f"{statistics.median(s['resolve']):.2f}" if "resolve" in s else ""
            e = errors[name]
            print(f"| {scene} | {name} | {statistics.median(times[name]):.2f} | {ratio:.2f} | "
                  f"{insert} | {resolve} | {e['max_channel_diff']} | "
                  f"{e['over_tolerance_percent']:.3f}% | {e['mean_diff']:.4f} |")


if __name__ == "__main__":
    main()
