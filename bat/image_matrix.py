#!/usr/bin/env python3
"""image_matrix.py: are two builds' images byte-identical? (issue "One shape for
every algorithm": a redesign changes no image)

    python3 bat/image_matrix.py --before OLD/src/cli/oit --after NEW/src/cli/oit [--quick]

Renders, with each build, the test suite's scenes (the six generated ones and
Debian's spider, WusonOBJ and 2CylinderEngine) x every algorithm x the
options it declares (`oit algorithms --json` of the after build: its views,
modulations, distances and parameters: --sort array, --layers 4 and 64, every
--moments), plus a local modulation (a faded part, a focus point), at 96x96,
and `oit demo` at 96x96; compares the PNGs byte for byte and prints the
count. Each build uses its own shader tree (beside its binary's source tree,
or --before-shaders / --after-shaders). Exit 1 if any image differs or a render
fails in one build and not the other. --quick: three scenes."""
import concurrent.futures
import filecmp
import json
import os
import subprocess
import sys
import tempfile
from pages import two_builds_parser

SCENES = ["cyclic", "onion", "spheres", "gearbox", "coplanar", "menger"]
REAL = {"spider": "/usr/share/assimp/models/OBJ/spider.obj",
        "wuson": "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
        "engine": "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}
VIEW_VALUES = {"heatmap": "heatmap", "peel-limit": "peel-limit:2", "layer": "layer:1", "neighbours": "neighbours",
               "curvature": "curvature", "distance": "distance", "fields": "fields"}


def variants(algorithm):
    """Every option combination worth a picture for one algorithm: (label, flags)."""
    out = [("plain", []), ("faded", ["--component-alpha", "0=0.2"]), ("focus", ["--focus-point", "0,0,0"])]
    for view in algorithm["views"]:
        if view != "colour":
            out.append((f"view-{view}", ["--view", VIEW_VALUES[view]]))
    for modulation in algorithm["modulations"]:
        if modulation != "none":
            out.append((f"mod-{modulation}", ["--modulation", modulation]))
    if "distance" in algorithm["modulations"]:
        for distance in algorithm["distances"]:
            if distance != "adjacent":
                value = "skip:2" if distance == "skip" else distance
                out.append((f"distance-{distance}", ["--modulation", "distance", "--distance", value]))
    if "--sort" in algorithm["options"]:
        out.append(("sort-array", ["--sort", "array"]))
    if "--layers" in algorithm["options"]:
        out += [("layers4", ["--layers", "4"]), ("layers64", ["--layers", "64"])]
    if "--moments" in algorithm["options"]:
        out += [("power6", ["--moments", "power6"]), ("trig3", ["--moments", "trig3"])]
    return out


def shader_dir(oit, given):
    if given:
        return given
    # BUILD/src/cli/oit -> the source tree's shaders (a build dir inside the tree)
    return os.path.normpath(os.path.join(os.path.dirname(oit), "..", "..", "..", "shaders"))


def main():
    parser = two_builds_parser(__doc__)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    builds = {"before": (args.before, shader_dir(args.before, args.before_shaders)),
              "after": (args.after, shader_dir(args.after, args.after_shaders))}
    work = tempfile.mkdtemp(prefix="oit-image-matrix-")
    algorithms = json.loads(subprocess.run([args.after, "algorithms", "--json"], check=True, capture_output=True,
                                           text=True).stdout)
    models = {}
    for scene in (SCENES[:3] if args.quick else SCENES):
        models[scene] = os.path.join(work, scene + ".obj")
        subprocess.run([args.after, "gen", scene, "--out", models[scene]], check=True, capture_output=True)
    if not args.quick:
        models.update({k: v for k, v in REAL.items() if os.path.exists(v)})

    jobs = []
    for scene, model in models.items():
        for algorithm in algorithms:
            for label, flags in variants(algorithm):
                for build in builds:
                    name = f"{scene}_{algorithm['name']}_{label}"
                    jobs.append((build, name, [os.path.abspath(builds[build][0]), "render", "--model", model,
                                               "--algorithm", algorithm["name"], "--size", "96x96",
                                               "--out", os.path.join(work, build, name + ".png")] + flags))
    for build in builds:
        os.makedirs(os.path.join(work, build), exist_ok=True)

    def run(job):
        build, name, command = job
        env = dict(os.environ, OIT_SHADER_DIR=builds[build][1])
        result = subprocess.run(command, capture_output=True, text=True, env=env)
        return build, name, result.returncode

    codes = {}
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        for build, name, code in pool.map(run, jobs):
            codes[build, name] = code
    for build, (oit, shaders) in builds.items():
        done = subprocess.run([oit, "demo", "--size", "96x96", "--out", os.path.join(work, build, "demo")],
                              capture_output=True, text=True, env=dict(os.environ, OIT_SHADER_DIR=shaders))
        if done.returncode != 0:
            sys.exit(f"image_matrix: {oit} demo failed ({done.returncode}): {done.stderr.strip()}")

    names = sorted({name for _, name in codes})
    same = differ = failed = 0
    for name in names:
        a, b = codes["before", name], codes["after", name]
        if a != b:
            print(f"exit {a} before, {b} after: {name}")
            failed += 1
        elif a == 0:
            if filecmp.cmp(os.path.join(work, "before", name + ".png"), os.path.join(work, "after", name + ".png"),
                           shallow=False):
                same += 1
            else:
                print(f"differs: {name}")
                differ += 1
    demo = sorted(os.listdir(os.path.join(work, "after", "demo")))
    for png in demo:
        if filecmp.cmp(os.path.join(work, "before", "demo", png), os.path.join(work, "after", "demo", png),
                       shallow=False):
            same += 1
        else:
            print(f"differs: demo/{png}")
            differ += 1
    refused = sum(1 for name in names if codes["after", name] != 0)
    print(f"{same} images byte-identical, {differ} differ, {failed} renders that failed in one build only "
          f"({len(names)} renders and {len(demo)} demo images per build; {refused} refused in both); {work}")
    sys.exit(1 if differ or failed else 0)


main()
