#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""How good each adaptive method's sample allocation is after a light change, against each pixel's true noise
(docs/renderer.md, "cv-notex and the change test").

After the scene's last light change its lighting is still, so the frames after it of `burley-1` (one sample a
pixel, a new sample rotation each frame) over several seeds are independent one-sample estimates: sigma_i, the
per-pixel standard deviation of the display luminance over them (scripts/eval/oracle.py's pixel_sigmas, over the
renderer's SSS mask), is the per-sample noise the allocation should follow. `emcv-eval --heatmaps` gives the
counts N_i each method spent at given frames under `--spp-budget B`. Under an error falling as 1 / N, a pixel's
squared error is sigma_i^2 / N_i, so each method's allocation scores mean(sigma^2) / mean(N) over
mean(sigma^2 / N) against the even split of the same mean count, in dB (negative: worse than even), beside the
correlation of N with sigma and the oracle's gain at B (oracle.allocation_gain: N proportional to sigma with a
floor of 1 and a cap of 64). Pixels that took no samples are left out of both. `--plain-notex` runs the counts
with cv-notex's plain push instead of its change test (notex_change.py's variant, read through EMCV_SHADER_DIR).

Usage: /usr/bin/python3 scripts/eval/allocation_check.py --scene FILE|NAME --after F [--size 128x128]
         [--frames 60] [--seeds 1,2,3,4,5] [--budget 8] [--at 31,33,40,50,59] [--methods spvg,cv,cv-notex] [--plain-notex]
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

import oracle
from adaptive_overhead import make_variant
from notex_change import PLAIN_PUSH

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run(cmd, env=None):
    done = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"allocation_check.py: {' '.join(cmd)} failed:\n{done.stderr}")


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True)
    p.add_argument("--after", type=int, required=True, help="the frame from which the lights hold still")
    p.add_argument("--size", default="128x128")
    p.add_argument("--frames", type=int, default=60)
    p.add_argument("--seeds", default="1,2,3,4,5")
    p.add_argument("--budget", type=int, default=8)
    p.add_argument("--at", default="31,33,40,50,59", help="frames whose counts are judged")
    p.add_argument("--methods", default="spvg,cv,cv-notex")
    p.add_argument("--build", default=os.path.join(ROOT, "build"))
    p.add_argument("--plain-notex", action="store_true", help="cv-notex without its change test")
    a = p.parse_args(argv)
    demo, evaluator = (os.path.join(a.build, "bin", n) for n in ("emcv-demo", "emcv-eval"))
    methods = a.methods.split(",")
    with tempfile.TemporaryDirectory() as tmp:
        luminance = []
        for seed in a.seeds.split(","):
            out = os.path.join(tmp, f"seed-{seed}")
            run([demo, "--scene", a.scene, "--method", oracle.METHOD, "--size", a.size, "--frames", str(a.frames),
                 "--seed", seed, "--resolve", "none", "--out", out])
            reference = oracle.read_frames(os.path.join(out, "reference"), a.frames)[a.after:]
            if any(not np.array_equal(r, reference[0]) for r in reference):
                sys.exit(f"allocation_check.py: the reference changes after frame {a.after}: pass a later --after")
            luminance.append(oracle.read_frames(os.path.join(out, oracle.METHOD), a.frames)[a.after:])
        luminance = np.concatenate(luminance)
        counts = os.path.join(tmp, "counts")
        env = dict(os.environ, EMCV_SHADER_DIR=make_variant(os.path.join(tmp, "plain"), PLAIN_PUSH)) if a.plain_notex else None
        run([evaluator, "--scene", a.scene, "--method", a.methods, "--size", a.size, "--frames", str(a.frames),
             "--spp-budget", str(a.budget), "--heatmaps", a.at, "--heatmap-dir", counts], env)
        at = [int(f) for f in a.at.split(",")]
        mask = np.loadtxt(os.path.join(counts, f"{methods[0]}.f{at[0]}.mask.csv"), delimiter=",", ndmin=2) > 0.5
        sigma = oracle.pixel_sigmas(luminance, mask)
        _, _, oracle_gain = oracle.allocation_gain(sigma, float(a.budget), 1.0, 64.0)
        print(f"{a.scene}, {a.size}, budget {a.budget}{', cv-notex with its plain push' if a.plain_notex else ''}: sigma from {luminance.shape[0]} one-sample frames "
              f"(frames {a.after}-{a.frames - 1} x {len(a.seeds.split(','))} seeds) over {int(mask.sum())} SSS pixels; "
              f"the oracle's gain {oracle.db(oracle_gain):+.2f} dB\n")
        print("| frame | " + " | ".join(f"{m}: dB vs even split (corr N, sigma)" for m in methods) + " |")
        print("|---:|" + "---|" * len(methods))
        for f in at:
            cells = []
            for m in methods:
                n = np.loadtxt(os.path.join(counts, f"{m}.f{f}.samples.csv"), delimiter=",", ndmin=2)[mask]
                took = n > 0
                even = np.mean(sigma[took] ** 2) / np.mean(n[took])
                spent = np.mean(sigma[took] ** 2 / n[took])
                cells.append(f"{oracle.db(even / spent):+.2f} ({np.corrcoef(n, sigma)[0, 1]:+.2f})")
            print(f"| {f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
