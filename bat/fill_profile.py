#!/usr/bin/env python3
"""fill_profile.py: where a linked-list fill fragment's time goes, by ablation.

Debian's Mesa is a release build: llvmpipe's LP_DEBUG and GALLIVM_DEBUG (shader
dumps, perf maps of the JIT code) are compiled out, so perf sees the shaders as
anonymous memory and can say only that ~3/4 of the time is in JIT code
(bat/profile.sh). This script takes the fill apart instead: it copies the shader
tree, removes one piece of ll/fill.frag at a time and times the fill stage of
each variant on the same frame, alternating the variants in rounds (so a busy
machine slows them alike) and taking the median over rounds:

    raster      an empty fragment shader: rasterization and shader invocation
    shade       + the shading every algorithm does (blend's draw does the same)
    counter     + the node index from the atomic fragment counter
    depth       + the canonical depth (common/canonical_depth.glsl), computed but not stored
    node        + the 16-byte node store (colour, depth, triangle)
    exchange    + the head swap (imageAtomicExchange)
    full        + the next-pointer store: ll/fill.frag as shipped

Each step's cost is its fill time minus the step before it, per fragment.
blend's draw stage on the same frame is printed beside it. Variants that do not
link the lists count on a spare counter, so the frame's checks still pass.
Run from the repository root:

    python3 bat/fill_profile.py [--oit build/src/cli/oit] [--size 400x400] [--rounds 5]
        [--frames 5] [--scenes gearbox,spheres,onion]

Scenes are `oit gen` output, written to a temporary directory.
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPARE = "ll_counters[OIT_LL_COUNTER_MAX_DISTANCE]"  # used only by the distance modulation
FRAGMENTS = "ll_counters[OIT_FRAME_COUNTER_FRAGMENTS]"
COUNTER = "uint node = atomicAdd(ll_counters[OIT_FRAME_COUNTER_FRAGMENTS], 1u);"
NODE = "ll_nodes[node] = ll_pack_node(colour, oit_canonical_depth(), uint(gl_PrimitiveID));"
LINK = "ll_next[node] = imageAtomicExchange(ll_heads, ivec2(gl_FragCoord.xy), node);"
# the same atomic, swapping in the end marker so the heads stay empty
EXCHANGE = "if (node < 0xFFFFFFFFu) imageAtomicExchange(ll_heads, ivec2(gl_FragCoord.xy), OIT_LIST_END);"
KEEP_SHADING = "if (colour.r + colour.a < -1.0) atomicAdd(" + SPARE + ", 1u); return;"
STEPS = ["raster", "shade", "counter", "depth", "node", "exchange", "full"]
# (a test the compiler cannot fold: clamp(s, 0, 1) < -1 would be, and the depth with it)
KEEP_DEPTH = "if (floatBitsToUint(oit_canonical_depth()) == 0x2345u) atomicAdd(" + SPARE + ", 2u);"
SCENES = {"gearbox": ("gearbox", 24, "--orbit 30,20"), "spheres": ("spheres", 3, "--orbit 30,20"),
          "onion": ("onion", 8, "--orbit 30,20")}


def variant_source(original, step):
    """ll/fill.frag with everything after `step` removed."""
    for needed in (COUNTER, NODE, LINK):
        if needed not in original:
            sys.exit(f"fill_profile.py: ll/fill.frag no longer contains '{needed}'; update the script")
    source = original
    if step == "full":
        return source
    if step == "exchange":
        return source.replace(LINK, EXCHANGE).replace(COUNTER, COUNTER.replace(FRAGMENTS, SPARE))
    # the lists stay empty: count on the spare counter so the sort's check still holds
    source = source.replace(LINK, "").replace(COUNTER, COUNTER.replace(FRAGMENTS, SPARE))
    if step == "node":
        return source
    source = source.replace(NODE, KEEP_DEPTH)
    if step == "depth":
        return source
    source = source.replace(KEEP_DEPTH, "")
    if step == "counter":
        return source
    start = source.index("uint node = atomicAdd")
    end = source.index("}", start)
    source = source[:start] + KEEP_SHADING + "\n" + source[end:]
    if step == "shade":
        return source
    body = source.index("void main()")
    return source[:body] + "void main()\n{\n    if (gl_FragCoord.x < -1.0) atomicAdd(" + SPARE + ", 1u);\n}\n"


def render(oit, shader_dir, model, view, algorithm, size, frames, pool):
    command = [oit, "render", "--model", model, *view.split(), "--algorithm", algorithm, "--size", size,
               "--frames", str(frames), "--json"]
    if pool:
        command += ["--fragment-pool", str(pool)]
    environment = dict(os.environ, OIT_SHADER_DIR=shader_dir)
    result = subprocess.run(command, capture_output=True, text=True, env=environment)
    if result.returncode != 0:
        sys.exit(f"fill_profile.py: failed ({result.returncode}): {' '.join(command)}\n{result.stderr}")
    figures = json.loads(result.stdout)
    return figures, {stage["name"]: stage["gpu_ms"] for stage in figures["stages"]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--oit", default=os.path.join(ROOT, "build/src/cli/oit"))
    parser.add_argument("--size", default="400x400")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--scenes", default="gearbox,spheres,onion")
    parser.add_argument("--json", help="also write the figures here")
    args = parser.parse_args()
    scenes = args.scenes.split(",")
    for scene in scenes:
        if scene not in SCENES:
            sys.exit(f"fill_profile.py: unknown scene '{scene}' ({', '.join(SCENES)})")
    with tempfile.TemporaryDirectory() as work:
        original = open(os.path.join(ROOT, "shaders/ll/fill.frag")).read()
        trees = {}
        for step in STEPS:
            tree = os.path.join(work, "shaders-" + step)
            shutil.copytree(os.path.join(ROOT, "shaders"), tree)
            with open(os.path.join(tree, "ll/fill.frag"), "w") as out:
                out.write(variant_source(original, step))
            trees[step] = tree
        results = []
        print(f"Fill stage of `ll` by ablation at {args.size}, median over {args.rounds} rounds of "
              f"--frames {args.frames} (`python3 bat/fill_profile.py --size {args.size} --rounds {args.rounds} "
              f"--frames {args.frames} --scenes {args.scenes}`)\n")
        print("| scene | fragments | blend draw | " + " | ".join(STEPS) + " | full / blend draw |")
        print("| --- | ---: | ---: | " + " | ".join("---:" for _ in STEPS) + " | ---: |")
        for scene in scenes:
            kind, complexity, view = SCENES[scene]
            model = os.path.join(work, scene + ".obj")
            subprocess.run([args.oit, "gen", kind, "--complexity", str(complexity), "--out", model],
                           check=True, capture_output=True)
            full, _ = render(args.oit, trees["full"], model, view, "ll", args.size, 2, 0)
            fragments = full["fragments"]
            pool = int(fragments * 1.1) + 1024
            times = {step: [] for step in STEPS + ["blend"]}
            for _ in range(args.rounds):
                _, stages = render(args.oit, trees["full"], model, view, "blend", args.size, args.frames, 0)
                times["blend"].append(stages["draw"])
                for step in STEPS:
                    _, stages = render(args.oit, trees[step], model, view, "ll", args.size, args.frames, pool)
                    times[step].append(stages["fill"])
            median = {step: statistics.median(values) for step, values in times.items()}
            row = {"scene": scene, "fragments": fragments, "ms": median,
                   "ns_per_fragment": {}}
            previous = 0.0
            cells = []
            for step in STEPS:
                increment = median[step] - previous
                row["ns_per_fragment"][step] = increment * 1e6 / fragments
                cells.append(f"{median[step]:.2f} ms (+{increment * 1e6 / fragments:.0f} ns)")
                previous = median[step]
            results.append(row)
            print(f"| {scene} | {fragments:,} | {median['blend']:.2f} ms | " + " | ".join(cells) +
                  f" | {median['full'] / median['blend']:.2f} |")
        print("\nEach cell: the fill stage's median time, and in brackets what this step adds per fragment "
              "(its time minus the previous column's, over the frame's fragments).")
        if args.json:
            with open(args.json, "w") as out:
                json.dump({"size": args.size, "rounds": args.rounds, "frames": args.frames, "scenes": results},
                          out, indent=1)


if __name__ == "__main__":
    main()
