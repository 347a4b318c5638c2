#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""What the SSS passes cost, method against method, at equal samples (docs/notebook/2026-12-07-results-adaptive-cost.md,
"The SSS passes at equal samples").

Runs emcv-eval (methods side by side, frame by frame) RUNS times for each build directory given, the builds
interleaved run by run so that the machine's load hits them alike, and prints one markdown row per build and
method: the median over runs of the method's mean SSS time over frames FIRST.. (sss_ms, the sum of the sss-*
passes; the mean, because a budget's frames that reuse a plan cost less than the frame that updates:
docs/renderer.md, "Updating one frame in M"), its ratio to the baseline's (the ratio is taken within each run, then
the median over runs), its mean samples per SSS pixel and the ratio of those. Under --spp-budget B the baseline is burley-B; under
--target-variance V it is spvg, and --first/--last pick the window (e.g. the 30 frames after a switch).

With --variant LABEL=NAME=VALUE[,NAME=VALUE...] (repeatable; LABEL= alone for none) the rows are the first build
run with each variant's --define tunables instead, interleaved the same way: a renderer choice that a tunable
switches (EMCV_HISTORY_PLAN_AHEAD) compared with itself in one run.

Usage: /usr/bin/python3 scripts/eval/sss_cost.py [--build DIR]... [--runs 3] [--size 128x128] [--scene light-off]
           [--frames 60] [--first 2] [--last N] [--spp-budget 8 | --target-variance V] [--timing auto|wall|gpu]
           [--methods burley-8,spvg,cv,cv-notex] [--variant LABEL=NAME=VALUE]... [--save-raw DIR]

With --save-raw DIR each run's CSV is kept there (LABEL-runK.csv) beside settings.json, written last, so that a
report made elsewhere (scripts/eval/gpu_report.py, from a GPU machine's runs) recomputes the same table
(load_saved, table).
"""
import argparse
import csv
import io
import json
import os
import re
import statistics
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import runner  # noqa: E402
from emcv_eval.docs import write_atomically  # noqa: E402  (the runs' CSVs, settings.json last)


def parse_variant(text):
    """"LABEL=NAME=VALUE,NAME=VALUE" -> (LABEL, ["NAME=VALUE", ...]); "LABEL=" -> (LABEL, [])."""
    label, sep, defines = text.partition("=")
    if not label or not sep:
        sys.exit(f"sss_cost.py: --variant needs LABEL=[NAME=VALUE,...], got {text!r}")
    return label, [d for d in defines.split(",") if d]


def run_eval(build, a, methods, defines=()):
    """One emcv-eval run: its CSV text."""
    cmd = runner.command(runner.tool_path(build, "emcv-eval"), scene=a.scene, methods=methods, size=a.size,
                         frames=a.frames, defines=defines)
    if a.timing != "auto":  # builds from before --timing took the wall clock, which is auto's on llvmpipe
        cmd += ["--timing", a.timing]
    if a.target_variance is not None:
        cmd += ["--target-variance", a.target_variance]
    else:
        cmd += ["--spp-budget", str(a.spp_budget)]
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def summarise(text, first, last):
    """An emcv-eval CSV -> ({method: (mean SSS ms over frames first..last, mean samples per SSS pixel)}, the
    clock of its times)."""
    rows = list(csv.DictReader(io.StringIO(text)))
    per = {}
    clock = rows[0].get("timing", "wall") if rows else "?"
    for r in rows:
        if first <= int(r["frame"]) <= last:
            per.setdefault(r["method"], []).append((float(r["sss_ms"]), float(r["mean_spp"])))
    return {m: (statistics.fmean(t for t, _ in v), statistics.fmean(n for _, n in v)) for m, v in per.items()}, clock


def table_rows(results, methods, baseline):
    """{label: [one summary per run]} -> [(label, method, median ms, median of the runs' ratios to the baseline,
    mean samples per SSS pixel, its ratio to the baseline's)]: each ratio taken within a run, then the median."""
    rows = []
    for label, runs in results.items():
        for m in methods:
            ms = statistics.median(r[m][0] for r in runs)
            ratio = statistics.median(r[m][0] / r[baseline][0] for r in runs)
            spp = statistics.fmean(r[m][1] for r in runs)
            spp_ratio = spp / statistics.fmean(r[baseline][1] for r in runs)
            rows.append((label, m, ms, ratio, spp, spp_ratio))
    return rows


def table(setting, results, methods, baseline, label_column):
    """The markdown this script prints: a heading line (setting, runs, clocks) and one row per label and method."""
    lines = [setting, "",
             f"| {label_column} | method | SSS ms (mean) | / {baseline} | samples per SSS pixel | / {baseline} |",
             "|---|---|---|---|---|---|"]
    lines += [f"| {b} | {m} | {ms:.3f} | {ratio:.2f} | {spp:.2f} | {spp_ratio:.2f} |"
              for b, m, ms, ratio, spp, spp_ratio in table_rows(results, methods, baseline)]
    return "\n".join(lines)


def raw_name(label, run):
    return re.sub(r"[^A-Za-z0-9._-]+", "_", label).strip("_") + f"-run{run}.csv"


def load_saved(raw_dir):
    """What --save-raw wrote, read back: (settings, {label: [one summary per run]}, clocks), the summaries over
    the window that run used."""
    with open(os.path.join(raw_dir, SETTINGS)) as f:
        settings = json.load(f)
    results, clocks = {}, set()
    for label in settings["labels"]:
        results[label] = []
        for run in range(1, settings["runs"] + 1):
            with open(os.path.join(raw_dir, raw_name(label, run))) as f:
                summary, clock = summarise(f.read(), settings["first"], settings["last"])
            results[label].append(summary)
            clocks.add(clock)
    return settings, results, clocks


SETTINGS = "settings.json"


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build", action="append", default=None)
    p.add_argument("--runs", type=int, default=3)
    p.add_argument("--size", default="128x128")
    p.add_argument("--scene", default="light-off")
    p.add_argument("--frames", type=int, default=60)
    p.add_argument("--first", type=int, default=2)
    p.add_argument("--last", type=int, default=None)
    p.add_argument("--spp-budget", type=int, default=8)
    p.add_argument("--target-variance", default=None)
    p.add_argument("--timing", default="auto")
    p.add_argument("--methods", default=None)
    p.add_argument("--variant", action="append", default=None)
    p.add_argument("--save-raw", default=None, metavar="DIR",
                   help="also write each run's emcv-eval CSV and the settings to DIR (load_saved reads them back)")
    a = p.parse_args(argv)
    builds = a.build or ["build"]
    # Each row set: (label, build, defines): the builds as they are, or the first build under each variant.
    runs = [(b, b, []) for b in builds]
    if a.variant:
        runs = [(label, builds[0], defines) for label, defines in map(parse_variant, a.variant)]
    if a.runs < 1:
        sys.exit("sss_cost.py: --runs must be at least 1")
    baseline = "spvg" if a.target_variance is not None else f"burley-{a.spp_budget}"
    methods = a.methods.split(",") if a.methods else [baseline] + [m for m in ("spvg", "cv", "cv-notex") if m != baseline]
    if baseline not in methods:
        methods = [baseline] + methods
    last = a.last if a.last is not None else a.frames - 1
    if a.save_raw:
        os.makedirs(a.save_raw, exist_ok=True)
    results = {label: [] for label, _, _ in runs}
    clocks = set()
    for run in range(1, a.runs + 1):
        for label, b, defines in runs:  # interleaved: run r of every build (variant) before run r + 1 of any
            text = run_eval(b, a, methods, defines)
            if a.save_raw:
                write_atomically(os.path.join(a.save_raw, raw_name(label, run)), text)
            summary, clock = summarise(text, a.first, last)
            results[label].append(summary)
            clocks.add(clock)
    mode = f"target variance {a.target_variance}" if a.target_variance is not None else f"budget {a.spp_budget} spp"
    setting = f"{a.scene}, {a.size}, {mode}, frames {a.first}-{last}, {a.runs} runs, clock {'/'.join(sorted(clocks))}"
    if a.save_raw:  # last: a folder with its settings holds every run they name
        write_atomically(os.path.join(a.save_raw, SETTINGS), json.dumps(
            {"setting": setting, "scene": a.scene, "size": a.size, "mode": mode, "first": a.first, "last": last, "runs": a.runs,
             "labels": list(results), "methods": methods, "baseline": baseline,
             "label_column": "variant" if a.variant else "build"}, indent=1) + "\n")
    print(table(setting, results, methods, baseline, "variant" if a.variant else "build"))


if __name__ == "__main__":
    main()
