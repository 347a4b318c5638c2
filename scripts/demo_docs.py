#!/usr/bin/python3
"""Regenerates the measured parts of docs/demo.md and the scene images under docs/images/ by running emcv-demo.

Usage (from the repository root, after building emcv-demo):
    /usr/bin/python3 scripts/demo_docs.py [--demo build/bin/emcv-demo] [--only summary,no-sss,passes,images]

Each part runs emcv-demo once (the exact command is written next to its table) and replaces the text between
<!-- BEGIN GENERATED: name --> and <!-- END GENERATED: name --> in docs/demo.md. docs/demo.md and the images
are written only after every requested part succeeded (each through a temporary name and a rename).
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "demo.md")
IMAGES = os.path.join(ROOT, "docs", "images")
PARTS = ["passes", "summary", "no-sss", "images"]

SUMMARY_ARGS = ["--scene", "light-off", "--method", "all,burley-8", "--spp-budget", "8", "--size", "256x256"]
NO_SSS_ARGS = ["--scene", "no-sss", "--method", "diffuse,burley-16,separable-17", "--size", "256x256",
               "--frames", "120"]
# The same comparison on a scene whose SSS object is visible: what the SSS passes cost when they do run.
STATIC_ARGS = ["--scene", "static", "--method", "diffuse,burley-16,separable-17", "--size", "256x256",
               "--frames", "60"]
IMAGE_SIZE = "192x192"
IMAGE_FRAME = {"flicker": 8}  # a frame that shows what the scene is about (a muzzle flash); others: frame 0


def shown(cmd):
    return " ".join(["build/bin/emcv-demo" if i == 0 else a for i, a in enumerate(cmd)])


def run(demo, args, out_dir=None):
    cmd = [demo] + args + (["--out", out_dir] if out_dir else [])
    start = time.monotonic()
    p = subprocess.run(cmd, capture_output=True, text=True, check=False)
    wall = time.monotonic() - start
    if p.returncode != 0:
        sys.exit(f"demo_docs.py: {' '.join(cmd)} failed with status {p.returncode}:\n{p.stderr}")
    return p.stdout, wall, shown([demo] + args + (["--out", "DIR"] if out_dir else []))


def read_rows(out_dir):
    with open(os.path.join(out_dir, "metrics.csv"), newline="") as f:
        return list(csv.DictReader(f))


def part_passes(demo, tmp):
    blocks = []
    for scene in ["light-off", "no-sss"]:
        out, _, cmd = run(demo, ["--scene", scene, "--method", "diffuse,burley-16,separable-17", "--print-passes"])
        blocks.append(f"`{cmd}`\n\n```text\n{out.rstrip()}\n```")
    return "\n\n".join(blocks)


def part_summary(demo, tmp):
    out_dir = os.path.join(tmp, "summary")
    out, wall, cmd = run(demo, SUMMARY_ARGS, out_dir)
    out = "\n".join(line for line in out.splitlines() if not line.startswith("wrote "))  # a temporary path
    return (f"`{cmd}` (wall clock {wall:.0f} s for the run itself, on the machine described above)\n\n"
            f"```text\n{out.rstrip()}\n```")


def frame_times(rows, methods):
    """(median, minimum) of frame_ms per method over frames 1.. (frame 0 is warm-up)."""
    out = {}
    for m in methods:
        values = [float(r["frame_ms"]) for r in rows if r["method"] == m and int(r["frame"]) >= 1]
        out[m] = (statistics.median(values), min(values))
    return out


def load_average():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


def part_no_sss(demo, tmp):
    methods = ["diffuse", "burley-16", "separable-17"]
    lines = ["| scene | method | SSS passes recorded | median frame_ms | ratio to diffuse | min frame_ms | "
             "ratio to diffuse |", "|---|---|---|---|---|---|---|"]
    commands = []
    loads = [load_average()]
    for args in (NO_SSS_ARGS, STATIC_ARGS):
        scene = args[1]
        out_dir = os.path.join(tmp, "bench-" + scene)
        _, _, cmd = run(demo, args, out_dir)
        loads.append(load_average())
        commands.append(cmd)
        rows = read_rows(out_dir)
        t = frame_times(rows, methods)
        for m in methods:
            sss = any(float(r["sss_ms"]) > 0 for r in rows if r["method"] == m)
            lines.append(f"| {scene} | {m} | {'yes' if sss else 'no'} | {t[m][0]:.2f} | "
                         f"{t[m][0] / t['diffuse'][0]:.3f} | {t[m][1]:.2f} | {t[m][1] / t['diffuse'][1]:.3f} |")
    return ("Commands (one run per scene, the methods side by side in it, frame by frame):\n\n" +
            "\n".join(f"- `{c}`" for c in commands) + "\n\n" + "\n".join(lines) +
            f"\n\n1-minute load average before, between and after the runs: {', '.join(loads)} (2 cores).")


def part_images(demo, tmp):
    names = [line.split()[0] for line in run(demo, ["--list-scenes"])[0].splitlines() if line.strip()]
    made = []
    for name in names:
        frame = IMAGE_FRAME.get(name, 0)
        out_dir = os.path.join(tmp, "image-" + name)
        _, _, cmd = run(demo, ["--scene", name, "--method", "reference", "--size", IMAGE_SIZE,
                               "--frames", str(frame + 1)], out_dir)
        made.append((name, frame, os.path.join(out_dir, "reference", f"frame-{frame:04d}.png"), cmd))
    table = ["| scene | image (reference method, frame shown) |", "|---|---|"]
    for name, frame, _, _ in made:
        table.append(f"| `{name}` | ![{name}](images/scene-{name}.png) frame {frame} |")
    commands = "\n".join(f"- `{cmd}` (frame {frame})" for name, frame, _, cmd in made)
    text = ("Made by `/usr/bin/python3 scripts/demo_docs.py --only images`, which runs:\n\n" + commands + "\n\n" +
            "\n".join(table))
    return text, made


def replace_block(doc, name, body):
    begin, end = f"<!-- BEGIN GENERATED: {name} -->", f"<!-- END GENERATED: {name} -->"
    i, j = doc.find(begin), doc.find(end)
    if i < 0 or j < i:
        sys.exit(f"demo_docs.py: docs/demo.md has no {begin} ... {end} block")
    return doc[: i + len(begin)] + "\n" + body + "\n" + doc[j:]


def write_atomically(path, data, mode="w"):
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), prefix=".tmp-")
    with os.fdopen(fd, mode) as f:
        f.write(data)
    os.chmod(tmp, 0o644)  # mkstemp makes it 0600
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--demo", default=os.path.join(ROOT, "build", "bin", "emcv-demo"))
    ap.add_argument("--only", default=",".join(PARTS), help="comma list of " + ", ".join(PARTS))
    a = ap.parse_args()
    parts = [p for p in a.only.split(",") if p]
    for p in parts:
        if p not in PARTS:
            sys.exit(f"demo_docs.py: --only: unknown part '{p}' (expected {', '.join(PARTS)})")
    if not (os.path.isfile(a.demo) and os.access(a.demo, os.X_OK)):
        sys.exit(f"demo_docs.py: no executable emcv-demo at {a.demo} (build the emcv-demo target first)")
    images = []
    bodies = {}
    with tempfile.TemporaryDirectory(prefix="emcv-demo-docs-") as tmp:
        for p in parts:
            if p == "images":
                bodies[p], images = part_images(a.demo, tmp)
            else:
                bodies[p] = {"passes": part_passes, "summary": part_summary, "no-sss": part_no_sss}[p](a.demo, tmp)
        # Read the page only now: the runs take minutes and other sections may have been edited meanwhile.
        with open(DOC) as f:
            doc = f.read()
        for p, body in bodies.items():
            doc = replace_block(doc, p, body)
        os.makedirs(IMAGES, exist_ok=True)
        for name, _, png, _ in images:
            with open(png, "rb") as f:
                write_atomically(os.path.join(IMAGES, f"scene-{name}.png"), f.read(), "wb")
    write_atomically(DOC, doc)
    print(f"demo_docs.py: updated {', '.join(parts)} in docs/demo.md")


if __name__ == "__main__":
    main()
