#!/usr/bin/python3
"""Regenerates the measured parts of docs/demo.md and the scene images under docs/images/ by running emcv-demo.

Usage (from the repository root, after building emcv-demo):
    /usr/bin/python3 scripts/demo_docs.py [--demo build/bin/emcv-demo] [--only summary,summary-ci,no-sss,passes,images]
    /usr/bin/python3 scripts/demo_docs.py --check passes,summary-ci [--demo ...]

Each part runs emcv-demo once (the exact command is written next to its table) and replaces the text between
<!-- BEGIN GENERATED: name --> and <!-- END GENERATED: name --> in docs/demo.md. docs/demo.md and the images
are written only after every requested part succeeded (each through a temporary name and a rename).

--check regenerates the named parts without writing anything and compares them with docs/demo.md's blocks,
times masked (they are the machine's, not the code's: sss_ms, sss_p95, frame_ms, the SSS pass time ratios and
the run's wall clock); everything else (pass lists, sample counts, PSNR) is deterministic on llvmpipe. Exit
status 0 when the docs agree, 1 with a diff when they do not, 77 when there is no OpenGL display (a skip for
CTest) unless EMCV_REQUIRE_GL=1. The test command runs it for the cheap parts (tests/docs, label docs).
"""
import argparse
import csv
import difflib
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "demo.md")
IMAGES = os.path.join(ROOT, "docs", "images")
PARTS = ["passes", "summary", "summary-ci", "no-sss", "images"]
CHECKABLE = ["passes", "summary", "summary-ci"]  # the parts whose text is deterministic once times are masked

SUMMARY_ARGS = ["--scene", "light-off", "--method", "all,burley-8", "--spp-budget", "8", "--size", "256x256"]
# The main job at the test command's size: what the docs test re-runs in seconds.
SUMMARY_CI_ARGS = ["--scene", "light-off", "--method", "all,burley-8", "--spp-budget", "8", "--size", "64x64"]
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
        if "(no display)" in p.stderr and os.environ.get("EMCV_REQUIRE_GL") != "1":
            print(f"demo_docs.py: skipped, no OpenGL display: {p.stderr.strip()}")
            sys.exit(77)
        sys.exit(f"demo_docs.py: {' '.join(cmd)} failed with status {p.returncode}:\n{p.stderr}")
    return p.stdout, wall, shown([demo] + args + (["--out", "DIR"] if out_dir else []))


def made_at():
    """"made at commit <short hash>" of the checkout that built emcv-demo (the docs are committed after it)."""
    p = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True)
    return f"made at commit {p.stdout.strip()}" if p.returncode == 0 else "made outside a git checkout"


def read_rows(out_dir):
    with open(os.path.join(out_dir, "metrics.csv"), newline="") as f:
        return list(csv.DictReader(f))


def part_passes(demo, tmp):
    blocks = []
    for scene in ["light-off", "no-sss"]:
        out, _, cmd = run(demo, ["--scene", scene, "--method", "diffuse,burley-16,separable-17", "--print-passes"])
        blocks.append(f"`{cmd}` ({made_at()})\n\n```text\n{out.rstrip()}\n```")
    return "\n\n".join(blocks)


def part_summary(demo, tmp):
    out_dir = os.path.join(tmp, "summary")
    out, wall, cmd = run(demo, SUMMARY_ARGS, out_dir)
    out = "\n".join(line for line in out.splitlines() if not line.startswith("wrote "))  # a temporary path
    return (f"`{cmd}` (wall clock {wall:.0f} s for the run itself, on the machine described above; {made_at()})\n\n"
            f"```text\n{out.rstrip()}\n```")


def part_summary_ci(demo, tmp):
    out, _, cmd = run(demo, SUMMARY_CI_ARGS)
    return f"`{cmd}` ({made_at()})\n\n```text\n{out.rstrip()}\n```"


SUMMARY_ROW = re.compile(r"^(\S+\s+\d+)\s+[0-9.]+\s+[0-9.]+\s+[0-9.]+(\s.*)$")


def masked(text):
    """The text with the machine's times replaced by T: the summary rows' sss_ms, sss_p95 and frame_ms, the
    comparison lines' SSS pass time ratios and the run's wall clock."""
    lines = []
    for line in text.splitlines():
        m = SUMMARY_ROW.match(line)
        if m:
            line = m.group(1) + " T T T" + re.sub(r"\s+", " ", m.group(2))
        line = re.sub(r"SSS pass time [0-9.]+x", "SSS pass time Tx", line)
        line = re.sub(r"\(wall clock [0-9]+ s", "(wall clock T s", line)
        line = re.sub(r"made at commit [0-9a-f]+", "made at commit C", line)
        lines.append(line.rstrip())
    return "\n".join(lines).strip() + "\n"


def block_of(doc, name):
    begin, end = f"<!-- BEGIN GENERATED: {name} -->", f"<!-- END GENERATED: {name} -->"
    i, j = doc.find(begin), doc.find(end)
    if i < 0 or j < i:
        sys.exit(f"demo_docs.py: docs/demo.md has no {begin} ... {end} block")
    return doc[i + len(begin): j]


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
    return (f"Commands (one run per scene, the methods side by side in it, frame by frame; {made_at()}):\n\n" +
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
    text = (f"Made by `/usr/bin/python3 scripts/demo_docs.py --only images` ({made_at()}), which runs:\n\n" +
            commands + "\n\n" +
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
    ap.add_argument("--check", default=None, help="comma list of " + ", ".join(CHECKABLE) + ": compare, write nothing")
    a = ap.parse_args()
    if not (os.path.isfile(a.demo) and os.access(a.demo, os.X_OK)):
        sys.exit(f"demo_docs.py: no executable emcv-demo at {a.demo} (build the emcv-demo target first)")
    if a.check is not None:
        return check([p for p in a.check.split(",") if p], a.demo)
    parts = [p for p in a.only.split(",") if p]
    for p in parts:
        if p not in PARTS:
            sys.exit(f"demo_docs.py: --only: unknown part '{p}' (expected {', '.join(PARTS)})")
    images = []
    bodies = {}
    with tempfile.TemporaryDirectory(prefix="emcv-demo-docs-") as tmp:
        for p in parts:
            if p == "images":
                bodies[p], images = part_images(a.demo, tmp)
            else:
                bodies[p] = GENERATORS[p](a.demo, tmp)
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


GENERATORS = {"passes": part_passes, "summary": part_summary, "summary-ci": part_summary_ci, "no-sss": part_no_sss}


def check(parts, demo):
    if not parts:
        sys.exit("demo_docs.py: --check: name at least one part")
    for p in parts:
        if p not in CHECKABLE:
            sys.exit(f"demo_docs.py: --check: '{p}' cannot be checked (expected {', '.join(CHECKABLE)})")
    with open(DOC) as f:
        doc = f.read()
    differ = []
    with tempfile.TemporaryDirectory(prefix="emcv-demo-docs-") as tmp:
        for p in parts:
            want, have = masked(GENERATORS[p](demo, tmp)), masked(block_of(doc, p))
            if want != have:
                differ.append(p)
                sys.stdout.writelines(difflib.unified_diff(have.splitlines(True), want.splitlines(True),
                                                           f"docs/demo.md ({p})", f"emcv-demo now ({p})"))
    if differ:
        print(f"demo_docs.py: docs/demo.md disagrees with emcv-demo in: {', '.join(differ)}; regenerate with "
              f"/usr/bin/python3 scripts/demo_docs.py --only {','.join(differ)}")
        return 1
    print(f"demo_docs.py: docs/demo.md agrees with emcv-demo in: {', '.join(parts)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
