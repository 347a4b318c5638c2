#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""What the statistics' grain (EMCV_HISTORY_BLOCK = K, docs/renderer.md "Block statistics"), or another tunable
(--tunable NAME=V1,V2,...), costs in quality at equal samples: cv at a budget of B beside burley-B, for K = 1, 2
and 4 (each value), per scene; PSNR of the raw and the resolved display image against the converged reference,
mean over frames FIRST.. (emcv-demo's metrics.json), and the mean samples per SSS pixel. Prints one markdown table
(rows: scene; columns: burley-B and cv at each value, raw / resolved, and cv's loss against the first value).

Usage: /usr/bin/python3 scripts/eval/block_size.py [--build build] [--size 128x128] [--spp-budget 8] [--first 2]
           [--jobs 2] [--method cv] [--tunable EMCV_HISTORY_BLOCK=1,2,4] [--frames N] SCENE...
(SCENE: a built-in name or a scene file; the scene's own length unless --frames.)
"""
import argparse
import concurrent.futures
import os
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from emcv_eval import runner  # noqa: E402

def parse_tunable(text):
    """"NAME=V1,V2,..." -> (NAME, [V1, V2, ...]) (at least two values)."""
    name, _, values = text.partition("=")
    values = [v for v in values.split(",") if v]
    if not name or len(values) < 2:
        sys.exit(f"block_size.py: --tunable needs NAME=V1,V2[,...], got {text!r}")
    return name, values


def run(a, scene, value):
    """One emcv-demo run of `a.method` and burley-B with the tunable at `value`: {method: (raw dB, resolved dB,
    spp)}."""
    with tempfile.TemporaryDirectory() as out:
        extra = ["--no-frames", "--out", out] + (["--frames", str(a.frames)] if a.frames else [])
        cmd = runner.command(runner.tool_path(a.build, "emcv-demo"), scene=scene, size=a.size,
                             methods=[a.method, f"burley-{a.spp_budget:g}"], budget=f"{a.spp_budget:g}",
                             defines=[f"{a.name}={value}"], extra=extra)
        runner.run(cmd, "block_size.py")
        rows = runner.metrics_json(out)
    per = {}
    for r in rows:
        if r["frame"] >= a.first and r["method"] != "reference":
            per.setdefault(r["method"], []).append((r["psnr_db"], r["psnr_resolved_db"], r["mean_spp"]))
    # A frame with no error (an image equal to the reference's: no SSS pixel on screen) has no PSNR (null).
    return {m: tuple(statistics.fmean(x) if (x := [v[i] for v in vals if v[i] is not None]) else float("nan")
                     for i in range(3)) for m, vals in per.items()}


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scenes", nargs="+")
    p.add_argument("--build", default="build")
    p.add_argument("--size", default="128x128")
    p.add_argument("--spp-budget", type=float, default=8.0)
    p.add_argument("--first", type=int, default=2)
    p.add_argument("--jobs", type=int, default=2)
    p.add_argument("--method", default="cv")
    p.add_argument("--tunable", default="EMCV_HISTORY_BLOCK=1,2,4")
    p.add_argument("--frames", type=int, default=None)
    a = p.parse_args(argv)
    a.name, values = parse_tunable(a.tunable)
    label = {"EMCV_HISTORY_BLOCK": "K", "EMCV_HISTORY_UPDATE_PERIOD": "M"}.get(a.name, a.name)
    if not os.path.isfile(runner.tool_path(a.build, "emcv-demo")):
        sys.exit(f"block_size.py: no emcv-demo under {a.build}/bin")
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        futures = {(s, k): pool.submit(run, a, s, k) for s in a.scenes for k in values}
        results = {key: f.result() for key, f in futures.items()}
    base = f"burley-{a.spp_budget:g}"
    last = f"frame {a.frames - 1}" if a.frames else "the scene's last"
    print(f"{a.method} at a budget of {a.spp_budget:g} beside {base}, {a.size}, frames {a.first} to {last}, "
          f"PSNR dB raw / resolved (mean over frames); loss = {label} = {values[0]}'s PSNR minus {label}'s\n")
    head = (f"| scene | {base} | " + " | ".join(f"{label} = {k}" for k in values) + " | " +
            " | ".join(f"loss {label} = {k}" for k in values[1:]) + f" | spp ({label} = {', '.join(values)}) |")
    print(head)
    print("|" + "---|" * (head.count("|") - 1))
    first = values[0]
    for s in a.scenes:
        r = {k: results[(s, k)] for k in values}
        b = r[first][base]
        cells = [f"{r[k][a.method][0]:.2f} / {r[k][a.method][1]:.2f}" for k in values]
        loss = [f"{r[first][a.method][0] - r[k][a.method][0]:+.2f} / {r[first][a.method][1] - r[k][a.method][1]:+.2f}"
                for k in values[1:]]
        spp = ", ".join(f"{r[k][a.method][2]:.2f}" for k in values)
        print(f"| {os.path.splitext(os.path.basename(s))[0]} | {b[0]:.2f} / {b[1]:.2f} | " + " | ".join(cells) + " | "
              + " | ".join(loss) + f" | {spp} |")


if __name__ == "__main__":
    main()
