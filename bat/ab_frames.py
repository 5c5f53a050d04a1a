#!/usr/bin/env python3
"""ab_frames.py: are two builds' frame times the same? Renders a few bench scenes with
every algorithm through `oit bench`, the builds taking turns (before, after, before, after,
...), and prints per scene and algorithm each build's median frame time and the ratio
after/before, paired round by round (pairing keeps the ratio meaningful when the machine's
speed drifts), with its median and range over the rounds.

With --cpu the figure is CPU time per frame instead of the frame's wall time: each scene and
algorithm runs twice per build and round, with 1 and 1 + --frames frames, llvmpipe rendering on
the calling thread (LP_NUM_THREADS=0), and the difference of the two processes' user + system
time divided by --frames. Other work on the machine slows the wall clock but hardly the CPU time
a process is charged, so this is the measure to use on a shared machine.

    python3 bat/ab_frames.py --before OLD/src/cli/oit --after NEW/src/cli/oit \\
        [--before-shaders DIR] [--after-shaders DIR] [--scene-list build/bench/scenes.txt]
        [--scenes gearbox-general,...] [--algorithms dp,ll,...] [--size 256] [--rounds 3] [--cpu]

The scene list is bat/setup.py's (bat/run_comparison.sh writes it). A refactoring that
leaves the passes alone should give ratios around 1 within their range; the range is the
machine's noise, not a tolerance."""
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
from pages import two_builds_parser

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = "gearbox-general,engine-general,spheres-general,onion-general,spider-general,menger3-general"
ALGORITHMS = "blend,dp,ddp,ll,ib,wboit,kbuffer,mlab,mboit"


def bench(oit, shaders, args, out):
    env = dict(os.environ)
    if shaders:
        env["OIT_SHADER_DIR"] = shaders
    command = [oit, "bench", "--scene-list", args.scene_list, "--scenes", args.scenes, "--algorithms",
               args.algorithms, "--sizes", str(args.size), "--frames", str(args.frames), "--warmup", "1",
               "--reference-max-pixels", "0", "--quiet", "--json", out]
    done = subprocess.run(command, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"ab_frames: {' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
    return {(r["scene"], r["algorithm"]): r["cpu_ms"]["median"] for r in json.load(open(out))["results"]}


def cpu_per_frame(oit, shaders, args, scene, algorithm, out):
    """CPU seconds per frame of one scene and algorithm: two runs, 1 and 1 + frames frames."""
    env = dict(os.environ, LP_NUM_THREADS="0")
    if shaders:
        env["OIT_SHADER_DIR"] = shaders
    spent = []
    for frames in (1, 1 + args.frames):
        command = [oit, "bench", "--scene-list", args.scene_list, "--scenes", scene, "--algorithms", algorithm,
                   "--sizes", str(args.size), "--frames", str(frames), "--warmup", "0",
                   "--reference-max-pixels", "0", "--quiet", "--json", out]
        # getrusage, not os.times: the kernel's own CPU time in microseconds, not clock ticks
        start = resource.getrusage(resource.RUSAGE_CHILDREN)
        done = subprocess.run(command, env=env, capture_output=True, text=True)
        end = resource.getrusage(resource.RUSAGE_CHILDREN)
        if done.returncode != 0:
            sys.exit(f"ab_frames: {' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
        spent.append((end.ru_utime - start.ru_utime) + (end.ru_stime - start.ru_stime))
    return 1000.0 * (spent[1] - spent[0]) / args.frames


def bench_cpu(oit, shaders, args, out):
    return {(scene, algorithm): cpu_per_frame(oit, shaders, args, scene, algorithm, out)
            for scene in args.scenes.split(",") for algorithm in args.algorithms.split(",")}


def main():
    parser = two_builds_parser(__doc__)
    parser.add_argument("--scene-list", default=os.path.join(ROOT, "build", "bench", "scenes.txt"))
    parser.add_argument("--scenes", default=SCENES)
    parser.add_argument("--algorithms", default=ALGORITHMS)
    parser.add_argument("--size", type=int, default=256)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--cpu", action="store_true", help="CPU time per frame instead of wall time")
    args = parser.parse_args()
    measure = bench_cpu if args.cpu else bench
    rounds = []
    with tempfile.TemporaryDirectory(prefix="oit-ab-") as work:
        for r in range(args.rounds):
            before = measure(args.before, args.before_shaders, args, os.path.join(work, f"a{r}.json"))
            after = measure(args.after, args.after_shaders, args, os.path.join(work, f"b{r}.json"))
            rounds.append((before, after))
            print(f"ab_frames: round {r + 1} of {args.rounds} done", file=sys.stderr)
    keys = [k for k in rounds[0][0] if all(k in a and k in b for a, b in rounds)]
    unit = "CPU ms per frame" if args.cpu else "ms"
    print(f"| scene | algorithm | before {unit} | after {unit} | after/before (median, range over {args.rounds} rounds) |")
    print("| --- | --- | ---: | ---: | --- |")
    all_ratios = []
    for key in keys:
        ratios = [b[key] / a[key] for a, b in rounds if a[key] > 0]
        all_ratios.append(statistics.median(ratios))
        print(f"| {key[0]} | {key[1]} | {statistics.median(a[key] for a, _ in rounds):.2f} | "
              f"{statistics.median(b[key] for _, b in rounds):.2f} | {statistics.median(ratios):.3f} "
              f"({min(ratios):.3f}-{max(ratios):.3f}) |")
    print(f"\n{len(keys)} runs; the median of their median ratios {statistics.median(all_ratios):.3f}, "
          f"from {min(all_ratios):.3f} to {max(all_ratios):.3f}")
    if args.cpu:
        # a frame of a few ms is lost in the difference of two processes' start-up CPU time
        steady = [statistics.median(b[key] / a[key] for a, b in rounds if a[key] > 0) for key in keys
                  if statistics.median(a[key] for a, _ in rounds) >= 20.0]
        if steady:
            print(f"{len(steady)} runs of 20 ms of CPU a frame or more: the median of their median ratios "
                  f"{statistics.median(steady):.3f}, from {min(steady):.3f} to {max(steady):.3f}")


if __name__ == "__main__":
    main()
