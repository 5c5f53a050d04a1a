#!/usr/bin/env python3
"""interrupted_outputs.py OIT WORK SCENES: a run interrupted by SIGTERM, SIGINT
or SIGHUP at any point leaves no temporary (FILE.tmp.*, a bundle's DIR.tmp.*)
and the previous outputs byte for byte, and dies by that signal; a run killed
with SIGKILL, where nothing can run, leaves its temporaries, and the next run
of the same output removes them, but not those of a run still going.

The points: while the model loads and the context is made (before any
temporary exists), while a PNG is written (its temporary exists: the test waits
for it, polling every millisecond), and for oit bench after its first rows and
images and again after more of them. About 25 s.
"""
import glob
import os
import shutil
import signal
import subprocess
import sys
import time


def fail(message):
    print(f"FAIL: {message}", file=sys.stderr)
    sys.exit(1)


def snapshot(paths):
    """{path: bytes} of the files, and of the files in the folders, among paths."""
    state = {}
    for path in paths:
        if os.path.isdir(path):
            for name in sorted(os.listdir(path)):
                with open(os.path.join(path, name), "rb") as f:
                    state[os.path.join(path, name)] = f.read()
        else:
            with open(path, "rb") as f:
                state[path] = f.read()
    return state


def temporaries(folder):
    return sorted(os.path.relpath(p, folder) for p in glob.glob(os.path.join(folder, "**", "*.tmp.*"), recursive=True))


def wait_for(condition, process, what, timeout=60.0):
    """Polls every millisecond until condition() holds; fails if the run ends first."""
    deadline = time.monotonic() + timeout
    while not condition():
        if process.poll() is not None:
            fail(f"the run ended (status {process.returncode}) before {what}")
        if time.monotonic() > deadline:
            process.kill()
            fail(f"no {what} within {timeout:.0f} s")
        time.sleep(0.001)


def default_signals():
    """In the child: the signals as a terminal would deliver them (a test started in the
    background of a shell inherits SIGINT ignored, which oit rightly keeps ignored)."""
    for number in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP):
        signal.signal(number, signal.SIG_DFL)


def start(command):
    return subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, preexec_fn=default_signals)


def interrupt(process, number, label):
    process.send_signal(number)
    try:
        _, err = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        process.kill()
        fail(f"{label}: no end within 60 s of {signal.Signals(number).name}")
    if process.returncode != -number:
        fail(f"{label}: status {process.returncode}, not death by {signal.Signals(number).name}: {err.decode()!r}")


def main():
    oit, work, scenes = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    model = os.path.join(scenes, "onion.obj")
    checked = 0

    # --- oit render --out: a large frame, so that its PNG takes a while to write ---
    out = os.path.join(work, "o.png")
    subprocess.run([oit, "render", "--model", model, "--algorithm", "reference", "--size", "16x16", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    before = snapshot([out])
    render = [oit, "render", "--model", model, "--algorithm", "blend", "--size", "2048x2048", "--out", out]
    writing = lambda: glob.glob(out + ".tmp.*")
    for number, point in [(signal.SIGTERM, "early"), (signal.SIGTERM, "write"), (signal.SIGINT, "early"),
                          (signal.SIGINT, "write"), (signal.SIGHUP, "write")]:
        label = f"render, {signal.Signals(number).name} {'while loading' if point == 'early' else 'during the PNG write'}"
        process = start(render)
        if point == "early":
            time.sleep(0.1)
        else:
            wait_for(writing, process, "the PNG's temporary file")
        interrupt(process, number, label)
        if snapshot([out]) != before:
            fail(f"{label}: the previous {out} changed")
        if temporaries(work):
            fail(f"{label}: temporaries left: {temporaries(work)}")
        checked += 1

    # --- oit bench --csv --json --bundle: rows and images come in as it runs ---
    csv, json_path, bundle = (os.path.join(work, name) for name in ("out.csv", "out.json", "bundle"))
    quick = ["--algorithms", "blend", "--sizes", "16", "--frames", "1", "--warmup", "0", "--quiet"]
    subprocess.run([oit, "bench", "--model", model, "--csv", csv, "--json", json_path, "--bundle", bundle] + quick,
                   check=True)
    before = snapshot([csv, json_path, bundle])
    sizes = ",".join(str(n) for n in range(96, 112))
    bench = [oit, "bench", "--model", model, "--algorithms", "blend,ll", "--sizes", sizes, "--frames", "3",
             "--warmup", "0", "--reference-max-pixels", "20000", "--quiet", "--csv", csv, "--json", json_path,
             "--bundle", bundle]
    images = lambda: glob.glob(bundle + ".tmp.*/*.png")
    for number, point in [(signal.SIGTERM, 1), (signal.SIGTERM, 8), (signal.SIGINT, 1), (signal.SIGINT, 8),
                          (signal.SIGHUP, 4)]:
        label = f"bench, {signal.Signals(number).name} after {point} image(s)"
        process = start(bench)
        wait_for(lambda: glob.glob(csv + ".tmp.*") and glob.glob(json_path + ".tmp.*") and len(images()) >= point,
                 process, f"{point} image(s) in the bundle's temporary folder")
        interrupt(process, number, label)
        if snapshot([csv, json_path, bundle]) != before:
            fail(f"{label}: the previous outputs changed")
        if temporaries(work):
            fail(f"{label}: temporaries left: {temporaries(work)}")
        checked += 1

    # --- SIGKILL: nothing runs; the next run of the same output removes the orphans ---
    process = start(render)
    wait_for(writing, process, "the PNG's temporary file")
    process.kill()
    process.wait()
    if not writing():
        fail("SIGKILL during the PNG write: expected its temporary to be left (nothing can run)")
    subprocess.run([oit, "render", "--model", model, "--algorithm", "blend", "--size", "16x16", "--out", out],
                   check=True, stdout=subprocess.DEVNULL)
    if temporaries(work):
        fail(f"the next render of {out} did not remove the killed run's temporary: {temporaries(work)}")
    # a run still going keeps its temporaries while another run of the same outputs starts and ends
    slow = start(bench)
    wait_for(lambda: glob.glob(csv + ".tmp.*") and len(images()) >= 1, slow, "the slow run's temporaries")
    live = [name for name in os.listdir(work) if ".tmp." in name]  # (not the PNGs inside: they come and go)
    subprocess.run([oit, "bench", "--model", model, "--csv", csv, "--json", json_path, "--bundle", bundle] + quick,
                   check=True)
    if not all(os.path.exists(os.path.join(work, t)) for t in live):
        slow.kill()
        fail("a run of the same outputs removed the temporaries of a run still going")
    slow.kill()
    slow.wait()
    if not temporaries(work):
        fail("SIGKILL of a bench: expected its temporaries to be left")
    subprocess.run([oit, "bench", "--model", model, "--csv", csv, "--json", json_path, "--bundle", bundle] + quick,
                   check=True)
    if temporaries(work):
        fail(f"the next bench did not remove the killed run's temporaries: {temporaries(work)}")
    checked += 3
    print(f"interrupted outputs: {checked} interruptions, no temporaries left, previous outputs kept")


if __name__ == "__main__":
    main()
