"""pages.py: what the scripts that write generated pages share (imported by
accuracy.py, capability_matrix.py, ties_cost.py and report.py, which run from bat/):
the commit and the machine a page names, the scenes it renders, and the
comparison of a regenerated page with the committed one (tests/generated_pages.sh).

    python3 bat/pages.py machine [--oit OIT] [--backend egl]   # the machine as JSON (bat/run_comparison.sh)
    python3 bat/pages.py diff COMMITTED REGENERATED            # exit 1 and a diff when they differ
"""
import argparse
import difflib
import json
import os
import platform
import re
import subprocess
import sys
import tempfile

# As gl_timer.c's software_renderer(): these renderers are timed by wall clock
# between glFinish() calls, every other one by GL_TIME_ELAPSED queries.
SOFTWARE_RENDERERS = ("llvmpipe", "softpipe", "swrast")


def two_builds_parser(doc):
    """The command line of a script comparing two builds (ab_frames.py, image_matrix.py): their
    binaries (--before, --after) and, where not beside their source trees, their shader trees."""
    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--before", required=True)
    parser.add_argument("--after", required=True)
    parser.add_argument("--before-shaders")
    parser.add_argument("--after-shaders")
    return parser


def commit_of(path):
    """The commit of the checkout holding path (a script, or an oit built in
    it), with -dirty for uncommitted changes: the page's header names it."""
    directory = os.path.dirname(os.path.realpath(path))
    result = subprocess.run(["git", "-C", directory, "describe", "--always", "--dirty"], capture_output=True,
                            text=True)
    return result.stdout.strip() or "unknown"


def commits(script, oit):
    """'X', or 'X (oit) / Y (script)' when the oit that rendered the page was
    built in another checkout than the script's."""
    of_oit, of_script = commit_of(oit), commit_of(script)
    return of_oit if of_oit == of_script else f"{of_oit} (oit) / {of_script} (script)"


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


# ----------------------------------------------------------------- the machine

def software_renderer(renderer):
    return any(name in (renderer or "") for name in SOFTWARE_RENDERERS)


def _cpuinfo():
    try:
        with open("/proc/cpuinfo") as f:
            return f.read()
    except OSError:
        return ""


def cpu_model():
    match = re.search(r"^model name\s*:\s*(.+)$", _cpuinfo(), re.M)
    return match.group(1).strip() if match else (platform.processor() or "unknown CPU")


def logical_cpus():
    """The CPUs this process may run on (what nproc prints)."""
    try:
        return len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        return os.cpu_count() or 0


def virtual_machine():
    """True when the CPU flags say a hypervisor runs this machine."""
    match = re.search(r"^flags\s*:\s*(.+)$", _cpuinfo(), re.M)
    return bool(match) and "hypervisor" in match.group(1).split()


def mesa_version():
    try:
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "libgl1-mesa-dri"], capture_output=True,
                             text=True).stdout
        return out.strip() or None
    except OSError:
        return None


def gl_renderer(oit, backend="egl"):
    """GL_RENDERER as `oit render --json` reports it (a tiny generated scene)."""
    with tempfile.TemporaryDirectory(prefix="oit-machine-") as work:
        model = os.path.join(work, "cyclic.obj")
        if subprocess.run([oit, "gen", "cyclic", "--out", model], capture_output=True).returncode != 0:
            return None
        result = subprocess.run([oit, "render", "--model", model, "--algorithm", "blend", "--size", "8x8",
                                 "--backend", backend, "--json", "--out", os.path.join(work, "x.png")],
                                capture_output=True, text=True)
        try:
            return json.loads(result.stdout).get("renderer")
        except json.JSONDecodeError:
            return None


def machine(oit=None, backend="egl"):
    """The machine as measured now: what a page whose figures are timings names."""
    return {
        "cpu": cpu_model(),
        "logical_cpus": logical_cpus(),
        "virtual_machine": virtual_machine(),
        "kernel": f"{platform.system()} {platform.release()}",
        "mesa": mesa_version(),
        "lp_num_threads": os.environ.get("LP_NUM_THREADS") or None,
        "renderer": gl_renderer(oit, backend) if oit else None,
        "backend": backend,
        "commit": commit_of(oit) if oit else None,  # of the checkout the oit was built in
    }


def machine_line(info, renderers, backends):
    """'Machine: CPU, N logical CPUs (a virtual machine), kernel; GL renderer R (Mesa V), egl back end.'
    renderers and backends: what the page's renders reported."""
    renderer = ", ".join(sorted(r for r in renderers if r)) or "none reported"
    backend = ", ".join(sorted(b for b in backends if b)) or "no"
    vm = " (a virtual machine)" if info.get("virtual_machine") else ""
    return (f"Machine: {info['cpu']}, {info['logical_cpus']} logical CPUs{vm}, {info['kernel']}; "
            f"GL renderer {renderer}" + (f" (Mesa {info['mesa']})" if info.get("mesa") else "")
            + f", {backend} back end.")


# ----------------------------------------------------------------- committed against regenerated

GENERATED_LINE = re.compile(r"^Generated by ")
DATE = re.compile(r" on \d{4}-\d{2}-\d{2}")
_REV = r"(?:[0-9a-f]{7,40}(?:-dirty)?|unknown)"  # what commit_of() gives
COMMIT = re.compile(rf"commit {_REV}(?: \((?:oit|benchmark)\) / {_REV} \((?:script|report)\))?")
JOBS = re.compile(r" --jobs \d+")
NUMBERS = re.compile(r"^\s*-?\d+(\.\d+)?( / -?\d+(\.\d+)?)*\s*$")


def _cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def normalise(text):
    """The page with what legitimately varies between two runs on one tree
    replaced by placeholders: the date, commit and --jobs of the 'Generated by' line,
    the 'Machine:' line, and the numbers of the table columns headed 'ms'
    (wall times: they vary between runs, see docs/testing.md). Everything else,
    the command included, must be equal."""
    out, timing_columns, in_table = [], set(), False
    lines = text.split("\n")
    for k, line in enumerate(lines):
        if GENERATED_LINE.match(line):
            # --jobs (capability_matrix.py) changes only the timings
            line = COMMIT.sub("commit <commit>", DATE.sub(" on <date>", JOBS.sub("", line)))
        elif line.startswith("Machine: "):
            line = "Machine: <machine>"
        elif line.startswith("|"):
            cells = _cells(line)
            following = lines[k + 1] if k + 1 < len(lines) else ""
            if not in_table and re.match(r"^\|\s*:?-", following):
                # a header: the columns whose name starts with "ms" hold timings
                timing_columns = {i for i, c in enumerate(cells) if re.match(r"^ms\b", c)}
            elif timing_columns and not re.match(r"^\|\s*:?-", line):
                cells = ["<ms>" if i in timing_columns and NUMBERS.match(c) else c for i, c in enumerate(cells)]
                line = "| " + " | ".join(cells) + " |"
            in_table = True
        else:
            in_table, timing_columns = False, set()
        out.append(line)
    return out


def diff_pages(committed, regenerated):
    """The unified diff of the normalised pages (empty when they agree)."""
    with open(committed) as f:
        a = normalise(f.read())
    with open(regenerated) as f:
        b = normalise(f.read())
    return list(difflib.unified_diff(a, b, committed, regenerated, lineterm="", n=1))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    m = sub.add_parser("machine", help="the machine as JSON")
    m.add_argument("--oit", help="an oit to ask for the GL renderer")
    m.add_argument("--backend", default="egl")
    d = sub.add_parser("diff", help="exit 1 when two pages differ beyond what varies between runs")
    d.add_argument("committed")
    d.add_argument("regenerated")
    args = parser.parse_args()
    if args.command == "machine":
        json.dump(machine(args.oit, args.backend), sys.stdout, indent=1)
        print()
        return 0
    lines = diff_pages(args.committed, args.regenerated)
    if lines:
        print("\n".join(lines))
        print(f"{args.committed} differs from a regeneration ({args.regenerated}) beyond the commit, date, machine "
              "and timings", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
