#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""What the SSS passes cost, method against method, at equal samples (docs/accuracy-vs-time.md, "SSS cost at
equal samples").

Runs emcv-eval (methods side by side, frame by frame) RUNS times for each build directory given, the builds
interleaved run by run so that the machine's load hits them alike, and prints one markdown row per build and
method: the median over runs of the method's median SSS time over frames FIRST.. (sss_ms, the sum of the sss-*
passes), its ratio to the baseline's (the ratio is taken within each run, then the median over runs), its mean
samples per SSS pixel and the ratio of those. Under --spp-budget B the baseline is burley-B; under
--target-variance V it is spvg, and --first/--last pick the window (e.g. the 30 frames after a switch).

With --variant LABEL=NAME=VALUE[,NAME=VALUE...] (repeatable; LABEL= alone for none) the rows are the first build
run with each variant's --define tunables instead, interleaved the same way: a renderer choice that a tunable
switches (EMCV_HISTORY_PLAN_AHEAD) compared with itself in one run.

Usage: /usr/bin/python3 scripts/eval/sss_cost.py [--build DIR]... [--runs 3] [--size 128x128] [--scene light-off]
           [--frames 60] [--first 2] [--last N] [--spp-budget 8 | --target-variance V] [--timing auto|wall|gpu]
           [--methods burley-8,spvg,cv,cv-notex] [--variant LABEL=NAME=VALUE]...
"""
import argparse
import csv
import io
import statistics
import subprocess
import sys


def parse_variant(text):
    """"LABEL=NAME=VALUE,NAME=VALUE" -> (LABEL, ["NAME=VALUE", ...]); "LABEL=" -> (LABEL, [])."""
    label, sep, defines = text.partition("=")
    if not label or not sep:
        sys.exit(f"sss_cost.py: --variant needs LABEL=[NAME=VALUE,...], got {text!r}")
    return label, [d for d in defines.split(",") if d]


def run_eval(build, a, methods, defines=()):
    cmd = [f"{build}/bin/emcv-eval", "--scene", a.scene, "--size", a.size, "--frames", str(a.frames),
           "--method", ",".join(methods)]
    for d in defines:
        cmd += ["--define", d]
    if a.timing != "auto":  # builds from before --timing took the wall clock, which is auto's on llvmpipe
        cmd += ["--timing", a.timing]
    if a.target_variance is not None:
        cmd += ["--target-variance", a.target_variance]
    else:
        cmd += ["--spp-budget", str(a.spp_budget)]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    last = a.last if a.last is not None else a.frames - 1
    per = {}
    clock = rows[0].get("timing", "wall") if rows else "?"
    for r in rows:
        if a.first <= int(r["frame"]) <= last:
            per.setdefault(r["method"], []).append((float(r["sss_ms"]), float(r["mean_spp"])))
    return {m: (statistics.median(t for t, _ in v), statistics.fmean(n for _, n in v)) for m, v in per.items()}, clock


def main():
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
    a = p.parse_args()
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
    results = {label: [] for label, _, _ in runs}
    clocks = set()
    for _ in range(a.runs):
        for label, b, defines in runs:  # interleaved: run r of every build (variant) before run r + 1 of any
            r, clock = run_eval(b, a, methods, defines)
            results[label].append(r)
            clocks.add(clock)
    mode = f"target variance {a.target_variance}" if a.target_variance is not None else f"budget {a.spp_budget} spp"
    last = a.last if a.last is not None else a.frames - 1
    print(f"{a.scene}, {a.size}, {mode}, frames {a.first}-{last}, {a.runs} runs, clock {'/'.join(sorted(clocks))}")
    print()
    print(f"| {'variant' if a.variant else 'build'} | method | SSS ms (median) | / " + baseline + " | samples per SSS pixel | / " + baseline + " |")
    print("|---|---|---|---|---|---|")
    for b in results:
        for m in methods:
            ms = statistics.median(r[m][0] for r in results[b])
            ratio = statistics.median(r[m][0] / r[baseline][0] for r in results[b])
            spp = statistics.fmean(r[m][1] for r in results[b])
            spp_ratio = spp / statistics.fmean(r[baseline][1] for r in results[b])
            print(f"| {b} | {m} | {ms:.3f} | {ratio:.2f} | {spp:.2f} | {spp_ratio:.2f} |")


if __name__ == "__main__":
    main()
