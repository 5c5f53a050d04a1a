#!/usr/bin/env python3
"""capabilities.py OIT WORKDIR: every algorithm renders what its capability table
(`oit algorithms --json`) declares and refuses the rest (issue "One shape for
every algorithm").

For every algorithm, every --view value, every --modulation and, where a
modulation measures distance, every --distance: a declared combination renders
(exit 0); an undeclared one is refused before any work with exit 2 and one line
`oit: error: ALGORITHM: ...`, and no image. Renders run two at a time on a
6-triangle scene at 16x16."""
import concurrent.futures
import json
import os
import subprocess
import sys

VIEWS = {"colour": "colour", "heatmap": "heatmap", "peel-limit": "peel-limit:1", "layer": "layer:0",
         "neighbours": "neighbours", "curvature": "curvature", "distance": "distance", "fields": "fields"}
MODULATIONS = ["none", "curvature", "distance", "dist-curv", "fields", "edges"]
DISTANCES = {"adjacent": "adjacent", "skip": "skip:2", "far": "far"}


def main():
    oit, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    model = os.path.join(work, "cyclic.obj")
    subprocess.run([oit, "gen", "cyclic", "--out", model], check=True, capture_output=True)
    listed = json.loads(subprocess.run([oit, "algorithms", "--json"], check=True, capture_output=True,
                                       text=True).stdout)
    names = {a["name"] for a in listed}
    assert len(names) == len(listed) >= 11, names
    cases = []  # (algorithm, what, flags, declared)
    for a in listed:
        assert set(a["views"]) <= set(VIEWS) and "colour" in a["views"], a
        assert set(a["modulations"]) <= set(MODULATIONS) and "none" in a["modulations"], a
        for view, value in VIEWS.items():
            cases.append((a["name"], f"--view {value}", ["--view", value], view in a["views"]))
        for modulation in MODULATIONS:
            cases.append((a["name"], f"--modulation {modulation}", ["--modulation", modulation],
                          modulation in a["modulations"]))
        measuring = [m for m in ("distance", "dist-curv") if m in a["modulations"]]
        if measuring:
            for distance, value in DISTANCES.items():
                cases.append((a["name"], f"--modulation {measuring[0]} --distance {value}",
                              ["--modulation", measuring[0], "--distance", value], distance in a["distances"]))
        else:
            assert a["distances"] == [], a

    def run(case):
        algorithm, what, flags, declared = case
        out = os.path.join(work, f"{algorithm}_{len(what)}_{abs(hash(what))}.png")
        if os.path.exists(out):
            os.remove(out)
        result = subprocess.run([oit, "render", "--model", model, "--algorithm", algorithm, "--size", "16x16",
                                 "--out", out] + flags, capture_output=True, text=True, timeout=300)
        lines = result.stderr.strip().splitlines()
        if declared:
            if result.returncode != 0 or not os.path.exists(out):
                return f"{algorithm} {what}: declared, but exit {result.returncode}: {result.stderr.strip()}"
        elif result.returncode != 2 or len(lines) != 1 or not lines[0].startswith(f"oit: error: {algorithm}: "):
            return f"{algorithm} {what}: undeclared, but exit {result.returncode}, stderr {result.stderr!r}"
        elif os.path.exists(out):
            return f"{algorithm} {what}: refused, yet {out} was written"
        return None

    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        failures = [f for f in pool.map(run, cases) if f]
    declared = sum(1 for c in cases if c[3])
    print(f"{len(cases)} combinations: {declared} declared rendered, {len(cases) - declared} undeclared refused"
          if not failures else "\n".join(failures))
    sys.exit(1 if failures else 0)


main()
