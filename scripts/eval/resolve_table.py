#!/usr/bin/env python3
"""The temporal resolve's effect per method, raw against resolved (docs/frame.md, "Temporal resolve"; the
tables as made at commit 326c448 and their reading: docs/notebook/2026-12-07-frame-resolve-effect.md).

Renders each scene with emcv-demo (--resolve taa, the adaptive methods under --spp-budget B) and prints one
markdown table per scene from its metrics.csv:
  - PSNR (whole frame) of the raw and of the resolved image, mean over frames: "before", frames 20 .. C - 1 for
    the scene's first light change at C (every frame from 20 on when it has none; frames 0-19 are the resolve's
    own warm-up from the raw first frame, 0.9^20 = 12% of it left), and "after", the 30 frames from C;
  - lag: after the change, the frames until the resolved PSNR first comes within 1 dB of its settled value (the
    mean over frames change+20 .. change+29) and stays there for the rest of that window; "-" without a change.

    /usr/bin/python3 scripts/eval/resolve_table.py [--build build] [--size 96x96] [--budget 8]
                                                   [--scenes static,light-off] [--methods M,...]
                                                   [--define NAME=VALUE ...]
"""
import argparse
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import runner  # noqa: E402

WINDOW = 30        # frames after a change the comparison covers (the summary's window)
SETTLED_FROM = 20  # the settled value is the mean over frames change+20 .. change+29; the warm-up at the start
LAG_DB = 1.0


def mean(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    return sum(values) / len(values) if values else None


def number(text):
    return float(text) if text not in ("", "inf") else (math.inf if text == "inf" else None)


def lag(psnr_by_frame, change):
    settled = mean([psnr_by_frame.get(f) for f in range(change + SETTLED_FROM, change + WINDOW)])
    if settled is None:
        return None
    for k in range(WINDOW):
        if all(psnr_by_frame.get(f) is not None and psnr_by_frame[f] >= settled - LAG_DB
               for f in range(change + k, change + WINDOW)):
            return k
    return WINDOW


def run_scene(build, scene, methods, size, budget, out, defines=()):
    """emcv-demo's rows for `scene` and its first light change (None without one), under `defines` (tunables)."""
    cmd = runner.command(runner.tool_path(build, "emcv-demo"), scene=scene, methods=methods, size=size,
                         budget=budget, defines=defines, extra=["--resolve", "taa", "--no-frames", "--out", out])
    done = runner.run(cmd, "resolve_table")
    # The summary names the first light change in its cv vs burley-B line ("from the first light change at frame
    # C"), which it prints when both ran: the default method list has both.
    change = None
    for line in done.stdout.splitlines():
        marker = "from the first light change at frame "
        if marker in line:
            change = int(line.split(marker)[1].split(")")[0])
    return runner.metrics_csv(out), change


def summary(rows, change, method):
    """One method's (raw before, resolved before, raw after, resolved after, lag): the means over frames
    SETTLED_FROM up to the first light change `change` (every frame from SETTLED_FROM on without one) and over
    the WINDOW frames from it, None where a span is empty; the lag None without a change."""
    frames = sorted({int(r["frame"]) for r in rows})
    before = [f for f in frames if f >= SETTLED_FROM and (change is None or f < change)]
    after = [f for f in frames if change is not None and change <= f < change + WINDOW]
    own = {int(r["frame"]): r for r in rows if r["method"] == method}
    raw = {f: number(own[f]["psnr_db"]) for f in own}
    resolved = {f: number(own[f]["psnr_resolved_db"]) for f in own}
    return (mean([raw.get(f) for f in before]), mean([resolved.get(f) for f in before]),
            mean([raw.get(f) for f in after]), mean([resolved.get(f) for f in after]),
            lag(resolved, change) if change is not None else None)


def table(scene, rows, change, methods):
    lines = ["scene `%s`%s" % (scene, "" if change is None else ", light change at frame %d" % change), "",
             "| method | raw PSNR before | resolved before | gain | raw after | resolved after | gain | lag (frames) |",
             "|---|---|---|---|---|---|---|---|"]
    for m in methods:
        raw_before, resolved_before, raw_after, resolved_after, k = summary(rows, change, m)
        cells = []
        for a, b in ((raw_before, resolved_before), (raw_after, resolved_after)):
            cells += ["-" if a is None else "%.2f" % a, "-" if b is None else "%.2f" % b,
                      "-" if a is None or b is None else "%+.2f" % (b - a)]
        lines.append("| %s | %s | %s |" % (m, " | ".join(cells), "-" if k is None else str(k)))
    return "\n".join(lines)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default="build")
    p.add_argument("--size", default="96x96")
    p.add_argument("--budget", type=int, default=8)
    p.add_argument("--scenes", default="static,light-off")
    p.add_argument("--methods", default=None, help="default: diffuse,burley-B,separable-17,spvg,cv,cv-notex")
    p.add_argument("--define", action="append", default=[], metavar="NAME=VALUE",
                   help="a tunable's other value for every run (emcv-demo --define; repeatable)")
    a = p.parse_args(argv)
    methods = (a.methods.split(",") if a.methods else
               ["diffuse", "burley-%d" % a.budget, "separable-17", "spvg", "cv", "cv-notex"])
    with tempfile.TemporaryDirectory() as tmp:
        for scene in a.scenes.split(","):
            rows, change = run_scene(a.build, scene, methods, a.size, a.budget, os.path.join(tmp, scene), a.define)
            print(table(scene, rows, change, methods))
            print()


if __name__ == "__main__":
    main()
