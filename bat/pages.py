"""pages.py: what the scripts that write docs/generated pages share (imported by
accuracy.py, capability_matrix.py and ties_cost.py, which run from bat/)."""
import os
import subprocess
import sys


def commit_of(path):
    """The commit of the checkout holding path (a script, or an oit built in
    it), with -dirty for uncommitted changes: the page's header names it."""
    directory = os.path.dirname(os.path.realpath(path))
    result = subprocess.run(["git", "-C", directory, "describe", "--always", "--dirty"], capture_output=True,
                            text=True)
    return result.stdout.strip() or "unknown"


def scene_models(oit, generated, real_models, work):
    """{name: path}: the generated scenes written into work by `oit gen`,
    then the real models that exist on this machine."""
    models = {}
    for scene in generated:
        path = os.path.join(work, scene + ".obj")
        result = subprocess.run([oit, "gen", scene, "--out", path], capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"failed ({result.returncode}): oit gen {scene}\n{result.stderr}")
        models[scene] = path
    models.update({name: path for name, path in real_models.items() if os.path.exists(path)})
    return models
