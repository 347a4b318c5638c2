#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""cv-notex with and without the change test (docs/renderer.md, "cv-notex and the change test").

cv-notex tracks the moving mean and variance of its residual r = f - G (alpha = 1). A light change moves r
wherever the scattered light differs from the unscattered (a shadow edge the kernel reaches across, a thin part
lit from behind), and a plain push reads that step as noise: sigma^2 jumps by eta N e^2 and forgets it at 1 - eta
a frame, so the budget spends there for many frames. As built, the push clips a move beyond 5 sigma as cv's
does (include/emcv/port/history.h, emcv_history_push_notex): the frame enters with the weight of a 5-sigma move
and the mean restarts at r. The variant "plain push" is this tree with shaders/adaptive/history_io.h's cv-notex
update replaced by the plain batch push of r (a copy read through EMCV_SHADER_DIR; the script refuses when the
anchor is no longer there), what cv-notex ran up to the commit that added the test.

Every scene with a light change or a moving camera (built-in, variations, validation) at B = 8 and 16, 128x128,
--resolve taa, --spp-budget B: cv-notex as built and with the plain push, spvg and burley-B beside them (these
read nothing of the change). Cells: the raw display image's PSNR against the reference (mean over frames of each
frame's dB, mean over the seeds) over frames 20 to the end ("all") and over the 30 frames from the scene's first
light change ("30 after"); cv-notex's resolved PSNR over all frames.

Usage: /usr/bin/python3 scripts/eval/notex_change.py [--build build] [--seeds 1] [--jobs 2] [--write-doc]
With --write-doc the table replaces the GENERATED block "notex-change" of docs/renderer.md.
"""
import csv
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

from adaptive_overhead import make_variant, variant_study_arguments
from run_eval import publish_table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SIZE = "128x128"
BUDGETS = (8, 16)
FIRST = 20  # frames 0-19 are the resolve's warm-up (docs/results.md, "Conventions")
PLAIN_PUSH = [("adaptive/history_io.h", "    emcv_history_push_notex(s, f, g, EMCV_HISTORY_ETA_MOVING, float(n));\n",
               "    emcv_moving_stats_push_batch(s, emcv_cv_residual(f, 1.0f, g), EMCV_HISTORY_ETA_MOVING, float(n));\n")]
# (scene file under demo/scenes, frames, the first light change or None)
CASES = [
    ("static.json", 60, None), ("light-off.json", 60, 30), ("flicker.json", 72, 8), ("club.json", 60, None),
    ("moving.json", 60, None), ("variations/switch-half.json", 60, 30), ("variations/switch-dim.json", 60, 30),
    ("variations/switch-on.json", 60, 30), ("variations/burst-1.json", 60, 30), ("variations/burst-3.json", 60, 30),
    ("variations/fade.json", 60, 21), ("variations/camera-switch.json", 60, 30),
    ("validation/skin-close.json", 60, 30), ("validation/skin-orbit.json", 60, 30),
    ("validation/mixed-off.json", 60, 30),
]


def run(build, shader_dir, scene, frames, budget, seed, methods, out):
    cmd = [os.path.join(build, "bin", "emcv-demo"), "--scene", os.path.join(ROOT, "demo", "scenes", scene), "--size",
           SIZE, "--frames", str(frames), "--method", methods, "--spp-budget", str(budget), "--seed", str(seed),
           "--resolve", "taa", "--no-frames", "--out", out]
    done = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, EMCV_SHADER_DIR=shader_dir))
    if done.returncode != 0:
        sys.exit(f"notex_change.py: {' '.join(cmd)} failed:\n{done.stderr}")
    rows = {}
    with open(os.path.join(out, "metrics.csv")) as f:
        for r in csv.DictReader(l for l in f if not l.startswith("#")):
            rows.setdefault(r["method"], {})[int(r["frame"])] = (float(r["psnr_db"]), float(r["psnr_resolved_db"]))
    return rows


def mean(values):
    return sum(values) / len(values)


def main(argv):
    a = variant_study_arguments(argv, __doc__, "1", "notex-change")
    seeds = a.seeds
    with tempfile.TemporaryDirectory() as tmp:
        built, plain = make_variant(None, []), make_variant(os.path.join(tmp, "plain"), PLAIN_PUSH)
        jobs = [(k, budget, seed, variant) for k in range(len(CASES)) for budget in BUDGETS for seed in seeds
                for variant in ("built", "plain")]

        def one(i):
            k, budget, seed, variant = jobs[i]
            scene, frames, _ = CASES[k]
            methods = f"cv-notex,spvg,burley-{budget}" if variant == "built" else "cv-notex"
            return run(a.build, built if variant == "built" else plain, scene, frames, budget, seed, methods,
                       os.path.join(tmp, f"out{i}"))

        with ThreadPoolExecutor(a.jobs) as pool:
            rows = dict(zip(jobs, pool.map(one, range(len(jobs)))))
    lines = ["| scene | B | window | burley-B raw | spvg raw | cv-notex raw, plain push | as built | change "
             "| cv-notex resolved (all), plain push | as built | change |",
             "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for k, (scene, frames, change) in enumerate(CASES):
        name = os.path.basename(scene).replace(".json", "")
        for budget in BUDGETS:
            windows = [("all", FIRST, frames)] + ([("30 after", change, min(change + 30, frames))] if change else [])
            for window, first, end in windows:
                def psnr(variant, method, which):
                    return mean([mean([rows[(k, budget, s, variant)][method][f][which] for f in range(first, end)])
                                 for s in seeds])
                burley, spvg = psnr("built", f"burley-{budget}", 0), psnr("built", "spvg", 0)
                raw_plain, raw_built = psnr("plain", "cv-notex", 0), psnr("built", "cv-notex", 0)
                if window == "all":
                    res_plain, res_built = psnr("plain", "cv-notex", 1), psnr("built", "cv-notex", 1)
                    resolved = f"{res_plain:.2f} | {res_built:.2f} | {res_built - res_plain:+.2f}"
                else:
                    resolved = "- | - | -"
                lines.append(f"| {name} | {budget} | {window} | {burley:.2f} | {spvg:.2f} | {raw_plain:.2f} | "
                             f"{raw_built:.2f} | {raw_built - raw_plain:+.2f} | {resolved} |")
    publish_table("\n".join(lines), a.write_doc, os.path.join(ROOT, "docs", "renderer.md"), "notex-change",
                  "scripts/eval/notex_change.py", argv)


if __name__ == "__main__":
    main(sys.argv[1:])
