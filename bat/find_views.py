#!/usr/bin/env python3
"""find_views.py: finds each model's 'longest' view for config/bench-scenes.json.

The thesis measured every model in a general view and in the view with the longest
per-pixel lists. This tries orbits of the default camera (azimuth every 30 degrees,
elevation -60..60 every 30) with `oit bench --algorithms ll` at 128x128 and keeps,
per model, the orbit with the longest list (ties: the larger Psi, then more fragments).
It rewrites the config's "longest" views; run it after adding a model:

    python3 bat/find_views.py [--build build] [--models a,b]
"""
import argparse
import csv
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import setup  # noqa: E402  (model sources)

AZIMUTHS = range(0, 360, 30)
ELEVATIONS = (-60, -30, 0, 30, 60)


def write_config(path, config):
    """The config with one model per line (as it is kept in the repository)."""
    lines = ["{"]
    for key, value in config.items():
        if key == "models":
            continue
        lines.append(f"  {json.dumps(key)}: {json.dumps(value)},")
    lines.append('  "models": [')
    models = [f"    {json.dumps(m)}" for m in config["models"]]
    lines.append(",\n".join(models))
    lines.append("  ]")
    lines.append("}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default=os.path.join(setup.ROOT, "build"))
    parser.add_argument("--config", default=setup.CONFIG)
    parser.add_argument("--models", help="comma-separated model names (default: all)")
    parser.add_argument("--size", default="128")
    args = parser.parse_args()
    oit = os.path.join(args.build, "src", "cli", "oit")
    config = json.load(open(args.config))
    cache = os.path.join(args.build, "bench", "models")
    os.makedirs(cache, exist_ok=True)
    wanted = set(args.models.split(",")) if args.models else None
    candidates = os.path.join(args.build, "bench", "view-candidates.txt")
    with open(candidates, "w") as f:
        for model in config["models"]:
            if wanted and model["name"] not in wanted:
                continue
            path = setup.model_path(oit, model, cache)
            if not path:
                continue
            for az in AZIMUTHS:
                for el in ELEVATIONS:
                    f.write(f"{model['name']}@{az},{el} {path} --orbit {az},{el}\n")
    result = subprocess.run([oit, "bench", "--scene-list", candidates, "--algorithms", "ll", "--sizes", args.size,
                             "--frames", "1", "--warmup", "0", "--reference-max-pixels", "0", "--quiet"],
                            capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"find_views: oit bench failed:\n{result.stderr}")
    best = {}
    for row in csv.DictReader(result.stdout.splitlines()):
        name, orbit = row["scene"].split("@")
        key = (int(row["max_list"]), float(row["psi"]), int(row["fragments"]))
        if name not in best or key > best[name][0]:
            best[name] = (key, orbit)
    for model in config["models"]:
        if model["name"] in best:
            (max_list, psi, fragments), orbit = best[model["name"]]
            model["views"]["longest"] = f"--orbit {orbit}"
            print(f"{model['name']}: --orbit {orbit}: longest list {max_list}, psi {psi:.3f}, "
                  f"{fragments} fragments at {args.size}x{args.size}")
    write_config(args.config, config)


if __name__ == "__main__":
    main()
