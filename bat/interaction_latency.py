#!/usr/bin/env python3
"""interaction_latency.py: how soon a drag shows motion in the workbench, before and after.

For each scene and algorithm, the workbench's window (QT_QPA_PLATFORM=offscreen)
loads the model, waits for the full frame, then replays a left-button drag
across the view (a move every 16 ms) and measures, with oit-interaction-probe
(src/app/interaction_probe.cpp):
  first motion   from the drag's first move to the first frame of the moved
                 camera reaching the view, and which frame that was
                 (algorithm, 1/N scale);
  frames         frames shown while the drag lasts, and the longest gap;
  refined        from the release to the chosen algorithm's full frame.
The same probe is built against an older commit (default: main) in
BUILD/interaction-before (git archive, the probe added to its CMakeLists; ccache
is used when CCACHE_DIR is set), and each case runs before, then after, one
after the other, so a busy machine slows both alike. Prints a markdown table and,
with --json, every probe's JSON line. Run from the repository root:

    python3 bat/interaction_latency.py [--build build] [--before main] [--size 1200x760]
        [--drag-ms 1500] [--algorithms dp,ll,ib] [--scenes engine,spheres] [--json FILE]

Scenes: engine = Khronos' 2CylinderEngine (Debian's assimp-testmodels), spheres =
`oit gen spheres --complexity 8` (512 spheres), written to BUILD/interaction-scenes.
Goals (issue 27): first motion within 100 ms on the engine, 250 ms on the spheres.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile

ENGINE = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
GOALS_MS = {"engine": 100.0, "spheres": 250.0}
PROBE_CMAKE = """
# added by bat/interaction_latency.py: the probe, built against this older tree
add_executable(oit-interaction-probe interaction_probe.cpp)
target_link_libraries(oit-interaction-probe PRIVATE oit_workbench_lib)
"""


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(command)}\n{result.stdout[-2000:]}\n{result.stderr[-2000:]}")
    return result.stdout


def cmake_launchers():
    if shutil.which("ccache"):
        return ["-DCMAKE_C_COMPILER_LAUNCHER=ccache", "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache"]
    return []


def build_before(build, commit):
    """The probe built against commit's sources; returns its path."""
    sha = run(["git", "rev-parse", "--verify", commit + "^{commit}"]).strip()
    root = os.path.join(build, "interaction-before")
    source, binary = os.path.join(root, "src"), os.path.join(root, "build")
    stamp = os.path.join(root, "commit")
    if not (os.path.exists(stamp) and open(stamp).read().strip() == sha):
        shutil.rmtree(root, ignore_errors=True)
        os.makedirs(source)
        archive = subprocess.run(["git", "archive", sha], capture_output=True, check=True).stdout
        subprocess.run(["tar", "-x", "-C", source], input=archive, check=True)
        shutil.copy("src/app/interaction_probe.cpp", os.path.join(source, "src/app"))
        with open(os.path.join(source, "src/app/CMakeLists.txt"), "a") as f:
            f.write(PROBE_CMAKE)
        run(["cmake", "-S", source, "-B", binary, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=RelWithDebInfo"] +
            cmake_launchers())
        with open(stamp, "w") as f:
            f.write(sha + "\n")
    run(["ninja", "-C", binary, "-j2", "oit-interaction-probe"])
    return os.path.join(binary, "src/app/oit-interaction-probe"), sha


def scene_paths(build, names):
    directory = os.path.join(build, "interaction-scenes")
    os.makedirs(directory, exist_ok=True)
    paths = {}
    for name in names:
        if name == "engine":
            paths[name] = ENGINE
        elif name == "spheres":
            path = os.path.join(directory, "spheres8.obj")
            if not os.path.exists(path):
                run([os.path.join(build, "src/cli/oit"), "gen", "spheres", "--complexity", "8", "--out", path])
            paths[name] = path
        else:
            sys.exit(f"unknown scene {name} (engine, spheres)")
    return paths


def probe(program, model, algorithm, size, drag_ms, home):
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen", XDG_CONFIG_HOME=os.path.join(home, "config"),
               XDG_RUNTIME_DIR=os.path.join(home, "runtime"), DBUS_SESSION_BUS_ADDRESS="disabled:")
    os.makedirs(env["XDG_RUNTIME_DIR"], mode=0o700, exist_ok=True)
    out = run([program, model, algorithm, size, str(drag_ms)], env=env)
    lines = [line for line in out.splitlines() if line.startswith("{")]
    return json.loads(lines[-1])


def describe(r):
    first = r["first_motion"]
    scale = "" if first["coarse_scale"] == 1 else f" 1/{first['coarse_scale']}"
    return (f"{r['first_motion_ms']:.0f} ms ({first['algorithm']}{scale}), {r['frames_during_drag']} frames, "
            f"gap {r['longest_gap_ms']:.0f} ms, refined {r['refined_ms'] / 1000:.1f} s")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--before", default="main", help="the commit to compare with (default main)")
    parser.add_argument("--size", default="1200x760")
    parser.add_argument("--drag-ms", type=int, default=1500)
    parser.add_argument("--algorithms", default="dp,ll,ib")
    parser.add_argument("--scenes", default="engine,spheres")
    parser.add_argument("--json", help="write every probe's result here")
    args = parser.parse_args()

    run(["ninja", "-C", args.build, "-j2", "oit-interaction-probe", "oit"])
    after = os.path.join(args.build, "src/app/oit-interaction-probe")
    before, before_sha = build_before(args.build, args.before)
    after_sha = run(["git", "rev-parse", "HEAD"]).strip()
    dirty = run(["git", "status", "--porcelain", "--untracked-files=no"]).strip() != ""
    scenes = scene_paths(args.build, args.scenes.split(","))
    results = []
    print(f"before: {args.before} {before_sha[:7]}; after: HEAD {after_sha[:7]}{' (uncommitted changes)' if dirty else ''}; "
          f"{args.size}, drag {args.drag_ms} ms", flush=True)
    print("| scene | algorithm | before: first motion | after: first motion | goal | met after |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as home:
        for scene, model in scenes.items():
            for algorithm in args.algorithms.split(","):
                row = {}
                for label, program in (("before", before), ("after", after)):
                    r = probe(program, model, algorithm, args.size, args.drag_ms, home)
                    r.update(scene=scene, build=label, commit=before_sha if label == "before" else after_sha)
                    results.append(r)
                    row[label] = r
                goal = GOALS_MS.get(scene)
                met = "yes" if goal and row["after"]["first_motion_ms"] <= goal else "no"
                print(f"| {scene} | {algorithm} | {describe(row['before'])} | {describe(row['after'])} | "
                      f"{goal:.0f} ms | {met} |", flush=True)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)


if __name__ == "__main__":
    main()
